// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The C++ façade: one call runs the whole pipeline on a program held in memory.
// lex -> interpret -> extract runs -> fit -> emit (-> verify).
#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "arcpress/core/diagnostic.hpp"
#include "arcpress/dialect/dialect.hpp"
#include "arcpress/emit/emitter.hpp"
#include "arcpress/extract/run.hpp"
#include "arcpress/fit/primitive.hpp"
#include "arcpress/verify/block_rate.hpp"
#include "arcpress/verify/path_compare.hpp"
#include "arcpress/verify/program_diff.hpp"

namespace arcpress {

inline constexpr const char* kVersion = "0.1.0";

struct CompressOptions {
  FitOptions fit;
  /// The target controller: how the input is read, what the fit may use (planes, helices,
  /// sweep, radius and length limits, which tighten `fit`'s) and how the output is printed.
  Dialect dialect;
  std::optional<ArcFormat> arc_format;  ///< I/J/K or R; absent: the dialect's own choice
  bool passthrough = false;  ///< lex and write back every block unchanged
  bool strict = false;       ///< any unreadable block is an error
  /// Re-read the output and compare it with the input as `arcpress diff` does (path both
  /// ways, rapids, non-motion blocks, feed, extrusion) before it is used.
  bool verify = true;
  /// Measure the block rate the input and the output demand (CompressResult::rate_in,
  /// rate_out; verify/block_rate.hpp), against the dialect's [throughput] limits.
  bool block_rate = false;
  /// Threads that fit runs at once, at most kMaxThreads; 0: one per hardware thread. Runs
  /// are independent, so the output is the same for any count.
  unsigned threads = 0;
  /// A comment naming arcpress, its version and these options, written after the program's
  /// first line where that line is a comment (a slicer's own first line, which its viewer
  /// looks for) and not already followed by one; never with `passthrough`. `arcpress diff`
  /// passes over it.
  bool header = true;
  /// Which path the band is held on: the programmed one (the circles as written), or the
  /// one the firmware moves along (each arc cut into the chords of the dialect's rule,
  /// Dialect::executed); Dialect: the latter where the dialect names a rule.
  enum class Band : uint8_t { Dialect, Program, Executed };
  Band band = Band::Dialect;
  /// The arc segmentation the band is held on: the dialect's where `band` asks for the
  /// executed path, else Rule::None.
  ArcSegmentation executed_rule() const {
    return band == Band::Program ? ArcSegmentation{} : dialect.executed;
  }
};

/// The bands' names as --band and arcpress_options_set_band() take them, in the order of
/// CompressOptions::Band ("dialect": the dialect's choice).
inline constexpr std::array<std::string_view, 3> kBandNames{"dialect", "program", "executed"};
/// The band of that name, if any.
inline std::optional<CompressOptions::Band> band_named(std::string_view name) {
  for (size_t i = 0; i < kBandNames.size(); ++i)
    if (kBandNames[i] == name) return static_cast<CompressOptions::Band>(i);
  return std::nullopt;
}

/// G1 moves that were put in no run, for one reason (see left_out_moves()).
struct NotFitted {
  Unfit why = Unfit::None;  ///< Unfit::None: a lone G1 between blocks that are no run
  size_t moves = 0;
  uint32_t first_line = 0;  ///< the first such move's line
  uint32_t cause_line = 0;  ///< unplaced moves: the line that made the position unknown (0: none)
};

struct CompressResult {
  bool ok = false;        ///< false: input errors (see the sink); `output` is then empty
  /// With CompressOptions::block_rate: the block rate the input and the output demand.
  std::optional<BlockRate> rate_in, rate_out;
  std::string output;
  size_t blocks_in = 0;
  size_t bytes_in = 0;
  size_t bytes_out = 0;
  EmitStats stats;
  /// Joints where the fit could not keep the tangent (the band, or the digits, forced a
  /// change): the fitter's account, which also names joints that turned out within the G1
  /// angle as read back, or that the check does not count as smooth.
  size_t forced_kinks = 0;
  /// Where they are: the input line of the move that starts at each, in order.
  std::vector<uint32_t> forced_kink_lines;
  size_t g1_moves = 0;       ///< G1 moves in the input
  size_t runs_fitted = 0;    ///< runs of G1 moves the fitter was given
  /// Runs written as the input's own moves because the check refused their fit (a fitter or
  /// rounding fault on extreme input): the rest of the program is still compressed.
  size_t runs_kept_as_input = 0;
  /// The G1 moves in no run, grouped by reason (empty with `passthrough`).
  std::vector<NotFitted> not_fitted;
  bool verified = false;     ///< `check` and `comparison` hold measurements of the output
  /// The feed moves of input and output that could not be placed, and the arcs too big to
  /// measure, (and so not measured) are the same moves, one for one: written back as they were.
  bool unplaced_kept = false;
  /// The output against the input by diff_programs(), the code of `arcpress diff`: the
  /// verdict on the output and its measured deviation. Where the move-by-move comparison
  /// below covers both paths (PathComparison::covers_path) and keeps the band, the paths'
  /// distance is its (max_deviation_mm and the worst place, on the executed path where the
  /// firmware moves on chords) and diff_programs() compares the rest; elsewhere it measures
  /// the whole paths too.
  ProgramDiff check;
  /// Pieces checked, and those of them whose whole paths were measured (see `check`).
  size_t pieces_checked = 0, pieces_measured_whole = 0;
  /// Move by move: every output move ends on an input vertex, the deviation of each
  /// replaced stretch, and the tangent change at smooth joints (fit statistics).
  PathComparison comparison;
  /// The smooth joints the check found turning by more than the G1 angle
  /// (comparison.kink_lines) that the fit did not report as forced, by input line: a
  /// broken promise wherever it is not empty.
  std::vector<uint32_t> unforced_kink_lines() const {
    std::vector<uint32_t> over = comparison.kink_lines, forced = forced_kink_lines, out;
    std::sort(over.begin(), over.end());
    std::sort(forced.begin(), forced.end());
    std::set_difference(over.begin(), over.end(), forced.begin(), forced.end(), std::back_inserter(out));
    return out;
  }
  /// True when the output may be used: read fine and, when verified, the same program as
  /// the input within the band, move by move and as a whole.
  bool within_band() const {
    return !verified || (check.agrees(band_mm) && (check.compared_all() || unplaced_kept) &&
                         comparison.within(band_mm) && comparison.max_wrong_side_mm <= side_allowance_mm);
  }
  /// With a one-sided band (FitOptions::band_side): how far the input may lie on the wrong
  /// side of the output, in mm: what printing the arcs' centres to their digits may move
  /// them (kBandSideRoundingShare of the band).
  double side_allowance_mm = 0;
  double band_mm = 0;
};

/// The range a floating option must lie in: a finite number from `lo` (above it where
/// `above_lo`) to `hi`, in `unit`. One table for the command line's checks and the library's.
struct OptionRange {
  double lo, hi;
  bool above_lo;
  const char* unit;
  bool holds(double v) const { return std::isfinite(v) && (above_lo ? v > lo : v >= lo) && v <= hi; }
};
inline constexpr OptionRange kToleranceRange{kMinToleranceMm, kMaxToleranceMm, false, "mm"};
inline constexpr OptionRange kG1AngleRange{0, 90, true, "degrees"};
inline constexpr OptionRange kCornerAngleRange{0, 180, false, "degrees"};
inline constexpr OptionRange kMinRadiusRange{0, 1e6, false, "mm"};
inline constexpr OptionRange kMaxRadiusRange{0, 1e6, true, "mm"};
inline constexpr OptionRange kMaxSweepRange{1, 359, false, "degrees"};
inline constexpr OptionRange kMinArcLengthRange{0, 1e4, false, "mm"};
inline constexpr OptionRange kExtrusionVarianceRange{0, 1, false, "(share of the rate)"};

/// The most threads CompressOptions::threads and DiffOptions::threads may ask for.
inline constexpr unsigned kMaxThreads = 1024;

/// Throws Error(kExitInput) unless every number of `o` is finite and in its documented range
/// (the CLI's options table); compress() calls it, so no search is ever asked to run for a
/// band it cannot reach.
void check_options(const FitOptions& o);

/// The fit options for one run: the user's, tightened by what the dialect's controller
/// accepts in that run's frame and plane.
FitOptions fit_options_for(const FitOptions& user, const Dialect& dialect, const Frame& frame, Plane plane);

/// Reads `r.output` back with the dialect and compares it with the input program `input`
/// (interpreted as `in`): fills r.check and r.comparison and sets r.verified. compress()
/// calls it when `opt.verify` is set; a caller that edits the output can call it again.
/// With the `runs` that were fitted, their joints are read in the planes they were fitted
/// in (CompareOptions::fitted_plane).
void verify_output(const Program& input, const Interpretation& in, const CompressOptions& opt, CompressResult& r,
                   std::span<const Run> runs = {});

/// Compresses `text` (the program called `name` in diagnostics). Never throws for bad
/// input: problems go to `sink`, and in strict mode any of them makes `ok` false. With
/// `verify`, the output is read back and compared with the input (see within_band()).
CompressResult compress(const std::string& name, std::string text, const CompressOptions& opt,
                        DiagnosticSink& sink);

}  // namespace arcpress
