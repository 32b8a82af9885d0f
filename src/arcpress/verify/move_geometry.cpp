// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/verify/move_geometry.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace arcpress {
namespace {

/// End points printed from the same text read back identically; this only absorbs the
/// different order of operations in unit conversion.
constexpr double kSamePointMm = 1e-7;

}  // namespace

ArcGeom arc_of_move(const Interpretation& in, size_t i) {
  const Move& m = in.moves[i];
  Vec3 s = in_plane(in.from(i), m.plane), e = in_plane(m.to, m.plane);
  ArcGeom g = ArcGeom::through(s, e, project(m.center, m.plane), m.kind == MoveKind::ArcCCW);
  // Only end points that coincide make a whole turn: an arc of a huge radius between two
  // distinct points turns by next to nothing, and is next to its chord.
  if ((s - e).head<2>().norm() <= kSamePointMm)
    g.sweep = (m.kind == MoveKind::ArcCCW ? 1 : -1) * 2 * kPi;
  g.sweep += (g.sweep >= 0 ? 1 : -1) * 2 * kPi * std::max(0, m.turns - 1);
  return g;
}

ProgressWindow move_progress_near(const Interpretation& in, size_t i, const Vec3& p, double slack_mm) {
  const Move& m = in.moves[i];
  if (is_arc(m.kind)) return arc_progress_near(in_plane(p, m.plane), arc_of_move(in, i), slack_mm);
  const AxisValues& f = in.from(i);
  return line_progress_near(p, Vec3(f[kX], f[kY], f[kZ]), m.xyz(), slack_mm);
}

double move_length_mm(const Interpretation& in, size_t i) {
  const Move& m = in.moves[i];
  if (!is_arc(m.kind)) {
    const AxisValues& f = in.from(i);
    return (m.xyz() - Vec3(f[kX], f[kY], f[kZ])).norm();
  }
  const ArcGeom g = arc_of_move(in, i);
  return std::hypot(g.radius_mm * g.sweep, g.h1 - g.h0);
}

bool extra_axes_move(const Interpretation& in) {
  for (size_t i = 0; i < in.moves.size(); ++i)
    for (int ax = kA; ax < kE; ++ax)
      if (in.moves[i].to[ax] != in.from(i)[ax]) return true;
  return false;
}

std::pair<double, int> extra_axes_apart(const AxisValues& x, const AxisValues& y) {
  std::pair<double, int> most{0.0, -1};
  for (int ax = kA; ax < kE; ++ax)
    if (const double d = std::abs(x[ax] - y[ax]); d > most.first) most = {d, ax};
  return most;
}

AxisValues extra_axes_at(const Interpretation& in, size_t i, const Vec3& p) {
  const AxisValues &f = in.from(i), &e = in.moves[i].to;
  AxisValues v = e;
  const ProgressWindow at = move_progress_near(in, i, p, 0);
  const double t = 0.5 * (at.lo[0] + at.hi[0]);
  for (int ax = kA; ax < kE; ++ax) v[ax] = f[ax] + t * (e[ax] - f[ax]);
  return v;
}

std::pair<double, int> extra_axes_gap(const Interpretation& in, size_t i, const Vec3& p, const AxisValues& target,
                                      double slack_mm) {
  const AxisValues &f = in.from(i), &e = in.moves[i].to;
  const ProgressWindow w = move_progress_near(in, i, p, slack_mm);
  std::pair<double, int> most{0.0, -1};
  for (int ax = kA; ax < kE; ++ax)
    if (const double gap = w.least_gap(f[ax], e[ax], target[ax]); gap > most.first) most = {gap, ax};
  return most;
}

double flat_arc_sagitta_mm(const ArcGeom& g) {
  const double turn = std::abs(g.sweep);
  if (!(turn <= kPi) || g.h0 != g.h1 || !std::isfinite(g.radius_mm)) return HUGE_VAL;
  const double s = std::sin(turn / 4);
  const double sagitta = 2 * g.radius_mm * s * s;
  return sagitta <= kFlatArcMm ? sagitta : HUGE_VAL;
}

double move_path(const Interpretation& in, size_t i, double chord_mm, std::vector<Vec3>& out) {
  const Move& m = in.moves[i];
  if (m.kind != MoveKind::ArcCW && m.kind != MoveKind::ArcCCW) {
    out.push_back(m.xyz());
    return 0;
  }
  ArcGeom g = arc_of_move(in, i);
  if (const double flat = flat_arc_sagitta_mm(g); flat <= kFlatArcMm) {
    out.push_back(m.xyz());  // its chord: no point of it can be told from the arc's
    return flat;
  }
  double r = std::max(g.radius_mm, kLengthEpsMm);
  double step = 2 * std::acos(std::clamp(1 - chord_mm / r, -1.0, 1.0));
  const double wanted = std::ceil(std::abs(g.sweep) / std::max(step, 1e-300));
  size_t n = size_t(std::clamp(wanted, 1.0, double(kMaxChordsPerMove)));
  if (n % 2) ++n;
  for (size_t k = 1; k < n; ++k) out.push_back(from_plane(g.point_at(double(k) / double(n)), m.plane));
  out.push_back(m.xyz());  // the end point exactly as read
  return r * (1 - std::cos(std::min(kPi, std::abs(g.sweep) / double(n)) / 2));
}

namespace {

/// A point of an arc's plane at `height` along its normal, in XYZ.
Vec3 from_plane(const Vec2& v, double height, Plane pl) { return from_plane(Vec3(v.x(), v.y(), height), pl); }

/// `p` about the arc's centre, seen along the plane's normal.
Vec2 about_center(const FlatArc& arc, const Vec3& p) { return project(p - arc.center, arc.plane); }

/// The point of the arc's circle in the direction `v` (in the plane) from its centre.
Vec3 on_circle(const FlatArc& arc, const Vec2& v) {
  return from_plane(project(arc.center, arc.plane) + v * (arc.radius_mm / v.norm()),
                    arc.center[axes_of(arc.plane).normal], arc.plane);
}

/// Move i as the flat arc arc_pieces() cuts, when it is one.
std::optional<ArcGeom> flat_arc_of(const Interpretation& in, size_t i) {
  const Move& m = in.moves[i];
  if (!is_arc(m.kind) || m.turns > 1) return std::nullopt;
  const ArcGeom g = arc_of_move(in, i);
  const double r = g.radius_mm;
  if (g.h1 != g.h0 || !(r > kLengthEpsMm) || !std::isfinite(r) || flat_arc_sagitta_mm(g) <= kFlatArcMm)
    return std::nullopt;
  return g;
}

}  // namespace

std::optional<double> flat_arc_length_mm(const Interpretation& in, size_t i) {
  const auto g = flat_arc_of(in, i);
  if (!g) return std::nullopt;
  const Vec3 end = from_plane(g->point_at(1), in.moves[i].plane);
  return g->radius_mm * std::abs(g->sweep) + (in.moves[i].xyz() - end).norm();
}

std::optional<FlatArc> arc_pieces(const Interpretation& in, size_t i, double max_sagitta_mm, double max_sweep_rad,
                                  double max_piece_mm, size_t max_pieces, std::vector<Vec3>& out, bool& straight_end) {
  const Move& m = in.moves[i];
  straight_end = false;
  const auto flat = flat_arc_of(in, i);
  if (!flat) return std::nullopt;
  const ArcGeom& g = *flat;
  const double r = g.radius_mm;
  const double fine = std::min(2 * std::acos(std::clamp(1 - max_sagitta_mm / r, -1.0, 1.0)),
                               2 * std::asin(std::min(1.0, max_piece_mm / (2 * r))));
  const double by_sweep = std::ceil(std::abs(g.sweep) / max_sweep_rad);
  const double by_size = std::min(std::ceil(std::abs(g.sweep) / std::max(fine, 1e-300)), double(max_pieces));
  const size_t n = size_t(std::max({1.0, by_sweep, by_size}));
  for (size_t k = 1; k <= n; ++k) out.push_back(from_plane(g.point_at(double(k) / double(n)), m.plane));
  if (!(out.back() == m.xyz())) {
    out.push_back(m.xyz());
    straight_end = true;
  }
  return FlatArc{m.plane, from_plane(g.center, g.h0, m.plane), r, m.kind == MoveKind::ArcCCW};
}

bool in_wedge(const FlatArc& arc, const Vec3& a, const Vec3& b, const Vec3& p) {
  const Vec2 A = about_center(arc, a), B = about_center(arc, b), V = about_center(arc, p);
  const double sign = arc.ccw ? 1.0 : -1.0;
  return sign * cross2(A, V) >= 0 && sign * cross2(V, B) >= 0 && V.dot(A + B) >= 0;
}

Vec3 nearest_on_piece(const FlatArc& arc, const Vec3& a, const Vec3& b, const Vec3& p) {
  const Vec2 V = about_center(arc, p);
  const double len = V.norm();
  if (len > 0 && in_wedge(arc, a, b, p)) return on_circle(arc, V);
  // Off the wedge the in-plane distance grows with the angle from p's own: an end is nearest.
  return (p - a).squaredNorm() <= (p - b).squaredNorm() ? a : b;
}

Vec3 point_on_piece(const FlatArc& arc, const Vec3& a, const Vec3& b, double t) {
  const Vec2 A = about_center(arc, a), B = about_center(arc, b);
  const double sweep = std::atan2(cross2(A, B), A.dot(B)) * t;
  return on_circle(arc, Eigen::Rotation2D<double>(sweep) * (A.norm() > 0 ? A : Vec2(1, 0)));
}

std::optional<double> segment_to_piece_bound(const FlatArc& arc, const Vec3& a, const Vec3& b, const Vec3& p0,
                                             const Vec3& p1) {
  if (!in_wedge(arc, a, b, p0) || !in_wedge(arc, a, b, p1)) return std::nullopt;
  const Vec2 v0 = about_center(arc, p0), v1 = about_center(arc, p1), d = v1 - v0;
  const double len2 = d.squaredNorm();
  const Vec2 foot = len2 > 0 ? Vec2(v0 + std::clamp(-v0.dot(d) / len2, 0.0, 1.0) * d) : v0;
  const double r = arc.radius_mm;
  const double radial = std::max({v0.norm() - r, v1.norm() - r, r - foot.norm(), 0.0});
  const int normal = axes_of(arc.plane).normal;
  const double height = std::max(std::abs(p0[normal] - arc.center[normal]), std::abs(p1[normal] - arc.center[normal]));
  return std::hypot(radial, height);
}

double piece_sagitta_mm(const FlatArc& arc, const Vec3& a, const Vec3& b) {
  const double half = (about_center(arc, b) - about_center(arc, a)).norm() / 2, r = arc.radius_mm;
  return r - std::sqrt(std::max(0.0, r * r - half * half));
}

}  // namespace arcpress
