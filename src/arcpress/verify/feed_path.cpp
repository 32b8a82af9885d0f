// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/verify/feed_path.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace arcpress {
namespace {

/// Move i exactly: kind, plane, turns, start, end and centre.
std::array<double, 12> move_key(const Interpretation& in, size_t i) {
  const Move& m = in.moves[i];
  const AxisValues& f = in.from(i);
  const bool arc = is_arc(m.kind);
  return {double(int(m.kind)) * 1000 + double(int(m.plane)) * 100 + double(m.turns), f[kX], f[kY], f[kZ], m.to[kX],
          m.to[kY], m.to[kZ], arc ? m.center.x() : 0.0, arc ? m.center.y() : 0.0, arc ? m.center.z() : 0.0, 0, 0};
}

}  // namespace

std::vector<uint32_t> FeedPath::distinct_segments() const {
  auto key_of = [&](size_t s) {
    const Vec3 pa = a(s), pb = b(s);
    std::array<double, 12> k{pa.x(), pa.y(), pa.z(), pb.x(), pb.y(), pb.z(), 0, 0, 0, 0, 0, 0};
    if (curved(s)) {
      const FlatArc& c = arc(s);
      k[6] = 1 + double(int(c.plane));
      k[7] = c.center.x();
      k[8] = c.center.y();
      k[9] = c.center.z();
      k[10] = c.ccw ? c.radius_mm : -c.radius_mm;
    }
    return k;
  };
  auto hash_of = [](const std::array<double, 12>& k) {
    uint64_t h = 0x9e3779b97f4a7c15ull;
    for (double d : k) {
      uint64_t bits = 0;
      std::memcpy(&bits, &d, sizeof bits);
      h = (h ^ bits) * 0xbf58476d1ce4e5b9ull;  // splitmix64's steps
      h ^= h >> 31;
    }
    return h;
  };
  size_t slots = 16;
  while (slots < 2 * size()) slots *= 2;
  constexpr uint32_t kEmpty = UINT32_MAX;
  std::vector<uint32_t> table(slots, kEmpty);
  std::vector<uint32_t> out;
  out.reserve(size());
  for (size_t s = 0; s < size(); ++s) {
    const std::array<double, 12> k = key_of(s);
    for (size_t at = hash_of(k) & (slots - 1);; at = (at + 1) & (slots - 1)) {
      if (table[at] == kEmpty) {
        table[at] = uint32_t(s);
        out.push_back(uint32_t(s));
        break;
      }
      if (key_of(table[at]) == k) break;  // a repeat of an earlier segment
    }
  }
  return out;
}

FeedPath feed_path(const Interpretation& in, double chord_mm, double tolerance_mm, bool segments) {
  FeedPath p;
  // Room for a segment and a half per move (most moves are one segment; arcs and long
  // travels are several), so the vectors are seldom grown step by step.
  const size_t room = segments ? in.moves.size() + in.moves.size() / 2 + 1 : 0;
  p.points.reserve(room);
  for (auto* v : {&p.first, &p.move_of, &p.section_of}) v->reserve(room);
  p.arc_of.reserve(room);
  std::vector<Vec3> pts;
  bool in_section = false;
  for (size_t i = 0; i < in.moves.size(); ++i) {
    const Move& m = in.moves[i];
    if (!is_feed(m.kind) || !m.known) {
      if (m.kind == MoveKind::Rapid && m.end_known) p.rapids.push_back(uint32_t(i));
      if (enters_from_unknown(m)) p.entries.push_back(uint32_t(i));
      in_section = false;
      continue;
    }
    // So far from the origin that a double holds its points more coarsely than the measure
    // needs: not measured (a program would differ from itself by its rounding). An arc's
    // points are placed from its centre, unless it is flat enough to be its chord.
    double farthest = std::max(xyz(in.from(i)).cwiseAbs().maxCoeff(), xyz(m.to).cwiseAbs().maxCoeff());
    const double centre_mm = is_arc(m.kind) ? m.center.cwiseAbs().maxCoeff() : 0.0;
    if (centre_mm > farthest && !(flat_arc_sagitta_mm(arc_of_move(in, i)) <= kFlatArcMm)) farthest = centre_mm;
    if (!(farthest <= farthest_measurable_mm(tolerance_mm))) {
      if (p.far_moves++ == 0) p.first_far_move = uint32_t(i);
      p.unmeasured.push_back(move_key(in, i));
      in_section = false;
      continue;
    }
    if (!in_section) {
      p.section_length_mm.push_back(0);
      p.section_e.push_back(0);
      p.section_e_rounding_mm.push_back(0);
      in_section = true;
    }
    ++p.feed_moves;
    uint32_t sec = uint32_t(p.section_length_mm.size() - 1);
    p.section_e[sec] += m.to[kE] - in.from(i)[kE];
    p.section_e_rounding_mm[sec] +=
        4 * std::numeric_limits<double>::epsilon() * std::max(std::abs(m.to[kE]), std::abs(in.from(i)[kE]));
    Vec3 prev = xyz(in.from(i));
    if (!segments && !is_arc(m.kind)) {  // a line: its length alone
      p.section_length_mm[sec] += (xyz(m.to) - prev).norm();
      continue;
    }
    if (!segments)  // a flat arc: its length alone, without its pieces
      if (const auto len = flat_arc_length_mm(in, i)) {
        p.section_length_mm[sec] += *len;
        continue;
      }
    // A section's first segment starts a polyline of its own.
    if (segments && (p.section_of.empty() || p.section_of.back() != sec)) p.points.push_back(prev);
    pts.clear();
    bool straight_end = false;
    const std::optional<FlatArc> arc =
        arc_pieces(in, i, tolerance_mm * kPieceSagittaShare, kPieceSweepRad, kPieceMm, kMaxPiecesPerArc, pts,
                   straight_end);
    if (arc) p.arcs.push_back(*arc);
    if (!arc) {
      const double sagitta_mm = move_path(in, i, chord_mm, pts);
      if (sagitta_mm > chord_mm) {
        // An arc too big (its radius, its turns) to follow within the measure's precision:
        // within a tenth of the band, its chords' distance is counted against the verdict;
        // beyond, it is not measured at all.
        if (sagitta_mm > kRoughShare * tolerance_mm) {
          if (p.rough_arcs++ == 0) p.first_rough_move = uint32_t(i);
          p.unmeasured.push_back(move_key(in, i));
        }
        p.chord_excess_mm = std::max(p.chord_excess_mm, std::min(sagitta_mm, kRoughShare * tolerance_mm) - chord_mm);
      }
    }
    for (size_t k = 0; k < pts.size(); ++k) {
      const Vec3& q = pts[k];
      const bool piece = arc && !(straight_end && k + 1 == pts.size());
      double len = (q - prev).norm();
      if (piece) {
        p.max_sagitta_mm = std::max(p.max_sagitta_mm, piece_sagitta_mm(*arc, prev, q));
        len = 2 * arc->radius_mm * std::asin(std::min(1.0, len / (2 * arc->radius_mm)));  // along the arc
      }
      if (!segments) {
        p.section_length_mm[sec] += len;
        prev = q;
        continue;
      }
      // Long segments are cut into pieces: an AABB over a long diagonal box is hit by
      // nearly every query (travel moves across a printed layer). (An arc's pieces are cut
      // short enough already.)
      int pieces = piece ? 1 : int(std::clamp(std::ceil(len / kPieceMm), 1.0, double(kMaxPiecesPerSegment)));
      for (int c = 1; c <= pieces; ++c) {
        Vec3 r = c == pieces ? q : Vec3(prev + (q - prev) * (double(c) / pieces));
        p.first.push_back(uint32_t(p.points.size() - 1));
        p.points.push_back(r);
        p.move_of.push_back(uint32_t(i));
        p.section_of.push_back(sec);
        p.arc_of.push_back(piece ? int32_t(p.arcs.size() - 1) : arc ? FeedPath::kClosingStep : FeedPath::kStraight);
      }
      p.section_length_mm[sec] += len;
      prev = q;
    }
  }
  return p;
}

}  // namespace arcpress
