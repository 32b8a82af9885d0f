// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/verify/executed_path.hpp"

#include <algorithm>

#include "arcpress/verify/move_geometry.hpp"

namespace arcpress {

namespace {

bool placed_arc(const Move& m) { return is_arc(m.kind) && m.known; }

}  // namespace

bool has_executed_chords(const Interpretation& in, const ArcSegmentation& rule) {
  return rule.moves_on_chords() && std::any_of(in.moves.begin(), in.moves.end(), placed_arc);
}

const Interpretation& executed_path(const Interpretation& in, const ArcSegmentation& rule, Interpretation& storage) {
  if (!has_executed_chords(in, rule)) return in;
  storage = executed_path(in, rule);
  return storage;
}

Interpretation executed_path(const Interpretation& in, const ArcSegmentation& rule) {
  if (!has_executed_chords(in, rule)) return in;
  Interpretation out = in.without_moves();
  out.moves.reserve(in.moves.size() * 2);
  std::vector<uint32_t> index_of(in.moves.size());  // input move -> its last move in `out`
  std::vector<Vec2> ends;
  for (size_t i = 0; i < in.moves.size(); ++i) {
    const Move& m = in.moves[i];
    if (placed_arc(m)) {
      const ArcGeom g = arc_of_move(in, i);
      // (A flat arc, which no chord end can be told from its chord: the chord.)
      const AxisValues& from = in.from(i);
      const auto ax = axes_of(m.plane);
      const uint32_t n = flat_arc_sagitta_mm(g) <= kFlatArcMm
                             ? 1
                             : executed_segments_read(rule, Vec2(from[ax.first], from[ax.second]), g.center,
                                                      Vec2(m.to[ax.first], m.to[ax.second]), g.sweep, g.h1 - g.h0);
      // The chord ends as the firmware computes them, in the plane's coordinates; the other
      // axes (the normal axis, E) advance evenly.
      ends.clear();
      executed_chord_ends(rule, Vec2(from[ax.first], from[ax.second]), g.center, Vec2(m.to[ax.first], m.to[ax.second]),
                          g.sweep, n, ends);
      for (uint32_t k = 1; k < n; ++k) {
        const double t = double(k) / n;
        Move c = m;
        c.kind = MoveKind::Line;
        for (int a = 0; a < kAxisCount; ++a) c.to[a] = from[a] + (m.to[a] - from[a]) * t;
        c.to[ax.first] = ends[k - 1].x();
        c.to[ax.second] = ends[k - 1].y();
        out.moves.push_back(c);
      }
      Move last = m;
      last.kind = MoveKind::Line;
      out.moves.push_back(last);
    } else {
      out.moves.push_back(m);
    }
    index_of[i] = static_cast<uint32_t>(out.moves.size() - 1);
  }
  for (int32_t& mv : out.move_of_block)
    if (mv >= 0) mv = static_cast<int32_t>(index_of[mv]);
  for (UnplacedMove& u : out.unplaced) u.move = index_of[u.move];
  return out;
}

}  // namespace arcpress
