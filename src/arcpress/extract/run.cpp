// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/extract/run.hpp"

#include <algorithm>
#include <cmath>

#include "arcpress/core/deviation.hpp"

namespace arcpress {
namespace {

/// Fewest moves a stretch needs to be cut out of its run and fitted in another plane.
constexpr size_t kMinPlanePieceMoves = 3;

/// How far apart two values of an axis may lie and still be one fixed coordinate: `spread_mm`
/// (what the fitter carries along a plane's normal axis inside each primitive), and at least
/// the floating noise of unit conversion, not the user's band.
bool within_spread(double lo, double hi, double spread_mm) {
  return hi - lo <= std::max(spread_mm, kLengthEpsMm * std::max({1.0, std::abs(lo), std::abs(hi)}));
}

/// The principal plane whose normal is `axis` (0 X, 1 Y, 2 Z).
Plane plane_with_normal(int axis) { return axis == 2 ? Plane::XY : axis == 1 ? Plane::ZX : Plane::YZ; }

/// What split_by_plane() asks of the moves [i, j) again and again, worked out once in a pass
/// or two over them, so that trying every start costs the same at each: linear in the moves.
class Stretch {
 public:
  Stretch(const Interpretation& in, size_t i, size_t j, const PlaneChoice& choice) : in_(in), i_(i), j_(j) {
    const size_t n = j - i;
    going_.assign(n + 1, 0);
    for (size_t k = 0; k < n; ++k) going_[k + 1] = going_[k] + !in.goes_nowhere(i + k);
    corner_after_.assign(n + 1, j);
    for (size_t k = j; k-- > i + 1;)
      corner_after_[k - 1 - i] =
          !in.goes_nowhere(k - 1) && corner_at(in, k, choice.band_mm, choice.corner_angle_deg) ? k : corner_after_[k - i];
    for (int axis = 0; axis < 3; ++axis) {
      flat_until(axis, 0, exact_[axis]);
      flat_until(axis, choice.spread_mm, near_[axis]);
    }
  }

  /// How many of the moves [m, t) go somewhere.
  size_t moves_going(size_t m, size_t t) const { return going_[t - i_] - going_[m - i_]; }
  /// The end of the longest stretch of moves from m (before j) whose vertices keep `axis`
  /// exactly (`exact`) or within the spread.
  size_t flat_until(int axis, size_t m, bool exact) const { return (exact ? exact_ : near_)[axis][m - i_]; }
  /// Whether the vertices of moves [m, t) spread along `axis` by more than the spread.
  bool moves_along(int axis, size_t m, size_t t) const { return near_[axis][m - i_] < t; }
  /// The first vertex k in (m, t) where the path has a corner (corner_at()), else t.
  size_t smooth_until(size_t m, size_t t) const { return std::min(corner_after_[m - i_], t); }

 private:
  /// ends[m - i] = the end of the longest stretch from m whose vertices keep `axis` within
  /// `spread_mm` (within_spread()): a window slid along the moves, its lowest and highest
  /// values kept in two monotone queues.
  void flat_until(int axis, double spread_mm, std::vector<size_t>& ends) const {
    const size_t n = j_ - i_;
    ends.assign(n, j_);
    auto value = [&](size_t v) { return in_.from(i_ + v)[axis]; };  // vertex v of the stretch (0 .. n)
    std::vector<size_t> lows, highs;  // vertex numbers, values rising / falling
    size_t lo_head = 0, hi_head = 0;
    size_t t = 0;  // the window holds vertices m .. t
    for (size_t m = 0; m < n; ++m) {
      if (t < m) t = m;
      auto push = [&](size_t v) {
        while (lows.size() > lo_head && value(lows.back()) >= value(v)) lows.pop_back();
        lows.push_back(v);
        while (highs.size() > hi_head && value(highs.back()) <= value(v)) highs.pop_back();
        highs.push_back(v);
      };
      if (lows.size() == lo_head) push(m);
      while (lo_head < lows.size() && lows[lo_head] < m) ++lo_head;
      while (hi_head < highs.size() && highs[hi_head] < m) ++hi_head;
      if (lo_head == lows.size()) push(m);
      // Grow the window while vertex t + 1 keeps it within the spread.
      while (t < n) {
        const double v = value(t + 1);
        const double lo = std::min(value(lows[lo_head]), v), hi = std::max(value(highs[hi_head]), v);
        if (!within_spread(lo, hi, spread_mm)) break;
        ++t;
        push(t);
      }
      ends[m] = i_ + t;  // moves m .. t - 1 keep it
    }
  }

  const Interpretation& in_;
  size_t i_, j_;
  std::vector<uint32_t> going_;        // prefix counts of moves that go somewhere
  std::vector<size_t> corner_after_;   // per vertex m - i: the first corner after it
  std::vector<size_t> exact_[3], near_[3];
};

/// Whether a vertex of moves [i, t) lies more than `band_mm` off the chord from the first to
/// the last, seen in `plane`: whether arcs in that plane have a curve to follow there.
bool curves_in(const Interpretation& in, size_t i, size_t t, Plane plane, double band_mm) {
  const auto ax = axes_of(plane);
  auto at = [&](const AxisValues& v) { return Vec2(v[ax.first], v[ax.second]); };
  const Vec2 a = at(in.from(i)), b = at(in.moves[t - 1].to);
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  for (size_t k = i; k + 1 < t; ++k) {
    const Vec2 p = at(in.moves[k].to);
    const double s = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
    if ((p - (a + s * d)).norm() > band_mm) return true;
  }
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
/// axis spreads by more than `spread_mm`) over at least kMinPlanePieceMoves moves that go
/// somewhere and all keep one other principal axis within `spread_mm`, those moves lie flat
/// in that other plane, whose arcs are the only ones that can follow them (their projection
/// on the program's plane is a straight line): where they curve in it by more than `band_mm`,
/// they become a run of their own in that plane. (A stretch of a helix where one axis is
/// about still, over its top, is straight in that plane too, and stays in the helix.)
/// So a raster pass in XZ under G17 becomes G18 arcs rather than lines, also where the
/// program's digits or a transform make its Y wander by a few microns. (Seed 004's PCA plane
/// test comes to this for the principal planes, the only ones G2/G3 have: the spread along
/// an axis is what decides, and it is measured exactly.) Where no axis stays fixed (a helix,
/// a 3D surface path) the program's plane stays, with helical arcs or lines.
void split_by_plane(const Interpretation& in, size_t i, size_t j, uint32_t min_moves, const PlaneChoice& choice,
                    std::vector<Run>& runs) {
  const Plane own = in.moves[i].plane;
  const int own_normal = axes_of(own).normal;
  // Flat in the program's plane, the common case: by one pass over the moves.
  double lo = in.from(i)[own_normal], hi = lo;
  bool flat = true;
  for (size_t t = i; t < j && flat; ++t) {
    lo = std::min(lo, in.moves[t].to[own_normal]);
    hi = std::max(hi, in.moves[t].to[own_normal]);
    flat = within_spread(lo, hi, choice.spread_mm);
  }
  if (flat) {
    add_run(in, i, j, own, min_moves, runs);
    return;
  }
  const Stretch st(in, i, j, choice);
  size_t piece = i;  // start of the stretch left in the program's plane
  // Per axis, the first start worth trying: a stretch [m, t) that is no piece because it is
  // too short or flat in the program's plane makes every start in (m, t) fail the same way;
  // one straight in the other plane leaves its later parts about as straight.
  size_t blocked[3] = {i, i, i};
  for (size_t m = i; m < j; ++m) {
    size_t best_end = m;
    int best_axis = -1;
    for (int axis = 0; axis < 3; ++axis) {
      if (axis == own_normal || m < blocked[axis]) continue;
      // (A move that goes nowhere lies in every plane: it neither makes a piece nor ends one.)
      auto piece_to = [&](size_t t) {
        return st.moves_going(m, t) >= kMinPlanePieceMoves && st.moves_along(own_normal, m, t) &&
               curves_in(in, m, t, plane_with_normal(axis), choice.band_mm);
      };
      // Where the axis keeps its very value, the piece runs as far as that, corners and all
      // (a plunge into a raster pass belongs to it); where it only stays within the spread,
      // the piece also ends at a corner (microns of wander around a plunge are chance).
      const size_t exact = st.flat_until(axis, m, true);
      const size_t near = st.smooth_until(m, st.flat_until(axis, m, false));
      const size_t t = near > exact && piece_to(near) ? near : piece_to(exact) ? exact : m;
      if (t == m) {
        blocked[axis] = std::min(exact, near);
      } else if (t > best_end) {
        best_end = t;
        best_axis = axis;
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

bool corner_at(const Interpretation& in, size_t k, double band_mm, double corner_angle_deg) {
  const Plane pl = in.moves[std::min(k, in.moves.size() - 1)].plane;
  auto point = [&](size_t v) {  // vertex v in the plane's coordinates, as the verifier reads it
    const auto& a = in.from(v);
    const auto ax = axes_of(pl);
    return Vec3(a[ax.first], a[ax.second], a[ax.normal]);
  };
  const auto b = in.vertex_beside(k, -1), a = in.vertex_beside(k, +1);
  return !b || !a || is_corner(point(*b), point(k), point(*a), band_mm, corner_angle_deg);
}

std::vector<Run> extract_runs(const Interpretation& in, uint32_t min_moves, const PlaneChoice& choice) {
  std::vector<Run> runs;
  const auto& mv = in.moves;
  size_t i = 0;
  while (i < mv.size()) {
    if (!mv[i].fittable()) {
      ++i;
      continue;
    }
    size_t j = i + 1;
    while (j < mv.size() && mv[j].fittable() && mv[j].block == mv[j - 1].block + 1 &&
           mv[j].frame == mv[i].frame && mv[j].plane == mv[i].plane && mv[j].feed_mm_min == mv[i].feed_mm_min &&
           mv[j].spindle == mv[i].spindle)
      ++j;
    // The first move must also follow its predecessor directly, or its start is not its block's.
    split_by_plane(in, i, j, min_moves, choice, runs);
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
  std::vector<RunChain> chains;
  RunChain cur;
  bool open = false;
  auto close = [&] {
    if (open && cur.run_count > 0) chains.push_back(cur);
    open = false;
  };
  for (size_t k = 0; k < mv.size(); ++k) {
    const int32_t r = run_of[k];
    if (!mv[k].in_chain()) {
      close();
      continue;
    }
    if (open) {
      const Move& prev = mv[k - 1];
      const bool same_piece = r >= 0 && run_of[k - 1] == r;
      if (prev.frame != mv[k].frame || prev.plane != mv[k].plane ||
          (!same_piece && corner_at(in, k, band_mm, corner_angle_deg)))
        close();
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

std::vector<LeftOut> left_out_moves(const Interpretation& in, const std::vector<Run>& runs) {
  std::vector<LeftOut> groups;
  auto add = [&](Unfit why, uint32_t move, uint32_t cause) {
    for (LeftOut& g : groups)
      if (g.why == why) {
        ++g.moves;
        return;
      }
    groups.push_back({why, 1, move, cause});
  };
  size_t r = 0, u = 0;
  for (uint32_t k = 0; k < in.moves.size(); ++k) {
    while (r < runs.size() && runs[r].first_move + runs[r].move_count <= k) ++r;
    if (r < runs.size() && runs[r].first_move <= k) continue;  // in a run
    const Move& m = in.moves[k];
    while (u < in.unplaced.size() && in.unplaced[u].move < k) ++u;
    if (m.kind != MoveKind::Line) continue;
    const uint32_t cause = u < in.unplaced.size() && in.unplaced[u].move == k ? in.unplaced[u].cause_line : 0;
    add(m.unfit, k, cause);
  }
  return groups;
}

}  // namespace arcpress
