// SPDX-License-Identifier: GPL-3.0-or-later
// The MK3's G2/G3 around its own mc_arc() (Prusa-Firmware Firmware/motion_control.cpp, built
// beside this file with prusa_mk3_shim.hpp), for marlin_executed.cpp, which calls
// GcodeSuite::G2_G3() for each arc: as the firmware's `case 2: case 3:` and
// prepare_arc_move() do, the destination is read as G1 reads it, I and J are the centre's
// offsets from the start (0 where absent), the radius is their length in floats, and
// mc_arc() runs from its first segment (no print being recovered); each segment it hands
// the planner goes to planned_line(). Built with marlin_shim.hpp (-include), whose types
// marlin_executed.cpp uses.
#include <cmath>

void mc_arc(const float* position, float* target, const float* offset, float feed_rate, float radius,
            bool isclockwise, uint16_t start_segment_idx);

bool planner_aborted = false;
void clamp_to_software_endstops(float*) {}  // (no endstops here: the program's own positions)
void plan_buffer_line(float x, float y, float z, const float& e, float, const float*, uint16_t) {
  planned_line(xyze_pos_t{x, y, z, e});
}

void GcodeSuite::G2_G3(const bool clockwise) {
  get_destination_from_command();
  const float offset[2] = {parser.seen['I' - 'A'] ? parser.value['I' - 'A'] : 0.f,
                           parser.seen['J' - 'A'] ? parser.value['J' - 'A'] : 0.f};
  const float position[4] = {current_position.x, current_position.y, current_position.z, current_position.e};
  float target[4] = {destination.x, destination.y, destination.z, destination.e};
  mc_arc(position, target, offset, feedrate_mm_s, std::hypot(offset[0], offset[1]), clockwise, 1);
  current_position = destination;
}
