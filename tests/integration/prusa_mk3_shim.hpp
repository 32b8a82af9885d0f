// SPDX-License-Identifier: GPL-3.0-or-later
// What Prusa-Firmware's Firmware/motion_control.cpp (mc_arc(), the arc code of the MK3, MK3S
// and MK2.5) needs of the rest of the firmware, so that it builds on a PC (marlin_executed.sh
// puts this header before the file with -include; the Marlin.h, stepper.h and planner.h it
// includes are left empty). The printer's AVR has a 32-bit double: M_PI is a float here too,
// so that `2 * M_PI` and `radius * ((2.0f * M_PI) / cs.min_arc_segments)` are worked out in
// floats as on the printer (hypot(), atan2(), cos() and ceil() take the float overloads). The
// arc settings (M500_conf in ConfigurationStore.h, changed by M214) are the variant's
// defaults, given with -D from Firmware/variants/MK3S.h.
#pragma once

#include <math.h>
#include <stdint.h>
#include <string.h>

#undef M_PI
#define M_PI 3.14159265358979323846f

enum { X_AXIS, Y_AXIS, Z_AXIS, E_AXIS };

struct M500_conf {  // (the fields mc_arc() reads)
  float mm_per_arc_segment;
  float min_mm_per_arc_segment;
  uint8_t n_arc_correction;
  uint16_t min_arc_segments;
  uint16_t arc_segments_per_sec;
};
inline M500_conf cs = {DEFAULT_MM_PER_ARC_SEGMENT, DEFAULT_MIN_MM_PER_ARC_SEGMENT, DEFAULT_N_ARC_CORRECTION,
                       DEFAULT_MIN_ARC_SEGMENTS, DEFAULT_ARC_SEGMENTS_PER_SEC};

void plan_buffer_line(float x, float y, float z, const float& e, float feed_rate,
                      const float* gcode_start_position = nullptr, uint16_t segment_idx = 0);
void clamp_to_software_endstops(float target[3]);
extern bool planner_aborted;
