// SPDX-License-Identifier: GPL-3.0-or-later
// Smoothieware's G2/G3 around its own Robot::append_arc() (src/modules/robot/Robot.cpp, cut
// from the firmware's source by marlin_executed.sh and included here as
// SMOOTHIEWARE_APPEND_ARC), for marlin_executed.cpp, which calls GcodeSuite::G2_G3() for each
// arc. Around the function stands what it reads of the firmware: a Robot in the XY plane with
// load_config()'s arc settings (mm_per_arc_segment 0, mm_max_arc_error 0.01 mm,
// arc_correction 5), the extruder as its fourth motor (E spread over the segments as the
// other axes beyond XYZ are), PI as Robot.cpp defines it (a float), and a kernel never
// halted. As Robot::compute_arc() does, the radius is hypotf() of the centre's offsets; each
// segment append_arc() hands append_milestone() goes to planned_line(). Built with
// marlin_shim.hpp (-include), whose types marlin_executed.cpp uses.
#include <cmath>
#include <cstring>
#include <string>

#define PI 3.14159265358979323846F
#define MAX_ROBOT_ACTUATORS 4
constexpr int A_AXIS = 3;

struct Gcode {
  bool is_error = false;
  std::string txt_after_ok;
};
struct Kernel {
  bool is_halted() const { return false; }
};
Kernel kernel;
#define THEKERNEL (&kernel)

struct Robot {
  float feed_rate = 0;  // mm/min
  float seconds_per_minute = 60;
  float machine_position[MAX_ROBOT_ACTUATORS] = {};
  uint8_t plane_axis_0 = X_AXIS, plane_axis_1 = Y_AXIS, plane_axis_2 = Z_AXIS;
  float mm_per_arc_segment = 0.0f, mm_max_arc_error = 0.01f;
  int arc_correction = 5;
  uint8_t n_motors = MAX_ROBOT_ACTUATORS;
  bool append_arc(Gcode* gcode, const float target[], const float offset[], float radius, bool is_clockwise);
  bool append_milestone(const float target[], float) {
    planned_line(xyze_pos_t{target[0], target[1], target[2], target[3]});
    return true;
  }
};

#include SMOOTHIEWARE_APPEND_ARC

void GcodeSuite::G2_G3(const bool clockwise) {
  get_destination_from_command();
  Robot robot;
  robot.feed_rate = feedrate_mm_s * 60;
  for (int a = 0; a < 4; ++a) robot.machine_position[a] = current_position[a];
  const float offset[MAX_ROBOT_ACTUATORS] = {parser.seen['I' - 'A'] ? parser.value['I' - 'A'] : 0.f,
                                             parser.seen['J' - 'A'] ? parser.value['J' - 'A'] : 0.f, 0.f, 0.f};
  const float target[MAX_ROBOT_ACTUATORS] = {destination.x, destination.y, destination.z, destination.e};
  Gcode gcode;
  robot.append_arc(&gcode, target, offset, hypotf(offset[0], offset[1]), clockwise);
  if (gcode.is_error) marlin_error(gcode.txt_after_ok.c_str());
  current_position = destination;
}
