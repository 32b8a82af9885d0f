// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Emission stage: the program text again, with each run replaced by its primitives.
// Blocks outside runs, and single-move lines the fitter kept, are copied byte for byte;
// new blocks copy the look of the blocks they replace (case, spacing, G1 vs G01, the
// input's own number text for every coordinate that comes from the input).
#include <optional>
#include <string>
#include <vector>

#include "arcpress/dialect/dialect.hpp"
#include "arcpress/emit/output_habits.hpp"
#include "arcpress/extract/run.hpp"
#include "arcpress/fit/primitive.hpp"
#include "arcpress/lex/block.hpp"

namespace arcpress {

struct EmitStats {
  size_t runs = 0;
  size_t moves_in = 0;    ///< G1 moves inside runs
  size_t lines_out = 0;   ///< G1 blocks written for runs (copied or new)
  size_t arcs_out = 0;    ///< G2/G3 blocks written
  size_t motion_words_added = 0;  ///< copied blocks that needed their motion word restated
  /// G17/G18/G19 blocks written around runs fitted in another plane than the program's.
  size_t plane_words_added = 0;
  /// Blocks that state the program's centre again (Dialect::centre_modal) after arcs arcpress
  /// wrote moved it, before a block of the program's that turns about it.
  size_t poles_restated = 0;
  size_t turns_spelled = 0;  ///< codes that turn as the last arc did, written as the program's way (Dialect::last_turn)
  /// Fitted arcs written as their input lines instead: after rounding to the printed digits
  /// they broke the band, the controller's radius rule, its sweep limits or its line length.
  size_t arcs_unprintable = 0;
  size_t long_lines_kept = 0;    ///< fitted lines kept as input lines: too long for the dialect
  /// Joints the dialect's rules may break: beside arcs whose end tangents its digits could
  /// not keep within the slack (no centre on the printed grid did), and beside fitted
  /// primitives written back as their input moves (arcs_unprintable, long_lines_kept). The
  /// input moves starting at them, start and end of each such block.
  std::vector<uint32_t> rule_joints;
  /// Per run: the 1-based output lines its blocks take, first and last.
  std::vector<std::pair<uint32_t, uint32_t>> run_lines;
  /// The output's lines written as byte copies of input blocks, in order (reading the
  /// output back takes their words over: lex()).
  std::vector<CopiedLine> copied;
};


/// Whether `w` sets the arc centre mode (G90.1 or G91.1): the dialect's arc header is then
/// not written.
inline bool sets_centre_mode(const Word& w) {
  return w.letter == 'G' && !w.is_expr && (w.code10() == 901 || w.code10() == 911);
}

/// How the output stands before the first block of a program emitted in pieces (a stream):
/// the defaults are a program's start.
struct EmitStart {
  int in_motion = 0;   ///< modal motion (G x10) of the input there
  int out_motion = 0;  ///< ... and of the output; -1: not known (the first block that relies on it states it)
  bool header_done = false;  ///< the dialect's arc header is written, or the program set the centre mode
  /// Where a setting of the controller's decides how I/J/K read (Dialect::start_centres
  /// Machine): whether an earlier piece may have written G90.1 or G91.1 before arcs of its own
  /// (else the setting holds here, as at the program's start).
  bool centres_maybe_said = false;
  /// Where I/J/K set a centre that holds (Dialect::centre_modal): whether an earlier piece may
  /// have written arcs that moved it (the program's is then stated again before it is read).
  bool pole_maybe_moved = false;
  /// Where codes turn as the last programmed arc did (Dialect::last_turn): whether an earlier
  /// piece may have written arcs since the program last set the way (its way is then
  /// spelled out where it is read).
  bool turn_maybe_moved = false;
  std::optional<OutputHabits> habits;  ///< the program's, found in its first piece; absent: this piece's own
};

struct EmitOptions {
  /// The band the fit was made for: every arc is re-checked against it after rounding.
  double band_mm = 0.01;
  Dialect dialect;                           ///< what the controller reads
  ArcFormat format = ArcFormat::Centre;      ///< I/J/K or R (R only where the dialect reads it)
  /// How far rounding the printed centre may turn an arc's tangent at either end, degrees.
  /// The fitter leaves joints at most 0.9 of the G1 angle apart; 0.05 of it per side keeps
  /// the printed joints inside the G1 angle.
  double tangent_slack_deg = 0.025;
  /// Threads that compose the runs' new blocks (0: one per hardware thread). The text is the
  /// same for any number.
  unsigned threads = 1;
  /// The chords the firmware cuts arcs into, where the band is held on them
  /// (CompressOptions::executed_rule()): a printed arc the firmware would cut into another
  /// number of chords than the fitted one has its chords checked against the band again.
  ArcSegmentation executed;
  /// Where at least 0 (FitOptions::extrusion_variance): a printed arc that extrudes keeps each
  /// move it replaces at its E per mm within this share of its own, as the fitted arc did;
  /// rounding the centre changes its length (a 0.0014 mm radius at 3 decimals: by 15 %).
  double extrusion_variance = -1;
  EmitStart start;
};

/// Writes the program with each run replaced by its fit. Every arc is printed, read back
/// from the printed digits as the controller would, and checked (band, end-radius rule,
/// sweep, chord, digits, line length, end tangents); one that fails any check is written as the input's
/// own G1 blocks instead.
std::string emit_program(const Program& program, const Interpretation& in, const std::vector<Run>& runs,
                         const std::vector<FitResult>& fits, const EmitOptions& options = {},
                         EmitStats* stats = nullptr);

}  // namespace arcpress
