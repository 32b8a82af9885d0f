// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/model/arc_centre.hpp"

#include <cmath>

namespace arcpress {

Vec3 ijk_centre(const Frame& frame, Plane plane, const AxisValues& from, const double* ijk, const bool* ijk_seen,
                bool as_absolute) {
  const auto a = axes_of(plane);
  Vec3 at(from[kX], from[kY], from[kZ]);
  for (int k = 0; k < 3; ++k) {
    if (k == a.normal) continue;
    const double off = ijk_seen[k] ? ijk[k] : 0.0;
    if (as_absolute)
      at[k] = ijk_seen[k] ? frame.to_mm(k, off) : from[k];
    else
      at[k] = from[k] + off * frame.unit_mm;
  }
  return at;
}

RadiusGap radius_gap(const Dialect& dialect, Plane plane, const AxisValues& from, const Vec3& centre,
                     const AxisValues& to) {
  const auto a = axes_of(plane);
  const Vec2 cc(centre[a.first], centre[a.second]);
  const double r0 = (Vec2(from[a.first], from[a.second]) - cc).norm();
  const double r1 = (Vec2(to[a.first], to[a.second]) - cc).norm();
  const double allowed =
      dialect.radius_rel > 0 ? std::max(dialect.radius_abs_mm, dialect.radius_rel * r0) : dialect.radius_abs_mm;
  return {std::abs(r1 - r0), allowed};
}

RadiusCentre radius_centre(const Vec2& s, const Vec2& e, double r_mm, bool ccw, double allowance_mm) {
  RadiusCentre out;
  const Vec2 chord = e - s;
  const double d = chord.norm();
  out.half_chord_mm = d / 2;
  if (d < kLengthEpsMm) {
    out.coincident = true;
    return out;
  }
  if (std::abs(r_mm) < d / 2 - allowance_mm) return out;
  const double h2 = r_mm * r_mm - d * d / 4;
  const double h = h2 > 0 ? std::sqrt(h2) : 0.0;
  // G3 with R > 0 (short way round): centre on the left of the chord; G2: on the right.
  const double side = (ccw ? 1.0 : -1.0) * (r_mm >= 0 ? 1.0 : -1.0);
  out.centre = (s + e) / 2 + side * h * left_normal(chord / d);
  return out;
}

}  // namespace arcpress
