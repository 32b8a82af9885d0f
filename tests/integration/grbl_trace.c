/* SPDX-License-Identifier: GPL-3.0-or-later
 * Linked with grbl-sim's validator (Grbl 1.1's own parser and motion control) and
 * -Wl,--wrap=plan_buffer_line: every line Grbl plans, the moves mc_arc() cuts each arc into
 * among them, is printed to standard error as a G-code block in millimetres, so that
 * `arcpress diff` can measure the path Grbl moves along (grbl_accepts.sh). */
#include "../grbl.h"
#include <stdio.h>

uint8_t __real_plan_buffer_line(float *target, plan_line_data_t *pl_data);

uint8_t __wrap_plan_buffer_line(float *target, plan_line_data_t *pl_data) {
  if (pl_data->condition & PL_COND_FLAG_RAPID_MOTION)
    fprintf(stderr, "G0 X%.6f Y%.6f Z%.6f\n", target[0], target[1], target[2]);
  else
    fprintf(stderr, "G1 X%.6f Y%.6f Z%.6f F%.4f\n", target[0], target[1], target[2], pl_data->feed_rate);
  uint8_t status = __real_plan_buffer_line(target, pl_data);
  plan_reset_buffer(); /* nothing runs the blocks: room for the next */
  return status;
}

/* The validator does not load Grbl's settings; its defaults ($12 = 0.002 mm arc tolerance). */
__attribute__((constructor)) static void grbl_trace_settings(void) { settings_restore(SETTINGS_RESTORE_DEFAULTS); }
