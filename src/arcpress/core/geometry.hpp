// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Small geometry vocabulary shared by all stages. Lengths are millimetres unless a name
// says otherwise; angles are radians unless a name ends in _deg.
#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <numbers>

namespace arcpress {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

/// Floating-point noise floor for lengths in mm: "is this zero?". Never a user tolerance.
inline constexpr double kLengthEpsMm = 1e-9;

/// A point is measured against a band of `band_mm` only where its coordinates' rounding (a
/// double's epsilon times their size, several times over in each distance) stays within
/// this share of the band...
inline constexpr double kFarShare = 1e-3 / 8;
/// ... so up to this many mm from the origin (about 5 600 km for a band of 0.01 mm). The
/// check measures no move beyond it, so the fitter rewrites none.
inline double farthest_measurable_mm(double band_mm) {
  return kFarShare * band_mm / std::numeric_limits<double>::epsilon();
}

inline constexpr double kPi = std::numbers::pi;
inline double deg_to_rad(double deg) { return deg * kPi / 180.0; }
inline double rad_to_deg(double rad) { return rad * 180.0 / kPi; }

/// z-component of the 2D cross product: > 0 when b turns left of a.
inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
inline Vec2 left_normal(const Vec2& t) { return {-t.y(), t.x()}; }
/// Direction of travel at a point of an arc, from the radius there (centre to point): the
/// radius turned a quarter in the arc's direction. Zero for a zero radius.
inline Vec2 arc_tangent(const Vec2& radius, bool ccw) {
  const Vec2 t = left_normal(radius.normalized());
  return ccw ? t : Vec2(-t);
}
/// A stand-in for the angle of (x, y) in [0, 2π): in [0, 4), growing with the angle, with
/// no trigonometry (0 at +x, 1 at +y, 2 at -x, 3 at -y). Comparing two of them compares
/// the angles exactly, which is all that ordering and span tests need.
inline double pseudo_angle(double x, double y) {
  double den = std::abs(x) + std::abs(y);
  if (den == 0) return 0;
  double p = y / den;  // [-1, 1]
  if (x < 0) return 2 - p;
  return y < 0 ? 4 + p : p;
}
/// pseudo_angle() of the direction at angle `rad` in [0, 2π).
inline double pseudo_angle_of(double rad) { return pseudo_angle(std::cos(rad), std::sin(rad)); }
/// Whether pseudo_angle(x, y) > bound for a point of the upper half-plane (y >= 0), where
/// pseudo-angles lie in [0, 2], without the division: with d = |x| + y, the pseudo-angle is
/// y / d for x >= 0 and 2 - y / d otherwise. (A test at every vertex of every scan.)
inline bool pseudo_angle_above(double x, double y, double bound) {
  const double d = std::abs(x) + y;
  return x >= 0 ? y > bound * d : y < (2 - bound) * d;
}
/// Whether pseudo_angle(x, y) < bound, as pseudo_angle_above(), for (x, y) not zero.
inline bool pseudo_angle_below(double x, double y, double bound) {
  const double d = std::abs(x) + y;
  return x >= 0 ? y < bound * d : y > (2 - bound) * d;
}

/// Working plane of an arc: the two in-plane axes and the normal axis (indices into XYZ),
/// oriented as RS274 defines G17/G18/G19 (G18's first axis is Z, so CCW is seen from +Y).
enum class Plane : uint8_t { XY, ZX, YZ };
struct PlaneAxes {
  int first, second, normal;
};
inline PlaneAxes axes_of(Plane p) {
  switch (p) {
    case Plane::XY: return {0, 1, 2};
    case Plane::ZX: return {2, 0, 1};
    case Plane::YZ: return {1, 2, 0};
  }
  return {0, 1, 2};
}
/// The G-code that selects the plane: 17, 18 or 19.
inline int plane_gcode(Plane p) { return 17 + int(p); }
/// XYZ point `v` seen along the plane's normal: its first and second coordinates.
inline Vec2 project(const Vec3& v, Plane p) {
  auto a = axes_of(p);
  return {v[a.first], v[a.second]};
}
/// XYZ point `v` in plane coordinates (first, second, normal).
inline Vec3 in_plane(const Vec3& v, Plane p) {
  auto a = axes_of(p);
  return {v[a.first], v[a.second], v[a.normal]};
}
/// Plane coordinates (first, second, normal) `v` back in XYZ.
inline Vec3 from_plane(const Vec3& v, Plane p) {
  auto a = axes_of(p);
  Vec3 r;
  r[a.first] = v.x();
  r[a.second] = v.y();
  r[a.normal] = v.z();
  return r;
}

}  // namespace arcpress
