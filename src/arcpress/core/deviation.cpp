// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/core/deviation.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <vector>

namespace arcpress {

double ArcGeom::sweep_of(const Vec3& start, const Vec3& end, const Vec2& center, bool ccw) {
  Vec2 s(start.x() - center.x(), start.y() - center.y());
  Vec2 e(end.x() - center.x(), end.y() - center.y());
  double sweep = std::atan2(cross2(s, e), s.dot(e));  // (-π, π]
  if (ccw && sweep <= 0) sweep += 2 * kPi;
  if (!ccw && sweep >= 0) sweep -= 2 * kPi;
  return sweep;
}

ArcGeom ArcGeom::through(const Vec3& start, const Vec3& end, const Vec2& center, bool ccw) {
  ArcGeom g;
  g.center = center;
  Vec2 s(start.x() - center.x(), start.y() - center.y());
  g.radius_mm = s.norm();
  g.start_angle = std::atan2(s.y(), s.x());
  g.sweep = sweep_of(start, end, center, ccw);
  g.h0 = start.z();
  g.h1 = end.z();
  return g;
}

bool is_corner(const Vec3& a, const Vec3& b, const Vec3& c, double band_mm, double corner_angle_deg) {
  Vec3 d1 = b - a, d2 = c - b;
  double l1 = d1.norm(), l2 = d2.norm();
  if (l1 <= kLengthEpsMm || l2 <= kLengthEpsMm) return true;
  double turn = std::acos(std::clamp(d1.dot(d2) / (l1 * l2), -1.0, 1.0));
  if (turn > deg_to_rad(corner_angle_deg)) return true;
  return turn * l1 * l2 / (4 * (l1 + l2)) > band_mm;
}

namespace {
/// Signed turn at q of the path p -> q -> r in the first two coordinates, radians (> 0 left).
double signed_turn(const Vec3& p, const Vec3& q, const Vec3& r) {
  Vec2 u(q.x() - p.x(), q.y() - p.y()), v(r.x() - q.x(), r.y() - q.y());
  return std::atan2(cross2(u, v), u.dot(v));
}
}  // namespace

bool is_corner_beside_corner(const Vec3* z, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3* d,
                             bool a_is_corner, bool c_is_corner, double band_mm) {
  if (a_is_corner == c_is_corner) return false;  // no corner near, or both: free on both sides
  const double turn = signed_turn(a, b, c);
  if (a_is_corner) {
    double excess = turn - (d ? signed_turn(b, c, *d) : 0.0);
    if (std::abs(excess) * (b - a).norm() / 4 > band_mm) return true;
  }
  if (c_is_corner) {
    double excess = turn - (z ? signed_turn(*z, a, b) : 0.0);
    if (std::abs(excess) * (c - b).norm() / 4 > band_mm) return true;
  }
  return false;
}

Vec3 nearest_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double len2 = d.squaredNorm();
  if (len2 <= kLengthEpsMm * kLengthEpsMm) return a;
  // From the nearer end, so that an end is returned exactly (from the other, a + (b - a)
  // can lose b entirely where a is far bigger: a segment from 1e100 to 1 ending at 0).
  const double t = std::clamp((p - a).dot(d) / len2, 0.0, 1.0);
  return t <= 0.5 ? Vec3(a + t * d) : Vec3(b - (1 - t) * d);
}

double ProgressWindow::least_gap(double v0, double v1, double target) const {
  double least = HUGE_VAL;
  for (int k = 0; k < count; ++k) {
    const double x = v0 + lo[k] * (v1 - v0), y = v0 + hi[k] * (v1 - v0);
    const double gap = target < std::min(x, y) ? std::min(x, y) - target : target > std::max(x, y) ? target - std::max(x, y) : 0.0;
    least = std::min(least, gap);
  }
  return least;
}

ProgressWindow line_progress_near(const Vec3& p, const Vec3& a, const Vec3& b, double slack_mm) {
  ProgressWindow w;
  const Vec3 d = b - a;
  const double len2 = d.squaredNorm();
  if (len2 <= kLengthEpsMm * kLengthEpsMm) return w;
  const double t = std::clamp((p - a).dot(d) / len2, 0.0, 1.0), half = slack_mm / std::sqrt(len2);
  w.lo[0] = std::max(t - half, 0.0);
  w.hi[0] = std::min(t + half, 1.0);
  return w;
}

ProgressWindow arc_progress_near(const Vec3& p, const ArcGeom& arc, double slack_mm) {
  ProgressWindow w;
  const double turn = std::abs(arc.sweep);
  if (turn <= 0) return w;
  const double dx = p.x() - arc.center.x(), dy = p.y() - arc.center.y();
  const double d = std::hypot(dx, dy);
  if (d <= slack_mm) {  // every point of the arc as near, for all that is known of the centre
    w.hi[0] = 1;
    return w;
  }
  // p's direction as the turn from the start, the arc's way round, in [0, 2π), and the
  // turn that moving p or the centre by `slack_mm` can make of it.
  double at = std::atan2(dy, dx) - arc.start_angle;
  if (arc.sweep < 0) at = -at;
  at = std::fmod(at, 2 * kPi);
  if (at < 0) at += 2 * kPi;
  const double half = std::asin(slack_mm / d);
  w.count = 0;
  for (const double centre : {at, at - 2 * kPi}) {
    const double lo = std::max(centre - half, 0.0), hi = std::min(centre + half, turn);
    if (lo > hi) continue;
    w.lo[w.count] = lo / turn;
    w.hi[w.count] = hi / turn;
    ++w.count;
  }
  if (w.count == 0) {  // past either end: the nearer end
    w.lo[0] = w.hi[0] = at - turn < 2 * kPi - at ? 1.0 : 0.0;
    w.count = 1;
  }
  return w;
}

double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  return (p - nearest_on_segment(p, a, b)).norm();
}

Deviation line_deviation(std::span<const Vec3> pts, double stop_above_mm) {
  Deviation dev;
  const Vec3& a = pts.front();
  const Vec3& b = pts.back();
  Vec3 d = b - a;
  double len2 = d.squaredNorm();
  double last_t = 0;
  for (size_t m = 1; m + 1 < pts.size(); ++m) {
    double dist = point_segment_distance(pts[m], a, b);
    if (dist > dev.max_mm) {
      dev.max_mm = dist;
      dev.at_index = m;
      if (dist > stop_above_mm) return dev;
    }
    // Vertices must advance along the chord, or a stretch of the chord could be far from
    // every input segment (a reversal inside the band).
    double t = len2 > 0 ? (pts[m] - a).dot(d) / len2 : 0;
    if (t < last_t - 1e-12) dev.ordered = false;
    last_t = std::max(last_t, t);
  }
  // The input segments are within max(vertex distance) of the chord (convexity), and with
  // ordered vertices every chord point is within that distance of some input segment.
  return dev;
}

namespace {

/// A segment or arc piece whose bound is not above this cannot raise the maximum found so
/// far, nor (below a finite stop) reach the stop: it need not be measured.
double unmeasured_below(const Deviation& dev, double stop_above_mm) {
  return stop_above_mm < HUGE_VAL ? std::max(dev.max_mm, stop_above_mm) : dev.max_mm;
}

/// arc_deviation() for the common case of a flat arc and a polyline in its plane, without
/// trigonometry: angles along the arc are pseudo-angles in the arc's own frame, and the arc
/// points measured (at the vertices' angles, piece middles, and where the arc runs parallel
/// to a segment) are built from unit vectors. The same measure as the general code.
Deviation planar_arc_deviation(std::span<const Vec3> pts, const ArcGeom& arc, double stop_above_mm) {
  Deviation dev;
  const double r = arc.radius_mm, z = arc.h0;
  const Vec2 c = arc.center;
  const size_t n = pts.size();
  auto rel = [&](size_t m) { return Vec2(pts[m].x() - c.x(), pts[m].y() - c.y()); };
  const Vec2 s_hat = rel(0).normalized();
  const double dir = arc.sweep >= 0 ? 1.0 : -1.0;
  // Pseudo-angle from the start, in the arc's direction.
  auto along = [&](const Vec2& v) { return pseudo_angle(v.dot(s_hat), dir * cross2(s_hat, v)); };
  const double total = std::abs(arc.sweep) >= 2 * kPi - 1e-9 ? 4.0 : along(rel(n - 1));
  auto note = [&](double d, size_t m) {
    if (d > dev.max_mm) {
      dev.max_mm = d;
      dev.at_index = m;
    }
  };
  // Scratch kept between calls: the fitter measures many short candidates.
  thread_local std::vector<double> phi, radial;
  thread_local std::vector<Vec2> unit;
  phi.resize(n);
  radial.resize(n);
  unit.resize(n);
  for (size_t m = 0; m < n; ++m) {
    Vec2 v = rel(m);
    double len = v.norm();
    unit[m] = len > 0 ? Vec2(v * (1 / len)) : s_hat;
    radial[m] = std::abs(len - r);
    // No point of the arc is nearer a vertex than the full circle is: a vertex off the circle
    // by more than the stop fails the candidate before anything else is measured.
    if (radial[m] > stop_above_mm && m > 0 && m + 1 < n) {
      dev.max_mm = radial[m];
      dev.at_index = m;
      return dev;
    }
    double a = m == 0 ? 0.0 : m + 1 == n ? total : along(v);
    // A vertex just behind the start (within rounding) reads as almost a full turn.
    if (a > total && a > 4 - 1e-9) a = 0;
    phi[m] = a;
    if (m > 0 && phi[m] < phi[m - 1] - 1e-12) {
      dev.ordered = false;
      if (stop_above_mm < HUGE_VAL) return dev;  // (under a finite stop, the first out of order ends it)
    }
  }
  // A piece between two vertices of half a turn or more has no middle from unit vectors.
  for (size_t m = 0; m + 1 < n; ++m)
    if (phi[m + 1] - phi[m] >= 2) return arc_deviation_by_angles(pts, arc, stop_above_mm);
  unit[0] = s_hat;
  // Input vertices to the arc.
  for (size_t m = 1; m + 1 < n; ++m) {
    note(phi[m] <= total ? radial[m] : std::min((pts[m] - pts.front()).norm(), (pts[m] - pts.back()).norm()), m);
    if (dev.max_mm > stop_above_mm) return dev;
  }
  // Input segments bulge towards the centre: the point of a chord nearest the centre.
  for (size_t m = 0; m + 1 < n; ++m) {
    Vec2 a(pts[m].x(), pts[m].y()), ab = Vec2(pts[m + 1].x(), pts[m + 1].y()) - a;
    double len2 = ab.squaredNorm();
    if (len2 <= 0) continue;
    double t = (c - a).dot(ab) / len2;
    if (t <= 0 || t >= 1) continue;
    note(std::max(r - (a + t * ab - c).norm(), 0.0), m);
    if (dev.max_mm > stop_above_mm) return dev;
  }
  // Arc to input: each piece of the arc between two vertices' angles against that segment.
  if (!dev.ordered || arc.sweep == 0) return dev;
  auto on_arc = [&](const Vec2& u) { return Vec3(c.x() + r * u.x(), c.y() + r * u.y(), z); };
  for (size_t m = 0; m + 1 < n; ++m) {
    const Vec2 &u0 = unit[m], &u1 = unit[m + 1];
    {
      // Cheap bound first: the piece is within its sagitta of its own chord, and that chord
      // within the vertices' radial distances of the input segment.
      // Below a finite stop, a piece that cannot reach it is not measured either.
      double cos_half = std::sqrt(std::max(0.0, 0.5 * (1 + u0.dot(u1))));
      if (r * (1 - cos_half) + std::max(radial[m], radial[m + 1]) <= unmeasured_below(dev, stop_above_mm)) continue;
      Vec2 mid = u0 + u1;
      Vec2 cand[4] = {u0, u1, mid.squaredNorm() > 0 ? Vec2(mid.normalized()) : u0, Vec2(0, 0)};
      int count = 3;
      Vec2 ab(pts[m + 1].x() - pts[m].x(), pts[m + 1].y() - pts[m].y());
      if (ab.squaredNorm() > 0) {
        // The arc point whose radius is perpendicular to the segment, if inside the piece.
        Vec2 nrm = left_normal(ab.normalized());
        for (double sgn : {1.0, -1.0}) {
          double a = along(sgn * nrm);
          if (a > phi[m] && a < phi[m + 1]) cand[count++] = sgn * nrm;
        }
      }
      for (int k = 0; k < count; ++k) note(point_segment_distance(on_arc(cand[k]), pts[m], pts[m + 1]), m);
    }
    if (dev.max_mm > stop_above_mm) return dev;
  }
  return dev;
}

}  // namespace

Deviation arc_deviation(std::span<const Vec3> pts, const ArcGeom& arc, double stop_above_mm) {
  bool planar = arc.h0 == arc.h1 && pts.size() >= 2;
  for (const Vec3& p : pts) planar = planar && p.z() == arc.h0;
  if (planar) return planar_arc_deviation(pts, arc, stop_above_mm);
  return arc_deviation_by_angles(pts, arc, stop_above_mm);
}

namespace {

/// How close the measure off the arc's plane comes to the largest gap (mm).
constexpr double kOffPlaneSlackMm = 1e-9;
/// Stretches one such measure may halve; past them the bound that is left stands for the
/// gap (never less than the true one).
constexpr int kOffPlaneSplits = 400;

/// The largest |V(s)| for s in [at.front(), at.back()] where it could exceed `floor`,
/// within kOffPlaneSlackMm (below `floor`: some value not above it), for a gap V between
/// two points moving along a segment and an arc. `gap(s)` gives |V(s)| and |V'(s)|; |V''|
/// is at most `bend`. Taken at the points `at` (ascending), then each stretch is measured at
/// its middle c and halved while its bound exceeds both `floor` and the largest gap found
/// by more than the slack. On a stretch of width w, |V'| <= |V'(c)| + bend·w/2 =: L, so on
/// either half |V| is at most (the larger end value + |V(c)| + L·w/2) / 2, and |V|², whose
/// second derivative 2|V'|² + 2V·V'' is at most 2L² + 2·that·bend, at most the largest
/// end value squared + (2L² + 2·that·bend)·(w/2)²/8: the bound is the smaller.
template <class Gap>
double largest_gap(std::span<const double> at, double bend, double floor, Gap&& gap) {
  struct Stretch {
    double x, y, fx, fy;
  };
  thread_local std::vector<Stretch> todo;
  todo.clear();
  double fx = gap(at[0]).first, best = fx;
  for (size_t i = 1; i < at.size(); ++i) {
    const double fy = gap(at[i]).first;
    best = std::max(best, fy);
    if (at[i] > at[i - 1]) todo.push_back({at[i - 1], at[i], fx, fy});
    fx = fy;
  }
  // A stretch's gap at its middle, and its bound.
  auto measure = [&](const Stretch& st) {
    const double w = st.y - st.x;
    const auto [fc, slope] = gap(0.5 * (st.x + st.y));
    const double L = slope + bend * w / 2, ends = std::max(st.fx, st.fy);
    const double lip = 0.5 * (ends + fc + L * w / 2);
    const double top = std::max(ends, fc);
    return std::pair(fc, std::min(lip, std::sqrt(top * top + (2 * L * L + 2 * lip * bend) * w * w / 32)));
  };
  int splits = 0;
  while (!todo.empty()) {
    const Stretch st = todo.back();
    todo.pop_back();
    const auto [fc, bound] = measure(st);
    best = std::max(best, fc);
    if (bound <= std::max(floor, best) + kOffPlaneSlackMm) continue;
    if (++splits > kOffPlaneSplits) {  // (reached on none of the specification's cases or corpus files)
      best = std::max(best, bound);
      for (const Stretch& o : todo) best = std::max(best, measure(o).second);
      break;
    }
    const double c = 0.5 * (st.x + st.y);
    todo.push_back({st.x, c, st.fx, fc});
    todo.push_back({c, st.y, fc, st.fy});
  }
  return best;
}

}  // namespace

Deviation arc_deviation_by_angles(std::span<const Vec3> pts, const ArcGeom& arc, double stop_above_mm) {
  Deviation dev;
  const double r = arc.radius_mm;
  const double dir = arc.sweep >= 0 ? 1.0 : -1.0;
  const double total = std::abs(arc.sweep);
  // The angle of direction (x, y) from the centre, from the start in the arc's direction, [0, 2π).
  auto angle_of = [&](double x, double y) {
    double a = (std::atan2(y, x) - arc.start_angle) * dir;
    // (Both angles lie in [-π, π]: the remainder is needed only at ±2π.)
    if (std::abs(a) >= 2 * kPi) a = std::fmod(a, 2 * kPi);
    if (a < 0) a += 2 * kPi;
    return a;
  };
  auto angle_along = [&](const Vec3& p) { return angle_of(p.x() - arc.center.x(), p.y() - arc.center.y()); };
  auto note = [&](double d, size_t m) {
    if (d > dev.max_mm) {
      dev.max_mm = d;
      dev.at_index = m;
    }
  };
  const size_t n = pts.size();
  // Scratch kept between calls: the fitter measures many candidates.
  thread_local std::vector<double> phi, radial, off;
  phi.resize(n);
  phi[0] = 0;
  phi[n - 1] = total;
  // (Under a finite stop, the first vertex out of order ends the measure.)
  for (size_t m = 1; m < n; ++m) {
    if (m + 1 < n) {
      double a = angle_along(pts[m]);
      // A vertex just behind the start (within rounding) reads as almost 2π.
      if (a > total && a > 2 * kPi - 1e-9) a = 0;
      phi[m] = a;
    }
    if (phi[m] < phi[m - 1] - 1e-12) {
      dev.ordered = false;
      if (stop_above_mm < HUGE_VAL) return dev;
    }
  }
  // Input vertices to the arc (helical height interpolated by angle).
  const bool flat = arc.h0 == arc.h1;
  radial.resize(n);  // |distance to the centre - r| of each vertex
  for (size_t m = 0; m < n; ++m) {
    Vec2 rel(pts[m].x() - arc.center.x(), pts[m].y() - arc.center.y());
    radial[m] = std::abs(rel.norm() - r);
  }
  // Each vertex within the sweep: its distance to the arc's point at its angle, kept for the
  // bounds on the segments and pieces below.
  off.resize(n);
  auto vertex_gap = [&](size_t m) {
    // (The arc's height there as point_at(phi[m] / total) gives it, without its cosine and sine.)
    const double t = total > 0 ? phi[m] / total : 0;
    const double dz = pts[m].z() - (flat ? arc.h0 : arc.h0 + (arc.h1 - arc.h0) * t);
    return off[m] = std::sqrt(radial[m] * radial[m] + dz * dz);
  };
  for (size_t m = 1; m + 1 < n; ++m) {
    const Vec3& p = pts[m];
    note(phi[m] <= total ? vertex_gap(m) : std::min((p - pts.front()).norm(), (p - pts.back()).norm()), m);
    if (dev.max_mm > stop_above_mm) return dev;
  }
  vertex_gap(0);
  vertex_gap(n - 1);
  const bool advancing = dev.ordered && total > 0;
  const double rise = total > 0 ? (arc.h1 - arc.h0) / total : 0.0;  // mm per radian
  // Whether segment m and its vertices lie in the arc's plane.
  auto in_plane = [&](size_t m) { return flat && pts[m].z() == arc.h0 && pts[m + 1].z() == arc.h0; };
  // Input segments to the arc. One in the arc's plane is farthest from the circle at its
  // point nearest the centre (a chord bulges towards the centre). Off the plane (a helix, or
  // input above or below a flat arc), points of the segment and of the arc's piece between
  // its vertices' angles are matched by share, and the largest gap between them, which
  // bounds the distance both ways, is the measure of both.
  for (size_t m = 0; m + 1 < n; ++m) {
    Vec2 a(pts[m].x(), pts[m].y()), b(pts[m + 1].x(), pts[m + 1].y());
    Vec2 ab = b - a;
    double len2 = ab.squaredNorm();
    const bool planar = in_plane(m);
    if (!planar && advancing) {
      // Its point at share s lies no farther from the arc than from the arc's point at angle
      // phi[m] + s·Δ, and that point of the arc no farther from the segment (at the
      // vertices, the gap is each one's distance to the arc's point at its angle, as above).
      // Cheap bound first: the chord between the arc's points at the vertices' angles, at
      // share s, lies within the larger of the vertices' gaps of the segment's point, and
      // within r·((1 - cos(Δ/2)) + (Δ/2 - sin(Δ/2))) of the arc's point in the plane, at its
      // height (both heights run linearly), across and along the chord.
      const double delta = phi[m + 1] - phi[m], half = 0.5 * delta;
      const double reach = r * ((1 - std::cos(half)) + (half - std::sin(half))) + std::max(off[m], off[m + 1]);
      const double floor = unmeasured_below(dev, stop_above_mm);
      if (reach <= floor) continue;
      const Vec3 A = pts[m], AB = pts[m + 1] - pts[m];
      double at[4] = {0.0, 0.5, 1.0, 1.0};
      size_t count = 3;
      const double t = len2 > 0 ? (arc.center - a).dot(ab) / len2 : 0.0;
      if (t > 0 && t < 1) at[count++] = t;
      std::sort(at, at + count);
      // V(s) = A + s·AB - H(phi[m] + s·Δ): V' = AB - H'·Δ, |V''| = |H''|·Δ² = r·Δ².
      auto gap = [&](double s) {
        const double angle = arc.start_angle + dir * (phi[m] + s * delta);
        const double c = std::cos(angle), sn = std::sin(angle);
        const Vec3 h(arc.center.x() + r * c, arc.center.y() + r * sn, arc.h0 + rise * (phi[m] + s * delta));
        const Vec3 dh(-r * sn * dir, r * c * dir, rise);
        return std::pair((A + s * AB - h).norm(), (AB - delta * dh).norm());
      };
      note(largest_gap(std::span<const double>(at, count), r * delta * delta, floor, gap), m);
      if (dev.max_mm > stop_above_mm) return dev;
      continue;
    }
    if (len2 <= 0) continue;
    double t = (arc.center - a).dot(ab) / len2;
    if (t <= 0 || t >= 1) continue;
    Vec2 foot = a + t * ab;
    double inward = std::max(r - (foot - arc.center).norm(), 0.0);
    double dz = 0;  // heights at the foot: both linear, so compare the interpolations
    if (!planar) {
      double ph = phi[m] + t * (phi[m + 1] - phi[m]);
      double hz = pts[m].z() + t * (pts[m + 1].z() - pts[m].z());
      dz = hz - arc.point_at(total > 0 ? ph / total : 0).z();
    }
    note(std::sqrt(inward * inward + dz * dz), m);
    if (dev.max_mm > stop_above_mm) return dev;
  }
  // Arc to input: each piece of the arc between two vertices' angles against that segment,
  // at the piece ends, its middle, and where the arc runs parallel to the segment.
  if (advancing) {
    for (size_t m = 0; m + 1 < n; ++m) {
      // (Off the plane, the gaps measured with the segments bound these distances.)
      if (!in_plane(m)) continue;
      double p0 = phi[m], p1 = phi[m + 1];
      // Cheap bound first: the arc piece lies within its sagitta of its own chord, and that
      // chord within its end vertices' radial distances of the input segment. Only a piece
      // whose bound could raise the maximum (or reach the stop) is measured exactly.
      const double skip_at = unmeasured_below(dev, stop_above_mm);
      double sagitta = r * (1 - std::cos(0.5 * (p1 - p0)));
      if (sagitta + std::max(radial[m], radial[m + 1]) <= skip_at) continue;
      double cand[4] = {p0, p1, 0.5 * (p0 + p1), -1};
      Vec2 ab(pts[m + 1].x() - pts[m].x(), pts[m + 1].y() - pts[m].y());
      if (ab.squaredNorm() > 0) {
        // Arc point whose radius is perpendicular to the segment, on the far side.
        Vec2 nrm = left_normal(ab.normalized());
        for (double s : {1.0, -1.0}) {
          const double a = angle_of(s * nrm.x(), s * nrm.y());
          if (a > p0 && a < p1) cand[3] = a;
        }
      }
      for (double c : cand) {
        if (c < 0) continue;
        Vec3 q = arc.point_at(c / total);
        note(point_segment_distance(q, pts[m], pts[m + 1]), m);
      }
      if (dev.max_mm > stop_above_mm) return dev;
    }
  }
  return dev;
}

std::optional<double> chords_deviation_bound(std::span<const Vec3> pts, const ArcGeom& arc, std::span<const Vec2> ends,
                                             double stop_above_mm) {
  const double turn = std::abs(arc.sweep);
  if (pts.size() < 2 || turn >= 2 * kPi - 1e-9 || turn <= 0 || arc.h0 != arc.h1) return std::nullopt;
  for (const Vec3& p : pts)
    if (std::abs(p.z() - arc.h0) > kLengthEpsMm) return std::nullopt;
  const Vec2 c = arc.center;
  const double sign = arc.sweep >= 0 ? 1 : -1;
  // Places along the turn are pseudo-angles from the start in the arc's direction, as a
  // share of the whole turn's: ordered as the angles are, with no trigonometry per point.
  const Vec2 s_hat(std::cos(arc.start_angle), std::sin(arc.start_angle));
  const double whole = pseudo_angle_of(turn);
  // (Kept from call to call on the thread: the fitter asks this of many candidates.)
  thread_local std::vector<double> t, u;
  // Each vertex's and each chord end's place, in order along the turn; the first and the
  // last at the turn's ends.
  auto places = [&](size_t n, auto point, std::vector<double>& at) {
    at.assign(n + 1, 0.0);
    at[n] = 1;
    for (size_t j = 1; j < n; ++j) {
      const Vec2 v = point(j) - c;
      if (v.x() == 0 && v.y() == 0) return false;
      at[j] = pseudo_angle(v.dot(s_hat), sign * cross2(s_hat, v)) / whole;
      if (at[j] < at[j - 1] - 1e-12 || at[j] > 1 + 1e-12) return false;
      at[j] = std::clamp(at[j], at[j - 1], 1.0);
    }
    return true;
  };
  auto flat = [](const Vec3& p) { return Vec2(p.x(), p.y()); };
  const size_t m = pts.size() - 1, segments = ends.size() + 1;
  auto vertex = [&](size_t j) { return flat(pts[j]); };
  // Chord end k: 0 and `segments` are the arc's ends, the polyline's.
  auto chord_end = [&](size_t k) {
    if (k == 0) return flat(pts.front());
    if (k >= segments) return flat(pts.back());
    return ends[k - 1];
  };
  if (!places(m, vertex, t) || !places(segments, chord_end, u)) return std::nullopt;
  // Where the ray from the centre through `p` meets the segment a-b (its nearer end where it
  // misses); the ray's length does not matter.
  auto on_ray = [&](const Vec2& a, const Vec2& b, const Vec2& p) {
    const Vec2 d = b - a, ca = c - a, r = p - c;
    const double den = d.x() * r.y() - d.y() * r.x();
    if (std::abs(den) <= 1e-300) return a;
    const double mu = std::clamp((ca.x() * r.y() - ca.y() * r.x()) / den, 0.0, 1.0);
    return Vec2(a + mu * d);
  };
  auto distance = [](const Vec2& p, const Vec2& a, const Vec2& b) {
    const Vec2 d = b - a;
    const double len2 = d.squaredNorm();
    const double mu = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
    return (p - (a + mu * d)).squaredNorm();
  };
  // The turn cut at every vertex's place and every chord end's, walked in order: in each
  // piece, one segment j of the polyline and one chord k. At a piece's end that is a vertex,
  // the polyline's point is that vertex and the chord's is where the ray through it meets
  // the chord; at a chord end, the other way round. (Squared distances until the end.)
  // In the plane: every vertex lies within kLengthEpsMm of the arc's height and every chord
  // end on it, so a distance in space exceeds its plane's by at most twice that, added at the end.
  const double stop_plane = stop_above_mm - 2 * kLengthEpsMm;
  const double stop2 = stop_plane >= 0 ? stop_plane * stop_plane : -1.0;
  double bound2 = 0;
  size_t j = 0, k = 0;
  double lo = 0;
  // The piece before's segment and chord, and its points at its end (this piece's start).
  size_t last_j = SIZE_MAX, last_k = SIZE_MAX;
  Vec2 last_p{0, 0}, last_q{0, 0};
  for (;;) {
    while (j + 1 < m && t[j + 1] <= lo) ++j;
    while (k + 1 < segments && u[k + 1] <= lo) ++k;
    const double hi = std::min(t[j + 1], u[k + 1]);
    const Vec2 a = vertex(j), b = vertex(j + 1), c0 = chord_end(k), c1 = chord_end(k + 1);
    // At lo and at hi: each cut is a vertex's place or a chord end's, or both. Where the
    // piece before ends on the same segment (a chord end's cut) or the same chord (a
    // vertex's), its end points are this piece's start points, and the one measured
    // against what has not changed was measured there already.
    const bool same_segment = j == last_j && k == last_k + 1, same_chord = k == last_k && j == last_j + 1;
    const Vec2 p_lo = t[j] == lo ? a : same_segment ? last_p : on_ray(a, b, c0);
    const Vec2 q_lo = u[k] == lo ? c0 : same_chord ? last_q : on_ray(c0, c1, a);
    const Vec2 p_hi = t[j + 1] == hi ? b : on_ray(a, b, c1), q_hi = u[k + 1] == hi ? c1 : on_ray(c0, c1, b);
    if (!same_chord) bound2 = std::max(bound2, distance(p_lo, c0, c1));
    if (!same_segment) bound2 = std::max(bound2, distance(q_lo, a, b));
    bound2 = std::max({bound2, distance(p_hi, c0, c1), distance(q_hi, a, b)});
    if (bound2 > stop2) return std::sqrt(bound2) + 2 * kLengthEpsMm;
    if (hi >= 1) break;
    lo = hi;
    last_j = j, last_k = k, last_p = p_hi, last_q = q_hi;
  }
  return std::sqrt(bound2) + 2 * kLengthEpsMm;
}

double wrong_side_of_line_mm(std::span<const Vec3> pts, BandSide side) {
  if (side == BandSide::Both || pts.size() < 3) return 0;
  const Vec2 a(pts.front().x(), pts.front().y()), b(pts.back().x(), pts.back().y());
  const Vec2 d = b - a;
  const double len = d.norm();
  if (len <= 0) return 0;
  const Vec2 dir = d / len;
  double wrong = 0;
  for (size_t m = 1; m + 1 < pts.size(); ++m) {
    const double left = cross2(dir, Vec2(pts[m].x(), pts[m].y()) - a);  // the point's offset, left > 0
    wrong = std::max(wrong, side == BandSide::Left ? left : -left);
  }
  return wrong;
}

double wrong_side_of_arc_mm(std::span<const Vec3> pts, const Vec2& centre, bool ccw, BandSide side) {
  if (side == BandSide::Both || pts.size() < 2) return 0;
  const double r = (Vec2(pts.front().x(), pts.front().y()) - centre).norm();
  // A point's offset to the left of the arc: towards the centre of one that turns left.
  const double turn = ccw ? 1.0 : -1.0;
  auto left_of = [&](const Vec2& q) { return turn * (r - (q - centre).norm()); };
  double wrong = 0;
  auto note = [&](const Vec2& q) { wrong = std::max(wrong, side == BandSide::Left ? left_of(q) : -left_of(q)); };
  for (size_t m = 0; m + 1 < pts.size(); ++m) {
    const Vec2 p0(pts[m].x(), pts[m].y()), p1(pts[m + 1].x(), pts[m + 1].y());
    if (m > 0) note(p0);
    const Vec2 d = p1 - p0;
    const double len2 = d.squaredNorm();
    if (len2 <= 0) continue;
    const double t = (centre - p0).dot(d) / len2;
    if (t > 0 && t < 1) note(p0 + t * d);  // nearest the centre: the segment's extreme offset
  }
  return wrong;
}

}  // namespace arcpress
