// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Verification stage: reads two interpreted programs and measures how far the second's
// path is from the first's. The output of arcpress ends every move on a vertex of the input
// path, so the two move lists are walked together: each output move is matched with the
// stretch of input moves that ends at the same point, and the two-sided distance between
// them is measured exactly (core/deviation). A move that does not end on the input path is
// a mismatch and fails the check.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "arcpress/core/deviation.hpp"
#include "arcpress/dialect/arc_segmentation.hpp"
#include "arcpress/lex/block.hpp"
#include "arcpress/model/move.hpp"

namespace arcpress {

struct CompareOptions {
  double tolerance_mm = 0.01;       ///< band the output path must stay in
  double g1_angle_deg = 0.5;        ///< tangent change allowed at smooth joints
  double corner_angle_deg = 30.0;   ///< input turns sharper than this are corners
  /// Where given, one per input move: the plane it was fitted in. A joint between two moves
  /// fitted in the same plane is read in that plane (a pass fitted in XZ under G17 and
  /// written as lines is seen foreshortened in XY), any other in the plane the output is
  /// in there. Empty: the output's plane everywhere (`arcpress diff`).
  std::vector<Plane> fitted_plane;
  /// Measure how far each output move lies on the side of the input it replaces that
  /// `band_side` forbids (PathComparison::max_wrong_side_mm); Both: not measured.
  BandSide band_side = BandSide::Both;
  /// Where the firmware moves along chords (moves_on_chords()), each output arc is also
  /// measured as it is executed: its chords, cut as the firmware cuts them, against the
  /// input moves it replaces (PathComparison::max_executed_mm).
  ArcSegmentation executed;
  /// Where at least 0: each output move that replaces several input moves and extrudes (its
  /// E moves) extrudes evenly along itself as the controller does, and each input move's E
  /// per mm must lie within this share (of the larger) of the output move's
  /// (PathComparison::max_extrusion_rate_share), as the fitter holds them
  /// (FitOptions::extrusion_variance). Negative: not measured (`arcpress diff`).
  double extrusion_variance = -1;
};

/// What the printed numbers may change of an output move's E per mm beyond the fitter's own
/// arc, as a share: its length from the centre rounded to the printed digits (an arc of
/// 0.05 mm radius, the smallest fitted by default, moves by 0.07 % with 4 decimals).
inline constexpr double kExtrusionRateSlack = 0.002;

struct PathComparison {
  bool matched = true;              ///< every output move ends on the input path
  std::string mismatch;             ///< what did not match, with line numbers
  uint32_t mismatch_line_b = 0;     ///< ... the output's line there
  double max_deviation_mm = 0;      ///< largest two-sided distance of feed moves
  uint32_t worst_line_a = 0;        ///< 1-based lines (input, output) where it occurs
  uint32_t worst_line_b = 0;
  Vec3 worst_point{0, 0, 0};        ///< input vertex nearest the worst place, mm
  size_t moves_a = 0, moves_b = 0;  ///< feed moves compared
  /// Joints between two output feed moves of which at least one replaces several input
  /// moves, where the input is smooth (no corner in the sense of is_corner() and
  /// is_corner_beside_corner()).
  size_t smooth_joints = 0;
  size_t smooth_joints_over_g1 = 0;  ///< ... whose tangent changes by more than g1_angle_deg
  std::vector<uint32_t> kink_lines;  ///< ... where: the input line of the move starting at each
  double max_smooth_kink_deg = 0;

  /// With CompareOptions::band_side: the greatest distance by which the input path lies on
  /// the side of an output move that the band side forbids it (so the output on the wrong
  /// side of the input), and where (1-based lines, input and output).
  double max_wrong_side_mm = 0;
  uint32_t wrong_side_line_a = 0, wrong_side_line_b = 0;

  /// Whether the moves were paired one for one as compress() writes them, so that the
  /// distances above bound the whole paths' both ways: every input move lies in the stretch
  /// of an output move (feed moves in a feed move's, each rapid and each move whose path is
  /// not known in one of its own kind, moves that go nowhere anywhere), and with
  /// CompareOptions::executed, every output move's executed path was bounded too. Where
  /// not, only a measure of the whole paths can tell their distance.
  bool covers_path = true;
  /// With CompareOptions::executed moving on chords: an upper bound of the largest two-sided
  /// distance between an output move's executed path and the input moves it replaces (the
  /// input's lines as they are, an input arc it writes again as its own chords), and where
  /// (1-based lines, input and output, and the vertex where that output move starts).
  double max_executed_mm = 0;
  uint32_t executed_line_a = 0, executed_line_b = 0;
  Vec3 executed_point{0, 0, 0};

  /// The largest distance, in the axis's own unit (mm for U/V/W, degrees for A/B/C, the
  /// band's number read in it, as the fitter holds it), between an extra axis as an output
  /// move carries it (linearly with its progress: line_progress(), arc_progress()) and its
  /// value at a vertex of the input moves the output move replaces; where (1-based lines,
  /// input and output), and which axis (kAxisLetters; -1: none moved).
  double max_extra_axis = 0;
  uint32_t extra_axis_line_a = 0, extra_axis_line_b = 0;
  int extra_axis = -1;
  /// With CompareOptions::extrusion_variance: the largest difference between an input
  /// move's E per mm and that of the output move that replaces it, as a share of the larger,
  /// and where (1-based lines, input and output); and what is allowed (the variance and
  /// kExtrusionRateSlack; infinite where not measured).
  double max_extrusion_rate_share = 0;
  uint32_t extrusion_line_a = 0, extrusion_line_b = 0;
  double extrusion_allowed_share = HUGE_VAL;

  bool within(double tolerance_mm) const {
    return matched && max_deviation_mm <= tolerance_mm && max_extra_axis <= tolerance_mm &&
           max_extrusion_rate_share <= extrusion_allowed_share;
  }
};

/// The direction in which move i leaves its start, and arrives at its end, in the move's plane
/// (unit; zero for a line that goes nowhere in it).
Vec2 move_start_tangent(const Interpretation& in, size_t i);
Vec2 move_end_tangent(const Interpretation& in, size_t i);
/// The angle between two directions, degrees (0 where either is zero).
double turn_deg(const Vec2& a, const Vec2& b);

PathComparison compare_paths(const Program& a, const Interpretation& ia, const Program& b,
                             const Interpretation& ib, const CompareOptions& opt);

}  // namespace arcpress
