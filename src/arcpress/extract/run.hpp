// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Run extraction stage: maximal stretches of consecutive plain G1 feed blocks that a fitter
// may rewrite. A run never crosses a block that is anything else (comments, M-codes, feed or
// frame changes, unknown positions), so everything outside runs is written back untouched.
// A stretch that lies flat in another principal plane than the program's while the program's
// plane climbs is a run of its own in that plane (see extract_runs).
#include <cstdint>
#include <vector>

#include "arcpress/model/move.hpp"

namespace arcpress {

struct Run {
  uint32_t first_move = 0;  ///< index of the first move of the run in Interpretation::moves
  uint32_t move_count = 0;  ///< number of G1 moves; the run has move_count + 1 vertices
  uint32_t frame = 0;
  /// The plane the run is fitted in: the program's (Move::plane), or a principal plane in
  /// which every vertex of the run lies (the emitter then selects it around the run's arcs).
  Plane plane = Plane::XY;
  double feed_mm_min = 0;

  /// Vertex v (0 .. move_count): v = 0 is the start of the first move.
  const AxisValues& vertex(const Interpretation& in, uint32_t v) const { return in.from(first_move + v); }
  Vec3 point(const Interpretation& in, uint32_t v) const {
    const auto& a = vertex(in, v);
    return {a[kX], a[kY], a[kZ]};
  }
};

/// How extract_runs() chooses the plane of a stretch.
struct PlaneChoice {
  /// A principal axis whose values over a stretch spread by no more than this (mm; what the
  /// fitter carries along a plane's normal axis inside a primitive) is fixed there.
  double spread_mm = 0;
  /// A stretch takes another plane than the program's only where it curves in that plane
  /// by more than this (mm; the fit's tolerance); one whose axis is not fixed exactly, only
  /// within the spread, also ends at a corner (is_corner() with this band and
  /// `corner_angle_deg`).
  double band_mm = 0;
  double corner_angle_deg = 30;
};

/// Whether the path has a corner at vertex k (the start of move k): is_corner() in the plane
/// of move k, with the vertices beside it past moves that go nowhere; so where the feed path
/// ends on either side. A chain of runs ends there (chain_runs()).
bool corner_at(const Interpretation& in, size_t k, double band_mm, double corner_angle_deg);

/// Finds all runs of at least `min_moves` fittable moves.
std::vector<Run> extract_runs(const Interpretation& in, uint32_t min_moves = 2, const PlaneChoice& choice = {});

/// Runs that follow one another along the path and are fitted together, so that the joints
/// between them are tangent where the path is smooth: moves first_move .. first_move +
/// move_count - 1, holding runs first_run .. first_run + run_count - 1 and, between or around
/// them, lone G1 moves (fittable moves that are no run), the input's own arcs and the last
/// move before a block arcpress does not read (Move::in_chain()), all written back as they
/// are. Only blocks that do not move (comments, feed words, M-codes)
/// separate its moves, and all lie in one frame and program plane (its runs may be fitted
/// in another plane, see extract_runs()).
struct RunChain {
  uint32_t first_move = 0;
  uint32_t move_count = 0;
  uint32_t first_run = 0;
  uint32_t run_count = 0;
};

/// Groups `runs` (as extract_runs() found them) into chains. Where the path has a corner
/// between two pieces (is_corner() with `band_mm` and `corner_angle_deg`), nothing ties their
/// tangents, and a new chain starts, so chains stay short enough to fit on separate threads.
std::vector<RunChain> chain_runs(const Interpretation& in, const std::vector<Run>& runs, double band_mm,
                                 double corner_angle_deg);

/// G1 moves that are in no run, grouped by why (Move::unfit; Unfit::None: a fittable move
/// with no fittable neighbour to make a run with), in the order each reason first occurs.
struct LeftOut {
  Unfit why = Unfit::None;
  size_t moves = 0;
  uint32_t first_move = 0;  ///< the first such move
  uint32_t cause_line = 0;  ///< unplaced moves: the line that made the first one's axis unknown (0: never set)
};
std::vector<LeftOut> left_out_moves(const Interpretation& in, const std::vector<Run>& runs);

}  // namespace arcpress
