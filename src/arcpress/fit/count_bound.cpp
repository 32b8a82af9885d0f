// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/fit/count_bound.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "arcpress/fit/angle_ranges.hpp"
#include "arcpress/fit/run_fitter.hpp"  // the shares of the band and the angle the fitter keeps back

namespace arcpress {
namespace {

/// Directions modulo π (angles in [0, π)) as a union of closed intervals.
class DirectionSet {
 public:
  void reset() {
    set_.assign(1, {0.0, kPi});
  }
  bool empty() const { return set_.empty(); }
  /// Keeps the directions within `half` (rad) of `centre` (rad, any value) modulo π.
  void keep(double centre, double half) {
    if (half >= kPi / 2) return;
    double c = std::fmod(centre, kPi);
    if (c < 0) c += kPi;
    Interval allowed[2];
    int count = 0;
    if (c - half < 0) {
      allowed[count++] = {0.0, c + half};
      allowed[count++] = {c - half + kPi, kPi};
    } else if (c + half > kPi) {
      allowed[count++] = {0.0, c + half - kPi};
      allowed[count++] = {c - half, kPi};
    } else {
      allowed[count++] = {c - half, c + half};
    }
    next_.clear();
    for (const Interval& s : set_)
      for (int k = 0; k < count; ++k) {
        const double lo = std::max(s.lo, allowed[k].lo), hi = std::min(s.hi, allowed[k].hi);
        if (lo <= hi) next_.push_back({lo, hi});
      }
    set_.swap(next_);
  }

 private:
  struct Interval {
    double lo, hi;
  };
  std::vector<Interval> set_, next_;
};

using Range = AngleRange;

/// The (offset, curvature) points of a convex polygon: offsets (rad) of the start tangent
/// from a range's middle, curvatures (1/mm) of the circle leaving along it.
class Polygon {
 public:
  void box(double half_width_rad, double k_lo, double k_hi) {
    v_ = {{-half_width_rad, k_lo}, {half_width_rad, k_lo}, {half_width_rad, k_hi}, {-half_width_rad, k_hi}};
  }
  bool empty() const { return v_.size() < 3; }
  /// Keeps the points with a·offset + b·curvature <= c.
  void keep(double a, double b, double c) {
    tmp_.clear();
    const size_t n = v_.size();
    for (size_t s = 0; s < n; ++s) {
      const Vec2& p = v_[s];
      const Vec2& q = v_[(s + 1) % n];
      const double fp = a * p.x() + b * p.y() - c, fq = a * q.x() + b * q.y() - c;
      if (fp <= 0) tmp_.push_back(p);
      if ((fp < 0 && fq > 0) || (fp > 0 && fq < 0)) tmp_.push_back(p + (q - p) * (fp / (fp - fq)));
    }
    v_.swap(tmp_);
  }
  /// The smallest and largest offset.
  Range offsets() const {
    Range r{kPi, -kPi};
    for (const Vec2& p : v_) {
      r.lo = std::min(r.lo, p.x());
      r.hi = std::max(r.hi, p.x());
    }
    return r;
  }

 private:
  std::vector<Vec2> v_, tmp_;
};

/// Whether a primitive from vertex i must end before vertex j (> i): at vertex j - 1, when
/// that lies between them and is one of `ends`. (Called for j = i + 1, i + 2, ... in turn.)
bool ends_before(PrimitiveEnds ends, size_t i, size_t j) {
  return j > i + 1 && j - 1 < ends.size() && ends[j - 1];
}

}  // namespace

size_t min_primitive_count(std::span<const Vec2> pts, double band_mm, PrimitiveEnds ends) {
  const size_t n = pts.size() < 2 ? 0 : pts.size() - 1;  // moves
  if (n == 0) return 0;
  // The circles through vertex i and vertex j: by the left normal N (a unit vector, either
  // sign) at vertex i, the curvature is k = 2 d·N / |d|² (d from i to j). A vertex u (from i)
  // is within the band ε of such a circle when |k (|u|² − ε²) − 2 u·N| ≤ 2ε (exact, the full
  // circle), that is when |w·N| ≤ ε with w = d (|u|² − ε²) / |d|² − u: N lies within
  // asin(ε / |w|) of the direction square to w. k = 0 is the line through both.
  const double eps = band_mm;
  std::vector<size_t> best(n + 1, std::numeric_limits<size_t>::max());
  best[0] = 0;
  DirectionSet normals;
  // The points tested against a primitive from vertex i to vertex j (> i + 1), by index: 2m is
  // vertex m (i < m < j), 2m + 1 the middle of the move from vertex m (i <= m < j). A move's
  // middle lies on the input path the primitive replaces, so within the band of it, and the
  // circle is nearer than the arc: without it, the circles through a long move's two ends
  // would include those that bow far off its middle.
  auto point = [&](size_t p) { return p % 2 ? Vec2(0.5 * (pts[p / 2] + pts[p / 2 + 1])) : pts[p / 2]; };
  for (size_t i = 0; i < n; ++i) {
    size_t killer = 0;  // the point that ended the last test from i: tried first
    for (size_t j = i + 1; j <= n && !ends_before(ends, i, j); ++j) {
      if (best[i] + 1 >= best[j]) continue;
      const Vec2 d = pts[j] - pts[i];
      const double dd = d.squaredNorm();
      bool ok = true;
      if (j > i + 1 && dd > 0) {
        normals.reset();
        auto holds = [&](size_t p) {
          const Vec2 u = point(p) - pts[i];
          const Vec2 w = d * ((u.squaredNorm() - eps * eps) / dd) - u;
          const double len = w.norm();
          if (len <= eps) return true;
          normals.keep(std::atan2(w.y(), w.x()) + kPi / 2, std::asin(eps / len));
          return !normals.empty();
        };
        if (killer > 2 * i && killer < 2 * j) ok = holds(killer);
        for (size_t p = 2 * j - 1; ok && p > 2 * i; --p) {
          if (p == killer) continue;
          if (!holds(p)) {
            ok = false;
            killer = p;
          }
        }
      }
      // (Back at vertex i, any circle through it is allowed: a bound may allow too much.)
      if (ok) best[j] = best[i] + 1;
    }
  }
  return best[n];
}

size_t min_g1_primitive_count(std::span<const Vec2> pts, double band_mm, double g1_angle_deg,
                              const EndTangents& joins, PrimitiveEnds ends) {
  const size_t n = pts.size() < 2 ? 0 : pts.size() - 1;  // moves
  if (n == 0) return 0;
  const double eps = band_mm, g1 = deg_to_rad(g1_angle_deg);
  const double half = deg_to_rad(0.125);  // a state's tangent range is at most twice this wide
  // The circle leaving vertex i along the tangent at angle θ0 + δ, with curvature k: a vertex
  // u (from i) is within ε of it when |k w − 2 u·N| <= 2ε, w = |u|² − ε², N its left normal.
  // u·N = (u·N0) cos δ − (u·T0) sin δ differs from the line (u·N0) − (u·T0) δ by at most
  // |u| (δ²/2 + |δ|³/6): with that allowance the condition bounds (δ, k) by two half-planes.
  const double bend = half * half / 2 + half * half * half / 6;
  const double slack = 1e-9 * eps;  // rounding, on the side of keeping
  // A vertex's own direction: the angles at it are kept near it (no wrap-around).
  auto reference = [&](size_t v) {
    const Vec2 d = pts[std::min(v + 1, n)] - pts[v > 0 ? v - 1 : 0];
    return std::atan2(d.y(), d.x());
  };
  struct State {
    size_t v;
    double mid;    // rad: the tangents mid ± width, the piece of the range that arrived
    double width;  // rad, at most half (a state reaching past what arrived keeps chains that are not there)
  };
  std::vector<std::vector<Range>> taken(n + 1), arriving(n + 1);
  std::vector<size_t> touched;
  std::vector<State> layer, next;
  auto add_states = [&](size_t v, const std::vector<Range>& ranges) {
    for (const Range& r : ranges) {
      const int pieces = std::max(1, int(std::ceil((r.hi - r.lo) / (2 * half))));
      const double step = (r.hi - r.lo) / pieces;
      for (int k = 0; k < pieces; ++k) next.push_back({v, r.lo + (k + 0.5) * step, step / 2});
    }
  };
  {
    const double ref = reference(0);
    if (joins.start) {
      const double t = near_angle(std::atan2(joins.start->y(), joins.start->x()), ref);
      add_states(0, take_new({{t - g1, t + g1}}, taken[0]));
    } else {
      add_states(0, take_new({{ref - kPi, ref + kPi}}, taken[0]));
    }
  }
  // Whether the last primitive, arriving along tangents a .. b (rad), joins the end tangent.
  const bool end_fixed = joins.end.has_value();
  const double end_rad = end_fixed ? std::atan2(joins.end->y(), joins.end->x()) : 0.0;
  auto joins_end = [&](double a, double b) {
    if (!end_fixed) return true;
    const double e = near_angle(end_rad, (a + b) / 2);
    return e >= a - g1 && e <= b + g1;
  };
  // Circles turning left (k >= 0) and right (k <= 0) apart: a move inside the arc may not cut
  // more than ε into the circle, and its middle, from `a` at u, bounds k from one side only:
  // k w - 2 u·N >= -2ε turning left, <= 2ε turning right (from |u - N/k| >= 1/|k| - ε).
  std::array<Polygon, 2> sides, at_end;
  for (size_t count = 1; !next.empty(); ++count) {
    layer.swap(next);
    next.clear();
    for (const State& st : layer) {
      const size_t i = st.v;
      const Vec2 T0(std::cos(st.mid), std::sin(st.mid)), N0 = left_normal(T0);
      sides[0].box(st.width, 0, 1e9);
      sides[1].box(st.width, -1e9, 0);
      // The half-planes a point u (from vertex i) puts on (δ, k): both sides of the band, or
      // (a move's middle) the inner side only.
      auto bound = [&](Polygon& poly, const Vec2& u, bool outer, bool inner) {
        const double w = u.squaredNorm() - eps * eps;
        if (w <= 0) return;  // within ε of vertex i, which is on every such circle
        const double bn = u.dot(N0), bt = u.dot(T0), allow = 2 * eps + 2 * u.norm() * bend + slack;
        if (outer) poly.keep(2 * bt, w, allow + 2 * bn);
        if (inner) poly.keep(-2 * bt, -w, allow - 2 * bn);
      };
      auto middle = [&](size_t m) { return Vec2(0.5 * (pts[m] + pts[m + 1]) - pts[i]); };
      for (size_t j = i + 1; j <= n && !ends_before(ends, i, j); ++j) {
        if (j > i + 1) {  // vertex j - 1 is now between the ends, and the move before it
          const Vec2 u = pts[j - 1] - pts[i];
          const double bn = u.dot(N0), bt = u.dot(T0), ul = u.norm();
          for (int side = 0; side < 2; ++side) {
            bound(sides[side], u, true, true);
            bound(sides[side], middle(j - 2), side == 1, side == 0);
            // An arc of at most half a turn lies ahead of its start tangent, and the vertex
            // within ε of it: u·T >= -ε, u·T = (u·T0) cos δ + (u·N0) sin δ.
            sides[side].keep(-bn, 0, bt + eps + ul * bend + slack);
          }
          if (sides[0].empty() && sides[1].empty()) break;
        }
        const Vec2 d = pts[j] - pts[i];
        const double dd = d.squaredNorm();
        if (dd == 0) {  // back at vertex i: any circle through it, leaving any way
          if (j == n) return count;
          arriving[j].push_back({reference(j) - kPi, reference(j) + kPi});
          touched.push_back(j);
          continue;
        }
        // The circle through vertex j, k |d|² = 2 d·N, and at most half a turn (T·d >= 0).
        const double chord = std::atan2(d.y(), d.x());
        const double rel = near_angle(chord - st.mid, 0);
        const double lo = std::max(-st.width, rel - kPi / 2), hi = std::min(st.width, rel + kPi / 2);
        if (lo > hi) continue;
        const double dn = d.dot(N0), dt = d.dot(T0), allow = 2 * std::sqrt(dd) * bend + slack;
        Range off{kPi, -kPi};
        for (int side = 0; side < 2; ++side) {
          Polygon& end = at_end[side];
          end = sides[side];
          end.keep(2 * dt, dd, allow + 2 * dn);
          end.keep(-2 * dt, -dd, allow - 2 * dn);
          end.keep(1, 0, hi + 1e-15);
          end.keep(-1, 0, -lo + 1e-15);
          bound(end, middle(j - 1), side == 1, side == 0);
          if (j == i + 1) {
            // One move: the arc stays within ε of it, so it bulges by at most ε off its
            // chord, which bounds its curvature: |k| <= 8ε / (|d|² + 4ε²).
            const double k_max = 8 * eps / (dd + 4 * eps * eps) * (1 + 1e-9);
            end.keep(0, 1, k_max);
            end.keep(0, -1, k_max);
          }
          if (end.empty()) continue;
          const Range r = end.offsets();
          off = {std::min(off.lo, r.lo), std::max(off.hi, r.hi)};
        }
        if (off.lo > off.hi) continue;
        // The arc ends along its start tangent mirrored in the chord; the next may turn by g1.
        const double ref = reference(j);
        const double a = near_angle(2 * chord - st.mid - off.hi, ref), b = a + (off.hi - off.lo);
        if (j == n) {
          if (joins_end(a, b)) return count;
          continue;
        }
        arriving[j].push_back({a - g1, b + g1});
        touched.push_back(j);
      }
    }
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    for (size_t v : touched) {
      add_states(v, take_new(std::move(arriving[v]), taken[v]));
      arriving[v].clear();
    }
    touched.clear();
  }
  return 0;
}

size_t min_g1_primitive_count_as_fitted(std::span<const Vec2> pts, const FitOptions& o, const EndTangents& joins,
                                        PrimitiveEnds ends) {
  return min_g1_primitive_count(pts, o.tolerance_mm * (1 - rounding_reserve_share(o)),
                                o.g1_angle_deg * fit_detail::kJointShare, joins, ends);
}

size_t min_primitive_count_as_fitted(std::span<const Vec2> pts, const FitOptions& o, PrimitiveEnds ends) {
  return min_primitive_count(pts, o.tolerance_mm * (1 - rounding_reserve_share(o)), ends);
}

}  // namespace arcpress
