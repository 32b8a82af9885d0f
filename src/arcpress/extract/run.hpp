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

/// Finds all runs of at least `min_moves` fittable moves.
std::vector<Run> extract_runs(const Interpretation& in, uint32_t min_moves = 2);

}  // namespace arcpress
