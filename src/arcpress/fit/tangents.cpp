// SPDX-License-Identifier: GPL-3.0-or-later
// The input's own directions at a vertex (circles through its neighbours), and the start
// tangents the searches try where the tangent is free.
#include "arcpress/fit/angle_ranges.hpp"
#include "arcpress/fit/run_fitter.hpp"

namespace arcpress::fit_detail {

/// The input's own direction at vertex e, from each side apart: the mean of the tangents
/// at e of the circles through e and two vertices behind it, and through e and two ahead
/// (0.1 mm apart or more, or kLocalMoves moves). Where the curvature jumps (a fillet
/// meeting a straight side), each circle follows its own curve, where one circle through
/// both sides would bend the tangent towards the tighter (by 0.46° at the end of a 5 mm
/// fillet written in 0.2 mm moves, more than a joint may turn). input_tangent() where a
/// side lacks the vertices.
std::optional<Vec2> RunFitter::sided_tangent(uint32_t e, uint32_t lo, uint32_t hi) const {
  if (e <= lo || e >= hi) return std::nullopt;
  uint32_t wl = 1, wr = 1;
  while (e - wl > lo && wl < kLocalMoves && (q(e - wl) - q(e)).norm() < 0.1) ++wl;
  while (e + wr < hi && wr < kLocalMoves && (q(e + wr) - q(e)).norm() < 0.1) ++wr;
  if (e >= lo + 2 * wl && e + 2 * wr <= hi) {
    auto tl = circle_tangent(q(e), q(e - wl), q(e - 2 * wl));
    auto tr = circle_tangent(q(e), q(e + wr), q(e + 2 * wr));
    if (tl && tr && (*tr - *tl).squaredNorm() > 0) return Vec2((*tr - *tl).normalized());
  }
  return input_tangent(e, lo, hi);
}

/// The input's own direction at vertex e: tangent at e of the circle through e-w, e, e+w,
/// with w wide enough (0.1 mm each side, or kLocalMoves moves) that 4-decimal rounding
/// does not steer it. Nothing at the ends of the stretch [lo, hi].
std::optional<Vec2> RunFitter::input_tangent(uint32_t e, uint32_t lo, uint32_t hi) const {
  if (e <= lo || e >= hi) return std::nullopt;
  uint32_t w = 1;
  while (e - w > lo && e + w < hi && w < kLocalMoves &&
         ((q(e - w) - q(e)).norm() < 0.1 || (q(e + w) - q(e)).norm() < 0.1))
    ++w;
  Vec2 a = q(e - w), b = q(e), c = q(e + w);
  auto t = circle_tangent(b, c, a);  // at b, pointing towards c
  return t;
}

/// The tangent with which `c`, starting at vertex `from`, leaves it.
Vec2 RunFitter::start_tangent(const Chosen& c, uint32_t from) const {
  if (c.prim.kind == Primitive::Kind::Line) {
    Vec2 chord = q(c.prim.end_vertex) - q(from);
    return chord.norm() > kLengthEpsMm ? Vec2(chord.normalized()) : c.end_tangent;
  }
  return arc_tangent(q(from) - c.prim.center, c.prim.ccw);
}

/// The end tangent of the arc leaving `from` along T through `to`: T reflected about the
/// chord (a line's is the chord itself, within the line allowance of that).
Vec2 RunFitter::reflected_end(uint32_t from, const Vec2& T, uint32_t to) const {
  Vec2 c = q(to) - q(from);
  double len = c.norm();
  if (len <= kLengthEpsMm) return T;
  c /= len;
  return 2 * c.dot(T) * c - T;
}

/// The end tangent of the line or arc leaving `from` along T through `to`, as
/// through_candidate() would make it (not yet checked): the chord where that is a line, else
/// T reflected about the chord.
Vec2 RunFitter::end_along(uint32_t from, const Vec2& T, uint32_t to) const {
  const Vec2 u = q(to) - q(from);
  const bool line = pseudo_angle(u.dot(T), std::abs(u.dot(left_normal(T)))) <= line_alpha_;
  return unchecked(from, T, Candidate{to, 0.0, line}).end_tangent;
}

/// The start along `in` turned within kTurnShare of the G1 angle so that the arc from
/// `from` to `to` ends as close to `out` as it can (`in` itself without `out`); nothing
/// when even the largest turn misses it.
std::optional<Vec2> RunFitter::aimed(uint32_t from, const Vec2& in, uint32_t to, const std::optional<Vec2>& out) const {
  if (!out) return in;
  const double turn = kTurnShare * deg_to_rad(o_.g1_angle_deg);
  const Vec2 end = reflected_end(from, in, to);
  if (!two_turns_line_cone_.holds(end, *out)) return std::nullopt;
  return rotated(in, std::clamp(-angle_to(end, *out), -turn, turn));
}

/// The input's own directions at `a`, where the tangent is free: those of circles through
/// the next vertices, of the first chord, and of the input around `a` inside the stretch.
void RunFitter::input_tangents(uint32_t a, uint32_t limit, std::vector<Vec2>& out) const {
  out.clear();
  for (uint32_t w : {2u, 4u, 8u, 16u}) {
    if (a + w > limit) break;
    if (auto t = circle_tangent(q(a), q(a + w / 2), q(a + w))) out.push_back(*t);
  }
  Vec2 chord = q(a + 1) - q(a);
  if (chord.norm() > kLengthEpsMm) out.push_back(chord.normalized());
  if (auto t = input_tangent(a, stretch_start_, limit)) out.push_back(*t);
  // Where the path leaves `a` along the plane's normal (a plunge), it has no direction in
  // the plane: any will do for the lines that follow it.
  if (out.empty()) out.push_back(Vec2(1, 0));
}

/// Where the searches start at `a`: the tangents a smooth joint allows after the incoming
/// one (turned by no more than a line's chord may add to stay within kJointShare of the
/// G1 angle), else start_tangents().
void RunFitter::roots(uint32_t a, uint32_t limit, std::vector<Vec2>& out) const {
  out.clear();
  if (!arrives_along(a)) {
    // The bound's search and the beam after it start from the same free start: its
    // tangents are read once.
    RootsRead& read = s_.roots_read;
    if (read.stretch != stretch_id_ || read.a != a || read.limit != limit) {
      read.tangents.clear();
      start_tangents(a, limit, read.tangents);
      read.stretch = stretch_id_;
      read.a = a;
      read.limit = limit;
    }
    out = read.tangents;
    return;
  }
  out.push_back(*in_tangent_);
  for (const Turn& turn : root_turns_) out.push_back(turn(*in_tangent_));
}

/// The searches' start tangents at `a` where the tangent is free, appended to `out`: for
/// each end e the first primitive can reach, the range of start tangents whose circle
/// through e keeps the vertices and move middles between inside the band (start_range())
/// is known exactly, and its edges (kStartRangeInset inside) are the starts that end at e
/// turned furthest either way. Those of the kNearStartEnds nearest ends give the turns a
/// chain can take right after a corner, those of the kFarStartEnds furthest, with the
/// middle of the furthest, the longest first primitives; the chord to the furthest end a
/// line reaches, the line; into_next() the start from which the second move follows as a
/// line. 15 starts at most, where 46 were read off the input (the tangents of circles
/// through the next vertices, of the first chord and of the input around `a`, each turned
/// by 0.5° to 4° either way): those missed the narrow ranges that reach furthest and the
/// turns the band allows over a short first move (the corpus with default options:
/// 320 706 blocks and 4 024 forced kinks from the fan, 319 352 and 3 396 from the ranges).
void RunFitter::start_tangents(uint32_t a, uint32_t limit, std::vector<Vec2>& out) const {
  const size_t first = out.size();
  auto add = [&](const Vec2& T) {
    for (size_t i = first; i < out.size(); ++i)
      if (same_tangent_cone_.holds(out[i], T)) return;
    out.push_back(T);
  };
  // The two starts that end at r.e turned furthest either way (kStartRangeInset inside).
  auto put_edges = [&](const StartRange& r, bool middle) {
    add(range_start(a, r, kStartRangeInset));
    add(range_start(a, r, 1 - kStartRangeInset));
    if (middle) add(range_start(a, r, 0.5));
  };
  // A line's tangent is its chord: the one to the furthest end a line reaches (the scan
  // along it offers the lines a vertex or two shorter too). First, so that where a line
  // and an arc do as well, the line is kept.
  if (const uint32_t line_end = furthest_line_end(a, limit); line_end > a) add((q(line_end) - q(a)).normalized());
  // The ends reached, in the order found: the nearest one by one, then the furthest
  // (furthest_reached()) and the one before it.
  std::vector<StartRange>& reached = s_.reached;
  reached.clear();
  auto reach = [&](uint32_t e) {
    if (soft_between(a, e)) return false;
    const auto [lo, hi] = start_range(a, e);
    if (lo <= hi) reached.push_back({e, lo, hi});
    return lo <= hi;
  };
  int misses = 0;  // ends in a row that no start reaches (a later one may be reached again)
  uint32_t e = a + 1;
  for (; e <= limit && reached.size() < kNearStartEnds && misses < 2; ++e) {
    misses = reach(e) ? 0 : misses + 1;
    if (misses == 0) put_edges(reached.back(), false);
  }
  if (reached.size() == kNearStartEnds && e <= limit) {
    const uint32_t far = furthest_reached(e - 1, limit, reach);
    if (far - 1 > a && reached.back().e != far - 1) reach(far - 1);
  }
  std::sort(reached.begin(), reached.end(), [](const StartRange& x, const StartRange& y) { return x.e > y.e; });
  for (size_t i = 0; i < std::min(kFarStartEnds, reached.size()); ++i) put_edges(reached[i], i == 0);
  if (auto T = into_next(a, limit)) add(*T);
  // Where the path leaves `a` along the plane's normal (a plunge), it has no direction in
  // the plane: any will do for the lines that follow it.
  if (out.size() == first) out.push_back(Vec2(1, 0));
}

/// The start at `a` in range `r` at `share` of the way from its lowest angle to its
/// highest.
Vec2 RunFitter::range_start(uint32_t a, const StartRange& r, double share) const {
  return Turn(r.lo + share * (r.hi - r.lo))((q(r.e) - q(a)).normalized());
}

/// The directions (rad, near [lo, hi]) leaving vertex v whose primitive reaches vertex e
/// inside the band (start_range()) that lie within [lo, hi]; none when none does.
std::optional<std::pair<double, double>> RunFitter::starts_within(uint32_t v, uint32_t e, double lo, double hi) const {
  const auto [rlo, rhi] = start_range(v, e);
  if (rlo > rhi) return std::nullopt;
  const Vec2 chord = q(e) - q(v);
  const double at = near_angle(std::atan2(chord.y(), chord.x()), 0.5 * (lo + hi));
  const double from = std::max(lo, at + rlo), upto = std::min(hi, at + rhi);
  if (from > upto) return std::nullopt;
  return std::pair(from, upto);
}

/// The furthest vertex e after `a` (up to `limit`) whose chord from `a` passes within the
/// band of every vertex between (furthest_reached()); `a` itself when the first move has
/// no length in the plane.
uint32_t RunFitter::furthest_line_end(uint32_t a, uint32_t limit) const {
  auto reaches = [&](uint32_t e) {
    const Vec2 chord = q(e) - q(a);
    const double length = chord.norm();
    if (length <= kLengthEpsMm || soft_between(a, e)) return false;
    for (uint32_t m = a + 1; m < e; ++m)
      if (std::abs(cross2(chord, q(m) - q(a))) > eps_ * length) return false;
    return true;
  };
  return reaches(a + 1) ? furthest_reached(a + 1, limit, reaches) : a;
}

/// The tangent-chord angles (radians, positive turning left of the chord a→e) of the
/// circles from vertex a through vertex e that pass within the band of every vertex and
/// move middle between, as [lo, hi] (empty when lo > hi), within the largest sweep. The
/// scan's test of a point u (from a, off the tangent by u·N) against the circle of
/// curvature k, |k·(|u|² − ε²) − 2·u·N| <= 2ε, becomes for the circle through e (chord
/// length L, tangent turned by α from the chord, k = −2·sin α / L) |P·sin α + Q·cos α| <= ε
/// with P = (|u|² − ε²) / L − u along the chord and Q = u across it: an interval of α
/// around the zero of R·sin(α + β) (R² = P² + Q²) asin(ε / R) wide each way. The bounds
/// are kept as directions and compared as pseudo-angles; only the result's are angles.
/// The band is the in-plane share once a vertex climbs, as in the scan.
template <class Point>
bool RunFitter::start_bounds(uint32_t a, uint32_t e, bool middles, Point&& point) const {
  const Vec2 chord = q(e) - q(a);
  const double length = chord.norm();
  if (length <= kLengthEpsMm) return false;
  const Vec2 c = chord / length;
  const double inv_length = 1 / length;
  bool flat = true;
  for (uint32_t m = a + 1; m <= e && flat && !level_; ++m) flat = std::abs(p_[m].z() - p_[a].z()) <= kLengthEpsMm;
  const double eps = flat ? eps_ : eps_ * kPlaneShare;
  // Points 2a+1, 2a+2, ..., 2e-1: odd ones the move middles, even ones the vertices.
  const uint32_t step = middles ? 1 : 2;
  for (uint32_t j = 2 * a + step; j < 2 * e; j += step) {
    const Vec2 u = ((j & 1) ? middle_[j / 2] : q(j / 2)) - q(a);
    const double w = u.squaredNorm() - eps * eps;
    if (w <= 0) continue;  // within the band of `a` itself
    const double P = w * inv_length - u.dot(c), Q = cross2(c, u);
    const double R2 = P * P + Q * Q;
    if (R2 <= eps * eps) continue;
    // The zero of sin(α + β), α = −β, taken in (−π/2, π/2], and the interval's edges
    // asin(ε / R) either side of it: as directions R and R² times too long (ordering by
    // pseudo-angle, and atan2, take directions of any length).
    const Vec2 zero = P > 0 || (P == 0 && Q <= 0) ? Vec2(P, -Q) : Vec2(-P, Q);
    const double cos_half = std::sqrt(R2 - eps * eps);
    if (!point(Turn::by(cos_half, -eps)(zero), Turn::by(cos_half, eps)(zero))) return false;
  }
  return true;
}

/// Directions (cos α, sin α) in (−π, π), ordered by their pseudo-angle turned half a turn.
static double start_order(const Vec2& d) { return pseudo_angle(-d.x(), -d.y()); }

std::pair<double, double> RunFitter::start_range(uint32_t a, uint32_t e) const {
  Vec2 lo(start_sweep_.c, -start_sweep_.s), hi(start_sweep_.c, start_sweep_.s);
  double lo_order = start_order(lo), hi_order = start_order(hi);
  const bool met = start_bounds(a, e, true, [&](const Vec2& low, const Vec2& high) {
    if (const double o = start_order(low); o > lo_order) {
      lo = low;
      lo_order = o;
    }
    if (const double o = start_order(high); o < hi_order) {
      hi = high;
      hi_order = o;
    }
    return lo_order <= hi_order;
  });
  if (!met) return {1, -1};
  return {std::atan2(lo.y(), lo.x()), std::atan2(hi.y(), hi.x())};
}

bool RunFitter::start_reaches(uint32_t a, uint32_t e, bool middles) const {
  // The starts kept, as pseudo-angle intervals inside the largest sweep: a point's starts
  // are an interval around its first zero and one around the other, half a turn (2 in
  // pseudo-angle) away, which may wrap past it (that part lies outside the sweep). Where
  // more than four pieces would be kept, the last two become the one that spans both: more
  // starts than reach, never fewer, so that false still shows that none reaches.
  constexpr size_t kPieces = 4;
  double from[kPieces], to[kPieces];
  size_t count = 1;
  const double first = start_order(Vec2(start_sweep_.c, -start_sweep_.s));
  const double last = start_order(Vec2(start_sweep_.c, start_sweep_.s));
  from[0] = first;
  to[0] = last;
  return start_bounds(a, e, middles, [&](const Vec2& low, const Vec2& high) {
    const double lo = start_order(low), hi = start_order(high);
    const double other_lo = lo < 2 ? lo + 2 : lo - 2, other_hi = hi < 2 ? hi + 2 : hi - 2;
    double own_from[3] = {lo, other_lo, first}, own_to[3] = {hi, other_hi, other_hi};
    size_t owned = 2;
    if (other_lo > other_hi) {  // wrapped: [other_lo, 4) and [0, other_hi]
      own_to[1] = last;
      owned = 3;
    }
    double next_from[kPieces], next_to[kPieces];
    size_t made = 0;
    for (size_t i = 0; i < count; ++i)
      for (size_t k = 0; k < owned; ++k) {
        const double f = std::max(from[i], own_from[k]), t = std::min(to[i], own_to[k]);
        if (f > t) continue;
        if (made < kPieces) {
          next_from[made] = f, next_to[made++] = t;
        } else {
          next_from[kPieces - 1] = std::min(next_from[kPieces - 1], f);
          next_to[kPieces - 1] = std::max(next_to[kPieces - 1], t);
        }
      }
    std::copy(next_from, next_from + made, from);
    std::copy(next_to, next_to + made, to);
    count = made;
    return count > 0;
  });
}

/// The input's own directions at `a` (input_tangents()), each also turned by 0.5°, 1°, 2°
/// and 4° either way; appended to `out`. The layered search's starts where the tangent is
/// free.
void RunFitter::fanned_input_tangents(uint32_t a, uint32_t limit, std::vector<Vec2>& out) const {
  input_tangents(a, limit, s_.inputs);
  for (const Vec2& T : s_.inputs) {
    out.push_back(T);
    for (const Turn& turn : fan_turns_) out.push_back(turn(T));
  }
}

/// The start at `a` whose arc over the first move ends heading along the second: where the
/// input turns at a + 1 (a slicer's infill between two corners, a short move into a long
/// one), the one start from which the second move follows as a line, tangent.
std::optional<Vec2> RunFitter::into_next(uint32_t a, uint32_t limit) const {
  if (a + 2 > limit) return std::nullopt;
  const Vec2 next = q(a + 2) - q(a + 1);
  if (next.norm() <= kLengthEpsMm) return std::nullopt;
  return reflected_end(a, next.normalized(), a + 1);
}

/// Tangent at p0 of the circle through p0, p1, p2, pointing towards p1.
std::optional<Vec2> RunFitter::circle_tangent(const Vec2& p0, const Vec2& p1, const Vec2& p2) {
  Vec2 a = p1 - p0, b = p2 - p0;
  double d = 2 * cross2(a, b);
  if (a.norm() <= kLengthEpsMm || b.norm() <= kLengthEpsMm) return std::nullopt;
  // In a line: along it, towards p1 (p2 may lie on either side).
  if (std::abs(d) <= 1e-12 * a.norm() * b.norm()) return Vec2(b.dot(a) < 0 ? -b.normalized() : b.normalized());
  Vec2 c((b.y() * a.squaredNorm() - a.y() * b.squaredNorm()) / d,
         (-b.x() * a.squaredNorm() + a.x() * b.squaredNorm()) / d);  // centre relative to p0
  Vec2 t = left_normal(-c).normalized();
  if (t.dot(a) < 0) t = -t;
  return t;
}

}  // namespace arcpress::fit_detail
