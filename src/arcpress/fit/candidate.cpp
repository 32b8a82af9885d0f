// SPDX-License-Identifier: GPL-3.0-or-later
// Building a line or arc between two vertices and checking it exactly against the band,
// the plane's normal axis and the extra axes.
#include "arcpress/fit/run_fitter.hpp"

namespace arcpress::fit_detail {

/// Builds and checks the primitive for candidate `c` from `a` along `T`.
std::optional<Chosen> RunFitter::make(uint32_t a, const Vec2& T, const Candidate& c) const {
  if (c.line) return make_line(a, c.e, T);
  return make_arc(a, c.e, q(a) + left_normal(T) / c.k, c.k > 0);
}

template <class Window>
bool RunFitter::extra_axes_linear(uint32_t a, uint32_t e, const Window& window) const {
  const size_t k = extra_.size();
  if (k == 0 || e <= a + 1) return true;
  for (uint32_t m = a + 1; m < e; ++m) {
    const ProgressWindow w = window(m);
    for (size_t i = 0; i < k; ++i)
      if (w.least_gap(extra_values_[a * k + i], extra_values_[e * k + i], extra_values_[m * k + i]) > eps_) return false;
  }
  return true;
}

bool RunFitter::extrusion_even(uint32_t a, uint32_t e, double length_mm) const {
  if (e_rate_.empty()) return true;  // (over one move too: an arc is longer than the move's chord)
  const double rate = length_mm > kLengthEpsMm ? std::abs(e_values_[e] - e_values_[a]) / length_mm : 0.0;
  const double v = o_.extrusion_variance;
  for (uint32_t m = a; m < e; ++m)
    if (std::abs(e_rate_[m] - rate) > v * std::max(e_rate_[m], rate)) return false;
  return true;
}

/// The line from vertex a to vertex e, if the moves between stay inside the band.
std::optional<Chosen> RunFitter::make_line(uint32_t a, uint32_t e, const Vec2& fallback_tangent) const {
  if (!extra_axes_linear(a, e, [&](uint32_t m) { return line_progress_near(p_[m], p_[a], p_[e], kFitNearShare * eps_); }) ||
      !extrusion_even(a, e, (p_[e] - p_[a]).norm()))
    return std::nullopt;
  std::span<const Vec3> pts(p_.data() + a, e - a + 1);
  Deviation d = line_deviation(pts, eps_);
  if (!d.ordered || d.max_mm > eps_) return std::nullopt;
  if (wrong_side_of_line_mm(pts, o_.band_side) > kLengthEpsMm) return std::nullopt;  // (rounding of doubles)
  Chosen ch;
  ch.prim.end_vertex = e;
  ch.prim.kind = Primitive::Kind::Line;
  Vec2 chord = q(e) - q(a);
  ch.end_tangent = chord.norm() > 0 ? Vec2(chord.normalized()) : fallback_tangent;
  return ch;
}

/// The arc from vertex a to vertex e about `center`, if the moves between stay inside the
/// band (in-plane share when it climbs) and the arc keeps the options' limits.
std::optional<Chosen> RunFitter::make_arc(uint32_t a, uint32_t e, const Vec2& center, bool ccw) const {
  if (!arcs_ || e - a < std::max<uint32_t>(o_.min_arc_moves, 1)) return std::nullopt;
  std::span<const Vec3> pts(p_.data() + a, e - a + 1);
  bool flat = true;
  for (const auto& p : pts) flat = flat && std::abs(p.z() - pts.front().z()) <= kLengthEpsMm;
  if (!flat && !o_.helical) return std::nullopt;
  if ((q(e) - q(a)).squaredNorm() < o_.min_chord_mm * o_.min_chord_mm) return std::nullopt;
  ArcGeom g = ArcGeom::through(pts.front(), pts.back(), center, ccw);
  if (!std::isfinite(g.radius_mm) || g.radius_mm < o_.min_radius_mm || g.radius_mm > o_.max_radius_mm)
    return std::nullopt;
  const double sweep_deg = std::abs(g.sweep) * 180 / kPi;
  if (sweep_deg > o_.max_sweep_deg + 1e-9 || sweep_deg < o_.min_sweep_deg) return std::nullopt;
  if (g.radius_mm * std::abs(g.sweep) < o_.min_arc_length_mm) return std::nullopt;
  if (!extra_axes_linear(a, e, [&](uint32_t m) { return arc_progress_near(p_[m], g, kFitNearShare * eps_); }) ||
      !extrusion_even(a, e, std::hypot(g.radius_mm * g.sweep, g.h1 - g.h0)))
    return std::nullopt;
  const double band = flat ? eps_ : eps_ * kPlaneShare;
  // Where the firmware moves along chords, every point of them lies within their sagitta
  // of the circle, and every point of the circle as near them: a circle inside the band
  // with that taken off keeps the chords in the band. Else the chords are measured
  // themselves (a flat arc); the circle must keep the band too.
  const uint32_t chords = executed_segments(o_.executed, g.radius_mm, g.sweep, g.h1 - g.h0);
  if (chords >= kMaxArcSegments) return std::nullopt;  // more than the firmware counts
  double sagitta = chords_sagitta_mm(g.radius_mm, g.sweep, chords);
  const bool ring = o_.executed.count_may_grow();
  // (The ring is half its width off its middle circle at least: wider than twice the band, no
  // point lies within the band of it.)
  if (ring && sagitta / 2 > band) return std::nullopt;
  // The firmware's chord ends, which its small-angle steps may pull off the circle: the
  // chords lie within their sagitta and that drift of the circle. (Klipper's lie on it.)
  const Vec2 start(pts.front().x(), pts.front().y());
  std::vector<Vec2>& ends = s_.chord_ends;
  ends.clear();
  auto work_out_ends = [&] {
    if (chords > 1)
      executed_chord_ends(o_.executed, start, g.center, Vec2(pts.back().x(), pts.back().y()), g.sweep, chords, ends);
  };
  if (!(ring && sagitta > 0)) work_out_ends();  // (the ring's: below, where it needs them)
  if (chords > 1 && !ring && o_.executed.rule != ArcSegmentation::Rule::Klipper)
    sagitta += chords_drift_mm(start, g.center, g.sweep, ends);
  if (sagitta > 0 && ring) {
    // The firmware may cut more chords at a low feed: none of them is the path, the ring
    // about the circle that holds them all is (ring_deviation(): its ends' drift added last,
    // so that they are worked out only where the ring keeps the band without it).
    const Deviation d = ring_deviation_before_drift(o_.executed, pts, g, chords, band);
    if (!d.ordered || d.max_mm > band) return std::nullopt;
    work_out_ends();
    if (d.max_mm + chords_drift_mm(start, g.center, g.sweep, ends) > band) return std::nullopt;
  } else if (sagitta > 0) {
    Deviation near = arc_deviation(pts, g, band - sagitta);
    if (!near.ordered) return std::nullopt;
    if (near.max_mm > band - sagitta) {
      // The chords first: where the circle keeps the band, they are what most often leaves
      // it (Cura's screw at 0.01 mm on Marlin's chords: half the arcs that get here), and
      // their test fails sooner than the circle's passes. (A helix's chords climb as it
      // does, evenly by turn: they are measured in the plane, against the in-plane share of
      // the band, and its height is checked below.)
      std::optional<double> on_chords;
      if (flat) {
        on_chords = chords_deviation_bound(pts, g, ends, band);
      } else {
        std::vector<Vec3>& flat_pts = s_.flat_pts;
        flat_pts.assign(pts.begin(), pts.end());
        for (Vec3& p : flat_pts) p.z() = g.h0;
        ArcGeom plane = g;
        plane.h1 = g.h0;
        on_chords = chords_deviation_bound(flat_pts, plane, ends, band);
      }
      if (!on_chords || *on_chords > band) return std::nullopt;
      Deviation d = arc_deviation(pts, g, band);
      if (d.max_mm > band) return std::nullopt;
    }
  } else {
    Deviation d = arc_deviation(pts, g, band);
    if (!d.ordered || d.max_mm > band) return std::nullopt;
  }
  if (!flat) {
    // Height must follow the helix closely enough for the 3D distance to stay in the band.
    double len_sum = 0;
    for (size_t m = 1; m < pts.size(); ++m)
      len_sum += (Vec2(pts[m].x(), pts[m].y()) - Vec2(pts[m - 1].x(), pts[m - 1].y())).norm();
    double s = 0;
    for (size_t m = 1; m + 1 < pts.size(); ++m) {
      s += (Vec2(pts[m].x(), pts[m].y()) - Vec2(pts[m - 1].x(), pts[m - 1].y())).norm();
      double h = g.h0 + (g.h1 - g.h0) * (len_sum > 0 ? s / len_sum : 0);
      if (std::abs(pts[m].z() - h) > eps_ * kHeightShare) return std::nullopt;
    }
  }
  if (wrong_side_of_arc_mm(pts, center, ccw, o_.band_side) > kLengthEpsMm) return std::nullopt;
  Chosen ch;
  ch.prim.end_vertex = e;
  ch.prim.kind = Primitive::Kind::Arc;
  ch.prim.ccw = ccw;
  ch.prim.center = center;
  ch.prim.radius_mm = g.radius_mm;
  ch.end_tangent = arc_tangent(q(e) - center, ccw);
  return ch;
}

/// The line or arc leaving vertex a along T and ending exactly at vertex e, if scan()
/// would offer it (not yet checked exactly).
std::optional<Candidate> RunFitter::through_candidate(uint32_t a, const Vec2& T, uint32_t e) const {
  Vec2 u = q(e) - q(a);
  double uu = u.squaredNorm();
  if (uu <= kLengthEpsMm * kLengthEpsMm || u.dot(T) <= 0) return std::nullopt;
  if (soft_between(a, e)) return std::nullopt;
  Vec2 N = left_normal(T);
  const Candidate c{e, 2 * u.dot(N) / uu, pseudo_angle(u.dot(T), std::abs(u.dot(N))) <= line_alpha_};
  if (!on_circle(a, T, c)) return std::nullopt;
  return c;
}

/// The line or arc leaving vertex a along T and ending exactly at vertex e, checked.
std::optional<Chosen> RunFitter::through(uint32_t a, const Vec2& T, uint32_t e) const {
  auto c = through_candidate(a, T, e);
  if (!c) return std::nullopt;
  return make(a, T, *c);
}

/// scan()'s test of one end: every vertex between `a` and c.e lies within the band of the
/// full circle (or line) leaving `a` along T with curvature c.k: scan()'s vertex test
/// without a division. Cheap, and necessary for the exact check, so most candidates that
/// would fail it are turned away here.
bool RunFitter::on_circle(uint32_t a, const Vec2& T, const Candidate& c) const {
  const Vec2 N = left_normal(T);
  const double slack = 1e-12 * (1 + std::abs(c.k));
  // Each vertex, and for an arc each move's middle: a point of the input too, which the arc
  // must pass within the band of (for a line the exact check measures the chord).
  auto off = [&](const Vec2& p, double eps) {
    const Vec2 u = p - q(a);
    const double w = u.squaredNorm() - eps * eps;
    return w > 0 && std::abs(c.k * w - 2 * u.dot(N)) > 2 * eps + slack * w;
  };
  auto within = [&](double eps) {
    for (uint32_t m = a + 1; m < c.e; ++m)
      if (off(q(m), eps)) return false;
    if (!c.line)
      for (uint32_t m = a; m < c.e; ++m)
        if (off(middle_[m], eps)) return false;
    return true;
  };
  // The whole band first: most candidates that fail, fail there at once, and the in-plane
  // share a climbing primitive keeps is only narrower.
  if (!within(eps_)) return false;
  if (level_) return true;
  const double h0 = p_[a].z();
  bool flat = true;
  for (uint32_t m = a + 1; m <= c.e && flat; ++m) flat = std::abs(p_[m].z() - h0) <= kLengthEpsMm;
  return flat || within(eps_ * kPlaneShare);
}

}  // namespace arcpress::fit_detail
