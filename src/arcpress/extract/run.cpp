#include "arcpress/extract/run.hpp"

#include <algorithm>
#include <cmath>

#include "arcpress/core/deviation.hpp"

namespace arcpress {
namespace {

/// Fewest moves a stretch needs to be cut out of its run and fitted in another plane.
constexpr size_t kMinPlanePieceMoves = 3;

/// Whether two coordinates are the same position (floating noise of unit conversion, not
/// the user's band: a piece that wanders along an axis by more does not lie flat in it).
bool same_coordinate(double a, double b) { return std::abs(a - b) <= kLengthEpsMm * std::max(1.0, std::abs(a)); }

/// The principal plane whose normal is `axis` (0 X, 1 Y, 2 Z).
Plane plane_with_normal(int axis) { return axis == 2 ? Plane::XY : axis == 1 ? Plane::ZX : Plane::YZ; }

/// The end of the longest stretch of moves from `i` (before `j`) that keep `axis` where the
/// start of move `i` has it.
size_t flat_until(const Interpretation& in, size_t i, size_t j, int axis) {
  const double c = in.from(i)[axis];
  size_t t = i;
  while (t < j && same_coordinate(in.moves[t].to[axis], c)) ++t;
  return t;
}

/// Whether any of the moves [i, t) changes `axis`.
bool moves_along(const Interpretation& in, size_t i, size_t t, int axis) {
  for (size_t k = i; k < t; ++k)
    if (!same_coordinate(in.moves[k].to[axis], in.from(k)[axis])) return true;
  return false;
}

void add_run(const Interpretation& in, size_t i, size_t j, Plane plane, uint32_t min_moves, std::vector<Run>& runs) {
  if (j - i < min_moves) return;
  const Move& m = in.moves[i];
  Run r;
  r.first_move = uint32_t(i);
  r.move_count = uint32_t(j - i);
  r.frame = m.frame;
  r.plane = plane;
  r.feed_mm_min = m.feed_mm_min;
  runs.push_back(r);
}

/// Splits the fittable moves [i, j) (one frame, plane and feed) into runs by the plane they
/// lie in. The program's plane is kept wherever it can hold arcs. Where it climbs (its normal
/// axis moves) over at least kMinPlanePieceMoves moves that go somewhere and all keep one
/// other principal axis fixed, those moves lie flat in that other plane, whose arcs are the
/// only ones that can follow them (their projection on the program's plane is a straight
/// line): they become a run of their own in that plane. So a raster pass in XZ under G17 becomes G18 arcs rather
/// than lines. Where no axis stays fixed (a helix, a 3D surface path) the program's plane
/// stays, with helical arcs or lines.
void split_by_plane(const Interpretation& in, size_t i, size_t j, uint32_t min_moves, std::vector<Run>& runs) {
  const Plane own = in.moves[i].plane;
  const int own_normal = axes_of(own).normal;
  if (!moves_along(in, i, j, own_normal)) {  // flat in the program's plane: the common case
    add_run(in, i, j, own, min_moves, runs);
    return;
  }
  size_t piece = i;  // start of the stretch left in the program's plane
  // Per axis, the first start worth trying: a stretch [m, t) that is no piece because it is
  // too short or flat in the program's plane makes every start in (m, t) fail the same way.
  size_t blocked[3] = {i, i, i};
  for (size_t m = i; m < j; ++m) {
    size_t best_end = m;
    int best_axis = -1;
    for (int axis = 0; axis < 3; ++axis) {
      if (axis == own_normal || m < blocked[axis]) continue;
      size_t t = flat_until(in, m, j, axis);
      // (A move that goes nowhere lies in every plane: it neither makes a piece nor ends one.)
      if (in.moves_going(m, t) >= kMinPlanePieceMoves && moves_along(in, m, t, own_normal)) {
        if (t > best_end) {
          best_end = t;
          best_axis = axis;
        }
      } else {
        blocked[axis] = t;
      }
    }
    if (best_axis < 0) continue;
    add_run(in, piece, m, own, min_moves, runs);
    add_run(in, m, best_end, plane_with_normal(best_axis), min_moves, runs);
    piece = best_end;
    m = best_end - 1;
  }
  add_run(in, piece, j, own, min_moves, runs);
}

}  // namespace

std::vector<Run> extract_runs(const Interpretation& in, uint32_t min_moves) {
  std::vector<Run> runs;
  const auto& mv = in.moves;
  size_t i = 0;
  while (i < mv.size()) {
    if (!mv[i].fittable) {
      ++i;
      continue;
    }
    size_t j = i + 1;
    while (j < mv.size() && mv[j].fittable && mv[j].block == mv[j - 1].block + 1 &&
           mv[j].frame == mv[i].frame && mv[j].plane == mv[i].plane && mv[j].feed_mm_min == mv[i].feed_mm_min)
      ++j;
    // The first move must also follow its predecessor directly, or its start is not its block's.
    split_by_plane(in, i, j, min_moves, runs);
    i = j;
  }
  return runs;
}

std::vector<RunChain> chain_runs(const Interpretation& in, const std::vector<Run>& runs, double band_mm,
                                 double corner_angle_deg) {
  const auto& mv = in.moves;
  std::vector<int32_t> run_of(mv.size(), -1);
  for (size_t r = 0; r < runs.size(); ++r)
    for (uint32_t k = 0; k < runs[r].move_count; ++k) run_of[runs[r].first_move + k] = int32_t(r);
  auto point = [&](size_t i, Plane pl) {  // start of move i in the plane's coordinates
    const auto& v = in.from(i);
    const auto ax = axes_of(pl);
    return Vec3(v[ax.first], v[ax.second], v[ax.normal]);
  };
  std::vector<RunChain> chains;
  RunChain cur;
  bool open = false;
  auto close = [&] {
    if (open && cur.run_count > 0) chains.push_back(cur);
    open = false;
  };
  for (size_t k = 0; k < mv.size(); ++k) {
    const int32_t r = run_of[k];
    if (!mv[k].fittable && !(is_arc(mv[k].kind) && mv[k].known)) {
      close();
      continue;
    }
    if (open) {
      const Move& prev = mv[k - 1];
      const bool same_piece = r >= 0 && run_of[k - 1] == r;
      // The corner rule at the joint, with the vertices beside it past moves that go nowhere.
      auto corner = [&] {
        const auto b = in.vertex_beside(k, -1), a = in.vertex_beside(k, +1);
        return !b || !a || is_corner(point(*b, mv[k].plane), point(k, mv[k].plane), point(*a, mv[k].plane), band_mm,
                                     corner_angle_deg);
      };
      if (prev.frame != mv[k].frame || prev.plane != mv[k].plane || (!same_piece && corner())) close();
    }
    if (!open) {
      cur = {uint32_t(k), 0, r >= 0 ? uint32_t(r) : uint32_t(0), 0};
      open = true;
    }
    ++cur.move_count;
    if (r >= 0 && runs[size_t(r)].first_move == k) {
      if (cur.run_count == 0) cur.first_run = uint32_t(r);
      ++cur.run_count;
    }
  }
  close();
  return chains;
}

}  // namespace arcpress
