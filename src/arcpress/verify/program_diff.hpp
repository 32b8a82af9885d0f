// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Comparison of any two interpreted programs (`arcpress diff`): the feed path section by
// section (a section is the feed moves between two rapids), the rapids by their end points,
// and what is not geometry: the sequence of M/T/S/dwell/comment blocks, feed rates along
// the path, and extrusion per section.
//
// Distance is two-sided: every point of A's path to B's and of B's to A's. Each path is cut
// into segments held in a spatial index: lines as they are, an arc that keeps its plane's
// normal axis still into pieces of itself (a few degrees each, within half the band of their
// chords, by which the index's searches reach further), measured exactly, and any other arc
// (a helix, several turns) into chords whose sagitta is at most `arc_chord_mm`, far below the
// tolerance. Along each segment or piece of the other path the distance function is
// 1-Lipschitz. A straight stretch whose two ends have their nearest point on the same segment
// is no farther anywhere than at its ends (distance to a segment is convex); with both ends
// facing the same piece of an arc, no farther than its largest distance off that circle
// (the distance from the centre is convex along it). A stretch along a piece of an arc is
// bounded through its chord, plus its sagitta. A stretch whose bound could still beat the
// maximum found is split, down to `arc_chord_mm`. So no bulge between samples is missed;
// lines and flat arcs are measured exactly to that precision, helices to within their chords.
//
// Speed: the two paths usually run side by side in the same order, so each point is first
// measured against the stretch of the other path around the previous answer; the spatial
// index (a linear scan over boxes of consecutive segments, then the AABB tree once the
// scans have cost what building it would) is asked only for points where that could
// change the maximum or the worst places. The maximum is exact either way; the other listed
// places are measured at the points the search visits, which reach between a path's
// vertices only while they could beat the maximum. The paths are measured in shares whose
// number their lengths alone set, taken by the threads in turn, and the shares' worst
// places merged: the result is the same for any number of threads.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "arcpress/core/deviation.hpp"
#include "arcpress/lex/block.hpp"
#include "arcpress/model/move.hpp"
#include "arcpress/verify/block_rate.hpp"
#include "arcpress/verify/move_geometry.hpp"

namespace arcpress {

/// The bands a caller may ask for, mm: below 10 nm no controller moves, and no measure
/// needs to. diff_programs() throws std::invalid_argument outside them.
inline constexpr double kMinToleranceMm = 0.00001, kMaxToleranceMm = 100;

struct DiffOptions {
  double tolerance_mm = 0.01;  ///< the band B's path must stay in around A's
  size_t top = 5;              ///< how many worst places to report
  /// Threads for the two directions of the path measure (1 or more; 0: as the machine
  /// has). The result is the same for any count.
  unsigned threads = 0;
  /// Compare the feed along the paths. A caller that knows which moves of B stand for which
  /// of A compares it move by move instead (compare_paths(), as compress() does): where the
  /// band is as wide as the path's own features, pairing by place can take a stretch for
  /// another pass with another feed.
  bool feed = true;
  /// Distances of the paths at or below this are of no interest (mm): the measure makes
  /// exact only what exceeds it, so the maximum and worst places are exact where above it,
  /// and where the paths lie no farther apart anywhere it reports at most this. A caller
  /// that knows the paths' distance to be about some value already (the compressor's own
  /// check, from its move-by-move measure) spares the measure most of its work, above all on
  /// a path that retraces itself many times.
  double least_mm = 0;
  /// Measure the distance between the feed paths (both ways). A caller that has bounded it
  /// already, move by move over moves it paired one for one (compress(): compare_paths(),
  /// where PathComparison::covers_path holds), turns this off: everything else (rapids,
  /// entries, sections, extrusion, non-motion blocks, what could not be compared) is
  /// compared as ever, and max_deviation_mm, worst and deviation_of_b are left at nothing
  /// for the caller to fill. Requires `feed` off (the feed is compared along the measure).
  bool measure_path = true;
  /// Compare comments among the non-motion blocks. Off (`arcpress diff --ignore-comments`),
  /// a block that is only a comment is no block to compare, and a comment beside M, T, S or
  /// a dwell is not part of it: another tool's output, with its own header comments, can
  /// then be checked against its input.
  bool comments = true;
};

/// One place where the paths are apart.
struct DiffPlace {
  double deviation_mm = 0;
  Vec3 at{0, 0, 0};      ///< the point (on A's or B's path) farthest from the other path, mm
  uint32_t line_a = 0;   ///< 1-based line of the A move there
  uint32_t line_b = 0;   ///< ... and of the B move
};

struct ProgramSummary {
  size_t blocks = 0, bytes = 0, feed_moves = 0, rapids = 0, sections = 0;
  /// The block rate it demands, where the caller measured it (arcpress diff does).
  std::optional<BlockRate> rate;
  size_t non_motion = 0;     ///< M/T/S/dwell/comment and other non-word blocks compared
  double path_mm = 0;        ///< length of the feed path
  /// Feed moves (G1/G2/G3) that could not be placed: an axis they move has no known
  /// position at their end, so nothing of them can be compared. The first one's line and why.
  size_t unplaced_feed_moves = 0;
  uint32_t first_unplaced_line = 0;
  std::string unplaced_reason;
  /// Feed moves from an unknown position to a known one (the first move after homing, or
  /// after the program's start): compared by their end points, in order, as rapids are.
  size_t entry_moves = 0;
  uint32_t first_entry_line = 0;
  std::string entry_reason;
  /// Arcs too big (radius, turns) for the measure to follow within a tenth of the band:
  /// not measured. The first one's line.
  size_t unmeasured_arcs = 0;
  uint32_t first_unmeasured_line = 0;
  /// Feed moves so far from the origin that a double holds them more coarsely than the
  /// measure needs: not measured. The first one's line.
  size_t far_moves = 0;
  uint32_t first_far_line = 0;
  /// Moves of those two kinds (arcs too big, moves too far) that the other program has
  /// exactly too, the same kind, ends and centre: compared as the same path, not counted above.
  size_t identical_unmeasured = 0;
  /// Feed moves of either kind that were not compared.
  size_t not_compared() const { return unplaced_feed_moves + unmeasured_arcs + far_moves; }
};

struct ProgramDiff {
  ProgramSummary a, b;
  double max_deviation_mm = 0;          ///< feed paths, both ways
  std::vector<DiffPlace> worst;         ///< the worst places, largest first (at most `top`)
  double max_rapid_mm = 0;              ///< rapid end points
  DiffPlace worst_rapid;
  double max_entry_mm = 0;              ///< end points of feed moves from an unknown position
  DiffPlace worst_entry;
  double max_feed_difference_pct = 0;   ///< F at B's moves against A's nearest move
  DiffPlace worst_feed;                 ///< deviation_mm holds nothing here; lines only
  /// The share of B's feed path (by length) whose feed and S were compared with A's: paired
  /// with a piece of A that lies farther than a band's width, along A's path, from a joint
  /// where A's feed or S changes.
  double feed_compared_share = 0;
  /// The length of B's feed path for which no piece of A qualifies as its counterpart, so
  /// whose feed was not compared (mm), and the B line of the first such piece (0: none). A
  /// check that leaves any out is incomplete.
  double feed_unpaired_mm = 0;
  uint32_t feed_unpaired_line_b = 0;
  /// Where an extra axis (A/B/C, U/V/W) moves in either program: the largest difference of
  /// one, each in its own unit (mm, or degrees, the band's number read in it), between B and
  /// A where the feed is compared (each piece of B and its counterpart on A, the axes carried
  /// along each move with its progress: extra_axes_at()) and at the ends of rapids and of
  /// moves from an unknown position; where (deviation_mm holds it), and which axis
  /// (kAxisLetters; -1: none differ). Without the feed pairing (DiffOptions::feed), only at
  /// those ends.
  bool extra_axes_compared = false;
  double max_extra_axis = 0;
  DiffPlace worst_extra_axis;
  int extra_axis = -1;
  double max_extrusion_difference_mm = 0;     ///< E total per section
  double max_extrusion_per_mm_difference_pct = 0;
  size_t non_motion_differences = 0;
  bool comments_compared = true;        ///< DiffOptions::comments
  /// Human-readable findings that make the programs differ besides the distance, e.g.
  /// "non-motion block differs: A line 12 'M3 S1000', B line 12 'M4 S1000'".
  std::vector<std::string> findings;
  /// Per B move (index into B's moves): its largest distance to A's path, for plots.
  std::vector<double> deviation_of_b;
  /// The measure's precision: where its search stops, and the sagitta of the chords that
  /// helices are followed by.
  double arc_chord_mm = 0;

  /// Whether every feed move of both programs was placed, and so compared.
  /// arcpress diff --band-side: how far B lies on the side of A the band forbids, measured
  /// move by move as compress() measures its output (compare_paths()), where B's moves end
  /// on A's vertices; not measured elsewhere.
  struct SideMeasure {
    BandSide side = BandSide::Both;
    bool measured = false;
    std::string why_not;           ///< where not measured
    double max_wrong_side_mm = 0;  ///< how far A lies on the forbidden side of B's moves
    double allowance_mm = 0;       ///< what rounding the printed digits may cost
    uint32_t line_a = 0, line_b = 0;
  };
  std::optional<SideMeasure> band_side;

  bool compared_all() const {
    return a.not_compared() + b.not_compared() == 0 && feed_unpaired_mm == 0 && (!band_side || band_side->measured);
  }
  /// How much the measure of the paths may read short where big arcs' chords lie farther off
  /// them than its precision (0 for any ordinary program): counted against the band.
  double chord_excess_mm = 0;
  /// Whether what was compared agrees within the band.
  bool agrees(double tolerance_mm) const {
    return max_deviation_mm + chord_excess_mm <= tolerance_mm && max_rapid_mm <= tolerance_mm &&
           max_entry_mm <= tolerance_mm && max_extra_axis <= tolerance_mm && findings.empty() &&
           (!band_side || !band_side->measured || band_side->max_wrong_side_mm <= band_side->allowance_mm);
  }
  /// The programs are the same: everything compared, and it agrees. A check never passes
  /// what it did not compare.
  bool same(double tolerance_mm) const { return compared_all() && agrees(tolerance_mm); }
  enum class Verdict { Same, Different, Incomplete };
  /// Different where what was compared differs; else incomplete where not all was compared.
  Verdict verdict(double tolerance_mm) const {
    return !agrees(tolerance_mm) ? Verdict::Different : compared_all() ? Verdict::Same : Verdict::Incomplete;
  }
};

ProgramDiff diff_programs(const Program& a, const Interpretation& ia, const Program& b, const Interpretation& ib,
                          const DiffOptions& opt);

}  // namespace arcpress
