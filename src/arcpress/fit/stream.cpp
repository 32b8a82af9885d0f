// SPDX-License-Identifier: GPL-3.0-or-later
// Seeds 001 and 003 (--method stream): each primitive grows one vertex at a time through a
// window of moves, as a controller would buffer them, the arc through both ends whose
// centre best fits the points between.
#include "arcpress/fit/run_fitter.hpp"

namespace arcpress::fit_detail {

/// Seeds 001 and 003: each primitive grows one vertex at a time through a window of at
/// most `stream_window` moves, as a controller would buffer them. The arc through both end
/// points whose centre, on the chord's bisector, best fits the points between (least
/// squares) is kept while it stays inside the band; at the first vertex where neither it
/// nor a line does, the last fit that did is written and the next primitive starts there.
/// Then the joints are made tangent where the band allows (make_tangent()).
std::vector<Chosen> RunFitter::stream_chain(uint32_t a, uint32_t limit, size_t& forced) const {
  std::vector<Chosen> chain;
  const uint32_t start = a;
  while (a < limit) {
    Chosen best = input_move(a);
    for (uint32_t e = a + 2; e <= limit && e - a <= o_.stream_window && !soft_[e - 1]; ++e) {
      std::optional<Chosen> c = make_line(a, e, best.end_tangent);
      if (!c) c = through_ends(a, e);
      if (!c) break;
      best = *c;
    }
    chain.push_back(best);
    a = best.prim.end_vertex;
  }
  make_tangent(start, chain, forced);
  return chain;
}

/// Seed 001's circle: through vertices a and e, centre on the chord's perpendicular
/// bisector at the offset that minimises the squared algebraic residuals |p - c|² - r² of
/// the vertices between (linear in the offset, so closed-form); CW or CCW from the polar
/// angles of the start, second and end vertex about that centre, wrap-around included.
std::optional<Chosen> RunFitter::through_ends(uint32_t a, uint32_t e) const {
  Vec2 p0 = q(a), p1 = q(e), m = (p0 + p1) / 2;
  Vec2 chord = p1 - p0;
  double h2 = chord.squaredNorm() / 4;
  if (h2 <= kLengthEpsMm * kLengthEpsMm) return std::nullopt;
  Vec2 n = left_normal(chord.normalized());
  double num = 0, den = 0;
  for (uint32_t v = a + 1; v < e; ++v) {
    Vec2 d = q(v) - m;
    double resid = d.squaredNorm() - h2, slope = 2 * d.dot(n);  // residual = resid - s·slope
    num += resid * slope;
    den += slope * slope;
  }
  if (den <= 0) return std::nullopt;
  Vec2 center = m + n * (num / den);
  auto angle = [&](const Vec2& p) { return std::atan2(p.y() - center.y(), p.x() - center.x()); };
  auto ccw_from_start = [&](double t) {
    double d = t - angle(p0);
    while (d < 0) d += 2 * kPi;
    while (d >= 2 * kPi) d -= 2 * kPi;
    return d;
  };
  bool ccw = ccw_from_start(angle(q(a + 1))) < ccw_from_start(angle(p1));
  return make_arc(a, e, center, ccw);
}

}  // namespace arcpress::fit_detail
