#include "arcpress/verify/move_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace arcpress {
namespace {

/// End points printed from the same text read back identically; this only absorbs the
/// different order of operations in unit conversion.
constexpr double kSamePointMm = 1e-7;

Vec3 in_plane(const AxisValues& v, Plane pl) {
  auto a = axes_of(pl);
  return {v[a.first], v[a.second], v[a.normal]};
}

}  // namespace

ArcGeom arc_of_move(const Interpretation& in, size_t i) {
  const Move& m = in.moves[i];
  Vec3 s = in_plane(in.from(i), m.plane), e = in_plane(m.to, m.plane);
  ArcGeom g = ArcGeom::through(s, e, project(m.center, m.plane), m.kind == MoveKind::ArcCCW);
  if (std::abs(g.sweep) < 1e-12 || (s - e).head<2>().norm() <= kSamePointMm)
    g.sweep = (m.kind == MoveKind::ArcCCW ? 1 : -1) * 2 * kPi;
  g.sweep += (g.sweep >= 0 ? 1 : -1) * 2 * kPi * std::max(0, m.turns - 1);
  return g;
}

void move_path(const Interpretation& in, size_t i, double chord_mm, std::vector<Vec3>& out) {
  const Move& m = in.moves[i];
  if (m.kind != MoveKind::ArcCW && m.kind != MoveKind::ArcCCW) {
    out.push_back(m.xyz());
    return;
  }
  auto ax = axes_of(m.plane);
  ArcGeom g = arc_of_move(in, i);
  double r = std::max(g.radius_mm, kLengthEpsMm);
  double step = 2 * std::acos(std::clamp(1 - chord_mm / r, -1.0, 1.0));
  size_t n = std::clamp<size_t>(size_t(std::ceil(std::abs(g.sweep) / std::max(step, 1e-6))), 1, 200000);
  if (n % 2) ++n;
  for (size_t k = 1; k < n; ++k) {
    Vec3 p = g.point_at(double(k) / double(n)), q;
    q[ax.first] = p.x();
    q[ax.second] = p.y();
    q[ax.normal] = p.z();
    out.push_back(q);
  }
  out.push_back(m.xyz());  // the end point exactly as read
}

}  // namespace arcpress
