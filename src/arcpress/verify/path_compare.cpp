// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/verify/path_compare.hpp"

#include <optional>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "arcpress/core/deviation.hpp"
#include "arcpress/dialect/arc_segmentation.hpp"
#include "arcpress/verify/move_geometry.hpp"

namespace arcpress {
namespace {

/// End points printed from the same text read back identically; this only absorbs the
/// different order of operations in unit conversion.
constexpr double kSamePointMm = 1e-7;

bool same_point(const AxisValues& p, const AxisValues& q) {
  for (int ax = 0; ax < kE; ++ax)
    if (std::abs(p[ax] - q[ax]) > kSamePointMm) return false;
  return true;
}

/// Appends the path of move i to `pts`, in `pl` coordinates; returns how far its chords lie
/// from it (see move_path()).
double append_path(const Interpretation& in, size_t i, Plane pl, double chord_mm, std::vector<Vec3>& pts) {
  size_t first = pts.size();
  const double sagitta_mm = move_path(in, i, chord_mm, pts);
  for (size_t k = first; k < pts.size(); ++k) pts[k] = in_plane(pts[k], pl);
  return sagitta_mm;
}

/// An upper bound of the two-sided distance between the chords the firmware of `rule` cuts
/// output arc j (`arc`, in its plane's coordinates) into and the input polyline `pts` it
/// replaces (the same ends, up to floating noise), as executed_path() cuts it; nothing
/// where chords_deviation_bound() gives none (a helix, a whole turn).
std::optional<double> executed_arc_bound_mm(const Interpretation& ib, size_t j, const ArcGeom& arc,
                                            const ArcSegmentation& rule, std::span<const Vec3> pts,
                                            std::vector<Vec2>& ends) {
  // (A flat arc, which no chord end can be told from its chord: the chord.)
  if (flat_arc_sagitta_mm(arc) <= kFlatArcMm) {
    const Deviation d = line_deviation(pts);
    return d.ordered ? std::optional<double>(d.max_mm) : std::nullopt;
  }
  const Move& m = ib.moves[j];
  const Vec3 from = in_plane(ib.from(j), m.plane), to = in_plane(m.to, m.plane);
  const uint32_t n = executed_segments_read(rule, Vec2(from.x(), from.y()), arc.center, Vec2(to.x(), to.y()), arc.sweep,
                                            arc.h1 - arc.h0);
  ends.clear();
  executed_chord_ends(rule, Vec2(from.x(), from.y()), arc.center, Vec2(to.x(), to.y()), arc.sweep, n, ends);
  if (rule.count_may_grow()) {
    // Any count from n up may run: the ring about the circle that holds them all.
    const Deviation d = ring_deviation(rule, pts, arc, ends);
    return d.ordered ? std::optional<double>(d.max_mm + kSamePointMm) : std::nullopt;
  }
  const auto bound = chords_deviation_bound(pts, arc, ends);
  // The chords run from the output's own ends, the polyline from the input's: the same
  // points as read, up to the noise of unit conversion.
  return bound ? std::optional<double>(*bound + kSamePointMm) : std::nullopt;
}

}  // namespace

Vec2 move_start_tangent(const Interpretation& in, size_t i) {
  const Move& m = in.moves[i];
  Vec3 s = in_plane(in.from(i), m.plane), e = in_plane(m.to, m.plane);
  if (is_arc(m.kind)) {
    Vec3 c = in_plane(m.center, m.plane);
    return arc_tangent(Vec2(s.x() - c.x(), s.y() - c.y()), m.kind == MoveKind::ArcCCW);
  }
  Vec2 d(e.x() - s.x(), e.y() - s.y());
  return d.norm() > 0 ? Vec2(d.normalized()) : Vec2(0, 0);
}

Vec2 move_end_tangent(const Interpretation& in, size_t i) {
  const Move& m = in.moves[i];
  if (!is_arc(m.kind)) return move_start_tangent(in, i);
  Vec3 e = in_plane(m.to, m.plane), c = in_plane(m.center, m.plane);
  return arc_tangent(Vec2(e.x() - c.x(), e.y() - c.y()), m.kind == MoveKind::ArcCCW);
}

double turn_deg(const Vec2& a, const Vec2& b) {
  if (a.squaredNorm() == 0 || b.squaredNorm() == 0) return 0;
  return rad_to_deg(std::atan2(std::abs(cross2(a, b)), a.dot(b)));
}


PathComparison compare_paths(const Program& a, const Interpretation& ia, const Program& b,
                             const Interpretation& ib, const CompareOptions& opt) {
  PathComparison r;
  const double chord_mm = std::max(opt.tolerance_mm * kReadingShare / 2, 1e-6);
  size_t i = 0;  // next input move
  std::vector<Vec3> pts;
  std::vector<Vec2> chord_ends;
  std::vector<size_t> move_of_point;  // the input move each of `pts` lies on (its end, for a vertex)
  long prev_j = -1;          // previous output feed move, for joints
  bool prev_replaced = false;
  // Whether any extra axis (A/B/C, U/V/W) moves anywhere in the input: only then are they
  // measured along each output move that replaces several input moves.
  const bool extra_move = extra_axes_move(ia);
  if (opt.extrusion_variance >= 0) r.extrusion_allowed_share = opt.extrusion_variance + kExtrusionRateSlack;
  for (size_t j = 0; j < ib.moves.size(); ++j) {
    const Move& mb = ib.moves[j];
    // Find the input move that ends where this output move ends.
    size_t k = i;
    while (k < ia.moves.size() && !same_point(ia.moves[k].to, mb.to)) ++k;
    if (k >= ia.moves.size()) {
      r.matched = false;
      r.mismatch_line_b = b.blocks[mb.block].line;
      r.mismatch = fmt::format("output line {} ends at X{:.4f} Y{:.4f} Z{:.4f}, which is not on the input path after input line {}",
                               b.blocks[mb.block].line, mb.to[kX], mb.to[kY], mb.to[kZ],
                               i < ia.moves.size() ? a.blocks[ia.moves[i].block].line : 0);
      return r;
    }
    // Input moves after it that go nowhere at its feed belong to it too (a fit steps over
    // them), less as many as the output has such moves of its own next (those written back
    // as they were: the last ones). One at another feed starts the next run, whose first
    // output move stands for it.
    if (is_feed(mb.kind)) {
      size_t repeats_a = 0, repeats_b = 0;
      while (k + 1 + repeats_a < ia.moves.size() && ia.goes_nowhere(k + 1 + repeats_a)) ++repeats_a;
      while (j + 1 + repeats_b < ib.moves.size() && ib.goes_nowhere(j + 1 + repeats_b)) ++repeats_b;
      for (size_t taken = 0; taken + repeats_b < repeats_a && ia.moves[k + 1].feed_mm_min == mb.feed_mm_min; ++taken) ++k;
    }
    // What the stretch i..k holds: a rapid, or a move whose path is not known, stands for
    // one input move of its kind (after moves that go nowhere); a feed move for feed moves.
    if (!is_feed(mb.kind) || !mb.known) {
      r.covers_path = r.covers_path && ia.moves[k].kind == mb.kind && ia.moves[k].known == mb.known &&
                      ia.moves_going(i, k) == 0;
    } else {
      for (size_t q = i; q <= k && r.covers_path; ++q)
        r.covers_path = ia.goes_nowhere(q) || (is_feed(ia.moves[q].kind) && ia.moves[q].known);
    }
    // Replaced: it stands for several input moves (that go somewhere), or for one that it
    // is not (a line the fit wrote as an arc), so its joints are the fit's, not the input's own.
    bool replaced = ia.moves_going(i, k + 1) > 1;
    if (!replaced && is_feed(mb.kind))
      for (size_t q = i; q <= k; ++q) {
        const Move& ma = ia.moves[q];
        if (ia.goes_nowhere(q)) continue;
        replaced = is_arc(ma.kind) != is_arc(mb.kind) ||
                   (is_arc(mb.kind) && (ma.kind != mb.kind || (ma.center - mb.center).norm() > kSamePointMm));
      }
    if (is_feed(mb.kind) && mb.known) {
      ++r.moves_b;
      // The output move keeps the feed and the S (spindle speed, laser power) of every input
      // move it stands for.
      for (size_t q = i; q <= k; ++q) {
        const Move& ma = ia.moves[q];
        if (!is_feed(ma.kind) || (ma.feed_mm_min == mb.feed_mm_min && ma.spindle == mb.spindle)) continue;
        r.matched = false;
        r.mismatch_line_b = b.blocks[mb.block].line;
        r.mismatch = ma.feed_mm_min != mb.feed_mm_min
                         ? fmt::format("output line {} moves at F{} where input line {} moves at F{}",
                                       b.blocks[mb.block].line, mb.feed_mm_min, a.blocks[ma.block].line, ma.feed_mm_min)
                         : fmt::format("output line {} moves at S{} where input line {} moves at S{}",
                                       b.blocks[mb.block].line, mb.spindle, a.blocks[ma.block].line, ma.spindle);
        return r;
      }
      // The input stretch i..k as points in the output move's plane.
      pts.clear();
      pts.push_back(in_plane(ia.from(i), mb.plane));
      move_of_point.assign(1, i);
      bool input_is_same_arc = !replaced && is_arc(ia.moves[i].kind) && is_arc(mb.kind) &&
                               ia.moves[i].kind == mb.kind &&
                               (ia.moves[i].center - mb.center).norm() <= kSamePointMm;
      double sagitta_mm = 0;  // how far the input's chords lie from its arcs
      for (size_t q = i; q <= k; ++q) {
        if (is_feed(ia.moves[q].kind)) ++r.moves_a;
        // (A repeat adds no point: the fit steps over it, and a vertex twice would read as
        // the path turning back.)
        if (!input_is_same_arc && !ia.goes_nowhere(q))
          sagitta_mm = std::max(sagitta_mm, append_path(ia, q, mb.plane, chord_mm, pts));
        move_of_point.resize(pts.size(), q);
      }
      Deviation d;
      double wrong_side_mm = 0;
      std::optional<ArcGeom> arc;
      if (input_is_same_arc) {
        d.max_mm = 0;
      } else if (is_arc(mb.kind)) {
        arc = arc_of_move(ib, j);
        d = arc_deviation(pts, *arc);
        wrong_side_mm = wrong_side_of_arc_mm(pts, arc->center, arc->sweep > 0, opt.band_side);
      } else {
        d = line_deviation(pts);
        wrong_side_mm = wrong_side_of_line_mm(pts, opt.band_side);
      }
      if (opt.executed.moves_on_chords()) {
        bool input_arcs = false;
        for (size_t q = i; q <= k; ++q) input_arcs = input_arcs || is_arc(ia.moves[q].kind);
        std::optional<double> executed_mm;
        if (input_is_same_arc) {
          executed_mm = 0;  // the same arc from the same ends: the same chords
        } else if (!input_arcs && d.ordered) {
          executed_mm = arc ? executed_arc_bound_mm(ib, j, *arc, opt.executed, pts, chord_ends) : d.max_mm;
        }
        if (!executed_mm) {
          r.covers_path = false;
        } else if (*executed_mm > r.max_executed_mm) {
          r.max_executed_mm = *executed_mm;
          r.executed_line_b = b.blocks[mb.block].line;
          r.executed_line_a = a.blocks[ia.moves[i].block].line;
          r.executed_point = from_plane(pts.front(), mb.plane);
        }
      }
      // The extra axes at each input vertex inside the output move, against the output move
      // carrying them from its start to its end where it passes nearest the vertex.
      if (extra_move && replaced)
        for (size_t q = i; q < k; ++q) {
          const AxisValues& v = ia.moves[q].to;
          const auto [off, ax] = extra_axes_gap(ib, j, Vec3(v[kX], v[kY], v[kZ]), v, kCheckNearShare * opt.tolerance_mm);
          if (off <= r.max_extra_axis) continue;
          r.max_extra_axis = off;
          r.extra_axis = ax;
          r.extra_axis_line_a = a.blocks[ia.moves[q].block].line;
          r.extra_axis_line_b = b.blocks[mb.block].line;
        }
      // Each input move's E per mm against the output move's, which extrudes evenly.
      if (opt.extrusion_variance >= 0 && replaced && mb.to[kE] != ib.from(j)[kE]) {
        const double len_b = move_length_mm(ib, j);
        const double rate_b = len_b > kLengthEpsMm ? std::abs(mb.to[kE] - ib.from(j)[kE]) / len_b : 0.0;
        for (size_t q = i; q <= k; ++q) {
          if (ia.goes_nowhere(q)) continue;
          const double len_a = move_length_mm(ia, q);
          if (len_a <= kLengthEpsMm) continue;
          const double rate_a = std::abs(ia.moves[q].to[kE] - ia.from(q)[kE]) / len_a;
          const double share = std::abs(rate_a - rate_b) / std::max(rate_a, rate_b);
          if (share <= r.max_extrusion_rate_share) continue;
          r.max_extrusion_rate_share = share;
          r.extrusion_line_a = a.blocks[ia.moves[q].block].line;
          r.extrusion_line_b = b.blocks[mb.block].line;
        }
      }
      if (wrong_side_mm > r.max_wrong_side_mm) {
        r.max_wrong_side_mm = wrong_side_mm;
        r.wrong_side_line_b = b.blocks[mb.block].line;
        r.wrong_side_line_a = a.blocks[ia.moves[i].block].line;
      }
      if (!d.ordered) d.max_mm = std::max(d.max_mm, opt.tolerance_mm * 2 + 1.0);  // the path runs backwards
      // Input arcs too big for their chords to follow at the measure's precision: the
      // chords' distance counted against the output, as the arc could lie that much away.
      if (sagitta_mm > chord_mm) d.max_mm += sagitta_mm;
      if (d.max_mm > r.max_deviation_mm) {
        r.max_deviation_mm = d.max_mm;
        r.worst_line_b = b.blocks[mb.block].line;
        // The input move the worst point lies on (a vertex: the move that ends there).
        const size_t at = std::min(d.at_index, pts.size() - 1);
        r.worst_line_a = a.blocks[ia.moves[move_of_point[at]].block].line;
        r.worst_point = from_plane(pts[at], mb.plane);
      }
      // Tangency at the joint with the previous output feed move, judged by the input's
      // vertices beside the joint, and one further out, past moves that go nowhere.
      std::optional<size_t> v_before, v_after;
      if (prev_j == long(j) - 1 && prev_j >= 0 && (replaced || prev_replaced) && ib.moves[prev_j].plane == mb.plane &&
          !ia.moves[i].entered &&
          (v_before = ia.vertex_beside(i, -1)) && (v_after = ia.vertex_beside(i, +1))) {
        // The plane the joint was made in: where both moves were fitted, else the output's.
        Plane pl = mb.plane;
        if (!opt.fitted_plane.empty() && opt.fitted_plane[*v_before] == opt.fitted_plane[i]) pl = opt.fitted_plane[i];
        Vec3 before = in_plane(ia.from(*v_before), pl);
        Vec3 at = in_plane(ia.from(i), pl);
        Vec3 after = in_plane(ia.from(*v_after), pl);
        // Whether the neighbours are corners.
        std::optional<Vec3> before2, after2;
        if (auto u = ia.vertex_beside(*v_before, -1)) before2 = in_plane(ia.from(*u), pl);
        if (auto u = ia.vertex_beside(*v_after, +1)) after2 = in_plane(ia.from(*u), pl);
        bool before_corner = before2 && is_corner(*before2, before, at, opt.tolerance_mm, opt.corner_angle_deg);
        bool after_corner = after2 && is_corner(at, after, *after2, opt.tolerance_mm, opt.corner_angle_deg);
        if (!is_corner(before, at, after, opt.tolerance_mm, opt.corner_angle_deg) &&
            !is_corner_beside_corner(before2 ? &*before2 : nullptr, before, at, after, after2 ? &*after2 : nullptr,
                                     before_corner, after_corner, opt.tolerance_mm)) {
          ++r.smooth_joints;
          // (Only lines are written in another plane than the one they were fitted in.)
          auto line_in_plane = [&](size_t q) {
            const Vec3 step = in_plane(ib.moves[q].to, pl) - in_plane(ib.from(q), pl);
            return Vec2(step.x(), step.y());
          };
          const double kink = pl == mb.plane ? turn_deg(move_end_tangent(ib, size_t(prev_j)), move_start_tangent(ib, j))
                                             : turn_deg(line_in_plane(size_t(prev_j)), line_in_plane(j));
          r.max_smooth_kink_deg = std::max(r.max_smooth_kink_deg, kink);
          if (kink > opt.g1_angle_deg) {
            ++r.smooth_joints_over_g1;
            r.kink_lines.push_back(a.blocks[ia.moves[ia.joint_move(i)].block].line);
          }
        }
      }
      prev_j = long(j);
      prev_replaced = replaced;
    } else {
      prev_j = -1;
    }
    i = k + 1;
  }
  // Input moves after the last output move: none may go anywhere.
  r.covers_path = r.covers_path && ia.moves_going(i, ia.moves.size()) == 0;
  return r;
}

}  // namespace arcpress
