/* SPDX-License-Identifier: GPL-3.0-or-later */
/* arcpress's C library: opaque handles, a status from every call, no exception crosses it and
 * no state is shared between handles (two compressors may run on two threads at once).
 *
 *   arcpress_options *o = arcpress_options_new();
 *   arcpress_options_set_tolerance(o, 0.01);
 *   arcpress_options_set_dialect(o, "marlin");
 *   arcpress_compressor *c = NULL;
 *   if (arcpress_compressor_new(o, "part.gcode", &c) != ARCPRESS_OK) puts(arcpress_options_last_error(o));
 *   arcpress_push(c, bytes, n);                     (as often as bytes come)
 *   arcpress_take(c, &text, &len);                  (finished text so far, final)
 *   status = arcpress_finish(c);                    (ARCPRESS_OK: everything taken may be used)
 *   arcpress_take(c, &text, &len);
 *   arcpress_compressor_free(c); arcpress_options_free(o);
 *
 * Text returned by a call stays valid until the next call on the same handle. */
#ifndef ARCPRESS_H
#define ARCPRESS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum arcpress_status {
  ARCPRESS_OK = 0,
  ARCPRESS_CHECK_FAILED = 1, /* the output failed its check: throw away what was taken */
  ARCPRESS_BAD_INPUT = 2,    /* a usage error or input that cannot be read (see last_error, diagnostics) */
  ARCPRESS_IO_ERROR = 3,     /* a file could not be read or written */
  ARCPRESS_INTERNAL = 4      /* anything else (out of memory): the handle is unusable */
} arcpress_status;

typedef struct arcpress_options arcpress_options;
typedef struct arcpress_compressor arcpress_compressor;

/* Counts and the measured deviation of a compression (valid after arcpress_finish). */
typedef struct arcpress_stats {
  size_t bytes_in, bytes_out;
  size_t blocks_in;
  size_t g1_moves;        /* G1 moves in the input */
  size_t lines_out;       /* G1 blocks written for runs */
  size_t arcs_out;        /* G2/G3 blocks written */
  double max_deviation_mm;
  int verified;           /* 1: the output was read back and measured (only after arcpress_finish) */
} arcpress_stats;

const char* arcpress_version(void);

arcpress_options* arcpress_options_new(void);
void arcpress_options_free(arcpress_options* options);
/* The message of the last failed call on `options` (or on arcpress_compressor_new with it). */
const char* arcpress_options_last_error(const arcpress_options* options);
arcpress_status arcpress_options_set_tolerance(arcpress_options* options, double mm);
arcpress_status arcpress_options_set_g1_angle(arcpress_options* options, double degrees);
arcpress_status arcpress_options_set_corner_angle(arcpress_options* options, double degrees);
/* "arcs" (default), "global", "greedy", "stream", "lowe" or "keep". */
arcpress_status arcpress_options_set_method(arcpress_options* options, const char* method);
/* A shipped dialect by name ("fanuc", "marlin", ...) or a dialect TOML file of one's own. */
arcpress_status arcpress_options_set_dialect(arcpress_options* options, const char* name);
/* ARCPRESS_IO_ERROR where the file cannot be read; ARCPRESS_BAD_INPUT where it is no dialect
 * (an empty file names none). */
arcpress_status arcpress_options_set_dialect_file(arcpress_options* options, const char* path);
/* 0 (one per hardware thread) to 1024; more is ARCPRESS_BAD_INPUT. */
arcpress_status arcpress_options_set_threads(arcpress_options* options, unsigned threads);
arcpress_status arcpress_options_set_verify(arcpress_options* options, int verify);
arcpress_status arcpress_options_set_strict(arcpress_options* options, int strict);
/* Where the band is held: "executed" (on the chords the dialect's firmware cuts each arc
 * into), "program" (on the arcs as written) or "dialect" (the default: executed where the
 * dialect names a firmware rule). */
arcpress_status arcpress_options_set_band(arcpress_options* options, const char* band);
/* Which side of the input path the output may lie on, relative to the direction of travel:
 * "left", "right" or "both" (the default). One side needs the band on the programmed path
 * ("program" above, or a dialect without a firmware rule): arcpress_compressor_new() refuses
 * it on a firmware's chords. */
arcpress_status arcpress_options_set_band_side(arcpress_options* options, const char* side);
/* The units a program is in until its first G20 or G21, as the controller starts: "mm" or
 * "inch". Unset, the dialect's: printer firmwares start in mm; a CNC controller's start is
 * its own setting, read as mm with a warning where a program gives a length before G20 or
 * G21. Kept when a dialect is chosen after it. */
arcpress_status arcpress_options_set_units(arcpress_options* options, const char* units);
/* Share (0 .. 1) by which the E per mm of each move an arc or line replaces may differ from the arc's or line's. */
arcpress_status arcpress_options_set_extrusion_variance(arcpress_options* options, double share);
/* 0: no comment naming arcpress after the program's first line (1, the default: where that
 * line is a comment, as a slicer's is). */
arcpress_status arcpress_options_set_header(arcpress_options* options, int header);

/* `name` names the program in diagnostics. The compressor keeps its own copy of `options`:
 * they may be changed or freed at once. On failure *out is NULL and the message is
 * arcpress_options_last_error(options) (ARCPRESS_BAD_INPUT for the executed band on a
 * dialect that names no firmware rule). */
arcpress_status arcpress_compressor_new(arcpress_options* options, const char* name, arcpress_compressor** out);
void arcpress_compressor_free(arcpress_compressor* compressor);
/* After any call on a compressor fails, every later call on it fails too. Input that is not
 * G-code at all (an archive, an image, binary bytes) is refused: ARCPRESS_BAD_INPUT, with an
 * E-INPUT-NOT-GCODE diagnostic, and nothing is given out. */
arcpress_status arcpress_push(arcpress_compressor* compressor, const char* bytes, size_t length);
/* The program's jumps (GOTO 100, M99 P100, M97 P100: the blocks they name are written as they
 * are, with their numbers), read from its text ahead of arcpress_push(), whole lines from
 * line `first_line` on; call it as often as the text comes, before the first push. Without
 * it, each push's jumps are read before its lines, and a jump back to a block an earlier push
 * held fails the push (ARCPRESS_BAD_INPUT, E-FLOW-JUMP-BACK). Once called, the pushes read no
 * more jumps. The text after the program's end is kept too, for the subprograms there (O2000
 * after M30): the modes each leaves hold after its calls (M98 P2000); without it, every mode
 * after a call is unknown until the program states it. */
arcpress_status arcpress_read_jumps(arcpress_compressor* compressor, const char* bytes, size_t length,
                                    unsigned first_line);
/* After arcpress_read_jumps() of the whole program: the whole program once more, read ahead
 * for its loops (GOTO, M99 P; WHILE [..] DO1 .. END1, o1 do .. o1 while, RepRapFirmware's
 * while) whose end would run their first moves in another plane, units, motion or G90/G91
 * than they were read in. Their moves are then written as they are (a
 * W-FLOW-LOOP-MODES warning); without it, such a loop fails the push that brings its jump
 * (ARCPRESS_BAD_INPUT, E-FLOW-LOOP-MODES). Does nothing where the program has neither jump nor loop. */
arcpress_status arcpress_read_loops(arcpress_compressor* compressor, const char* bytes, size_t length);
/* The output finished since the last take, in order; *text is not NUL-terminated. */
arcpress_status arcpress_take(arcpress_compressor* compressor, const char** text, size_t* length);
/* Ends the input. ARCPRESS_OK: all output may be used; ARCPRESS_BAD_INPUT or
 * ARCPRESS_CHECK_FAILED: none of it. */
arcpress_status arcpress_finish(arcpress_compressor* compressor);
arcpress_status arcpress_get_stats(const arcpress_compressor* compressor, arcpress_stats* stats);
/* "file:line:col: warning: CODE: message" lines for the input's problems (may be ""). */
const char* arcpress_diagnostics(arcpress_compressor* compressor);
const char* arcpress_last_error(const arcpress_compressor* compressor);

#ifdef __cplusplus
}
#endif

#endif /* ARCPRESS_H */
