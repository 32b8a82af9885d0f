// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The curvature-interval scan's loop, a template over what receives each end, for the
// files that scan (private to fit/; scan.cpp explains it).
#include "arcpress/fit/run_fitter.hpp"

namespace arcpress::fit_detail {

template <class Sink>
void RunFitter::scan_ends(uint32_t a, const Vec2& T, uint32_t limit, Sink&& sink) const {
  auto one = [&](int, const Candidate& c) { sink(c); };
  if (level_) {
    fan_ends_in<true, 1>(a, &T, 1, limit, a + 1, one);
  } else {
    fan_ends_in<false, 1>(a, &T, 1, limit, a + 1, one);
  }
}

template <class Sink>
void RunFitter::fan_ends(uint32_t a, const Vec2* T, int count, uint32_t limit, uint32_t first_end,
                         Sink&& sink) const {
  if (level_) {
    fan_ends_in<true, kFanLanes>(a, T, count, limit, first_end, sink);
  } else {
    fan_ends_in<false, kFanLanes>(a, T, count, limit, first_end, sink);
  }
}

template <bool level, int Lanes, class Sink>
void RunFitter::fan_ends_in(uint32_t a, const Vec2* T, int count, uint32_t limit, uint32_t first_end,
                            Sink& sink) const {
  // One scan per tangent ("lane"), taken a vertex at a time together: what depends only on
  // the vertex is worked out once for all of them. Each lane's arithmetic is that of a scan
  // of its own, so the ends and curvatures are the same to the last bit. Ends before
  // `first_end` narrow the intervals but are not tested as ends. With one lane (scan_ends(),
  // every end from a + 1 on; the beam's and greedy walk's millions of scans) the lane is
  // alive while the loop runs, which the compiler is shown: the bookkeeping would cost some
  // 2 % of the whole program on the FreeCAD program.
  const int lanes = Lanes == 1 ? 1 : count;
  double tx[Lanes], ty[Lanes], nx[Lanes];  // the tangent T, its left normal N = (nx, tx)
  auto dot_n = [&](const Vec2& u, int j) { return u.x() * nx[j] + u.y() * tx[j]; };
  auto dot_t = [&](const Vec2& u, int j) { return u.x() * tx[j] + u.y() * ty[j]; };
  const Vec2 qa = q(a);
  const double h0 = p_[a].z();
  // The stretch's limits, read once: the sink writes memory, so the compiler would read
  // them again at every vertex.
  const ScanLimits lim = lim_;
  // The band a vertex must stay in: all of it while the primitive is flat, the in-plane
  // share once it climbs (from then on, for every vertex from `a`).
  double eps = eps_;
  double lo[Lanes], hi[Lanes];          // curvature interval (1/mm) the interior vertices allow
  double arc_lo[Lanes], arc_hi[Lanes];  // and the moves' middles, for arcs
  bool alive[Lanes];
  int live = lanes;
  auto open = [&] {
    for (int j = 0; j < lanes; ++j) lo[j] = arc_lo[j] = -kInf, hi[j] = arc_hi[j] = kInf;
  };
  for (int j = 0; j < lanes; ++j) tx[j] = T[j].x(), ty[j] = T[j].y(), nx[j] = -ty[j], alive[j] = true;
  open();
  // A point u from `a`, off T by b = u·N, is within ε of the circle of curvature k when
  // |k·(|u|² - ε²) - 2b| <= 2ε (exact for the full circle).
  // On one side only (--band-side), its left offset ℓ from the circle, which satisfies
  // k·|u|² - 2b = -2ℓ + k·ℓ² for either sign of k, lies in [-ε, 0] (the circle left of the
  // point) or [0, ε]: k·|u|² >= 2b, or <= 2b, replaces one of the two bounds.
  const BandSide side = lim.side;
  auto narrow_by = [&](const Vec2& u, double uu) {  // u from `a`, uu = |u|²
    const double w = uu - eps * eps;
    if (w > 0) {
      const double inv = 1 / w;
      for (int j = 0; j < lanes; ++j) {
        const double b = dot_n(u, j);
        lo[j] = std::max(lo[j], side == BandSide::Left ? 2 * b / uu : (2 * b - 2 * eps) * inv);
        hi[j] = std::min(hi[j], side == BandSide::Right ? 2 * b / uu : (2 * b + 2 * eps) * inv);
      }
    }
  };
  auto narrow = [&](uint32_t m) {
    const Vec2 u = q(m) - qa;
    narrow_by(u, u.squaredNorm());
  };
  // No input move may cut inside an arc by more than the band. A move whose middle lies
  // more than ε off T is more than ε inside every circle that turns towards it less than
  // the middle's own lower bound above (a circle turning the other way leaves it more than
  // ε outside, which the bounds of the move's end points already rule out), and the move's
  // point nearest the centre is nearer still, so the exact check would fail. Lines are the
  // chord, not this circle, and are not held to it.
  auto narrow_move = [&](uint32_t m) {  // the move from vertex m to m + 1
    const Vec2 u = middle_[m] - qa;
    const double w = u.squaredNorm() - eps * eps;
    for (int j = 0; j < lanes; ++j) {
      const double b = dot_n(u, j);
      if (b > eps) arc_lo[j] = std::max(arc_lo[j], (2 * b - 2 * eps) / w);
      if (b < -eps) arc_hi[j] = std::min(arc_hi[j], (2 * b + 2 * eps) / w);
    }
  };
  bool flat = true;
  Vec2 u{0, 0};  // the end before, from `a`, and its squared length
  double uu = 0;
  // A primitive ends at the first soft vertex at the latest.
  const uint32_t last = std::min(limit, next_soft_[a]);
  for (uint32_t e = a + 1; e <= last; ++e) {
    if (e > a + 1) narrow_by(u, uu);  // vertex e - 1 becomes an interior vertex
    narrow_move(e - 1);
    if (!level && flat && std::abs(p_[e].z() - h0) > kLengthEpsMm) {
      flat = false;
      eps = eps_ * kPlaneShare;
      open();
      for (uint32_t m = a + 1; m < e; ++m) narrow(m);
      for (uint32_t m = a; m < e; ++m) narrow_move(m);
    }
    if constexpr (Lanes == 1) {
      if (lo[0] > hi[0]) break;
    } else {
      for (int j = 0; j < lanes; ++j)
        if (alive[j] && lo[j] > hi[j]) alive[j] = false, --live;
      if (live == 0) break;
    }
    u = q(e) - qa;
    uu = u.squaredNorm();
    if (uu <= kLengthEpsMm * kLengthEpsMm) {
      if (level || flat) break;  // back at the start: a full circle is not a single primitive here
      // Straight above or below the start (a plunge written in steps): no direction in
      // the plane, so only a line can end here, which the exact check measures in 3D.
      for (int j = 0; j < lanes; ++j)
        if (alive[j]) sink(j, Candidate{e, 0.0, true});
      continue;
    }
    for (int j = 0; j < lanes; ++j) {
      if (Lanes > 1 && !alive[j]) continue;
      // The tangent-chord angle alpha (sweep = 2 alpha), held to the limits as the
      // pseudo-angle of |alpha|, and the curvature.
      const double ut = dot_t(u, j), un = dot_n(u, j), abs_un = std::abs(un);
      if (pseudo_angle_above(ut, abs_un, lim.max_alpha)) {
        alive[j] = false, --live;
        continue;
      }
      if (Lanes > 1 && e < first_end) continue;
      // The curvature k = K / uu of the circle through e, held to the intervals with a
      // relative slack of 1e-12 for rounding, multiplied through by uu > 0.
      const double K = 2 * un, slack = 1e-12 * (uu + std::abs(K));
      if (K + slack < lo[j] * uu || K - slack > hi[j] * uu) continue;
      const bool line = !pseudo_angle_above(ut, abs_un, lim.line_alpha);
      if (!line) {
        if (!lim.arcs || K + slack < arc_lo[j] * uu || K - slack > arc_hi[j] * uu) continue;
        // The radius uu / |K| within the options' limits.
        if (std::abs(K) < lim.min_curvature * uu || std::abs(K) > lim.max_curvature * uu) continue;
        if (e - a < lim.min_arc_moves || pseudo_angle_below(ut, abs_un, lim.min_alpha)) continue;
        if (!level && !flat && !lim.helical) continue;
        if (lim.min_arc_length_mm > 0 && 2 * std::atan2(abs_un, ut) * uu / std::abs(K) < lim.min_arc_length_mm)
          continue;
      }
      // Before a fixed move, the stretch must end heading along it.
      if (e == lim.stretch_end && lim.out_tangent) {
        const Vec2 c = u / std::sqrt(uu);
        const Vec2 end = line ? c : Vec2(2 * c.dot(T[j]) * c - T[j]);
        if (!joint_cone_.holds(end, *lim.out_tangent)) continue;
      }
      sink(j, Candidate{e, K / uu, line});
    }
    if (live == 0) break;
  }
}

}  // namespace arcpress::fit_detail
