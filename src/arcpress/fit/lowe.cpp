// SPDX-License-Identifier: GPL-3.0-or-later
// Seed 000 (--method lowe): Lowe's 1987 line detection splits the stretch at its
// breakpoints, then arcs are fitted over runs of the lines.
#include "arcpress/fit/run_fitter.hpp"

namespace arcpress::fit_detail {

/// Seed 000's line detection (Lowe 1987): the stretch from `a` to `limit` is split
/// recursively at the vertex farthest from the chord, and each piece is rated by its
/// significance, largest deviation over length (lower is more significant). Bottom up, a
/// piece stands for itself where it is inside the band, has no change of extrusion rate
/// inside, and is at least as significant as the most significant piece below it; else it
/// stands for its pieces. So the split adapts to the scale of the shape: a straight
/// stretch stays whole however noisy within the band, a curve is cut down to pieces of
/// kLoweMinMoves moves, whose ends the arcs may then take. The breakpoints, `a` first.
std::vector<uint32_t> RunFitter::lowe_breaks(uint32_t a, uint32_t limit) const {
  struct Piece {
    uint32_t i, j;
    uint32_t at;          // where it splits: the farthest vertex, or the first change of rate
    double significance;  // largest deviation / length (lower: more significant)
    bool must_split;      // outside the band, or a change of extrusion rate inside
    int left = -1, right = -1;
    double best = 0;    // the most significant significance it stands for
    bool whole = true;  // stands for itself
  };
  std::vector<Piece> pieces;
  auto add = [&](uint32_t i, uint32_t j) {
    double worst = 0;
    uint32_t at = i + 1;
    for (uint32_t m = i + 1; m < j; ++m)
      if (double d = point_segment_distance(p_[m], p_[i], p_[j]); d > worst) {
        worst = d;
        at = m;
      }
    const bool soft = soft_between(i, j);
    if (soft)
      for (at = i + 1; !soft_[at];) ++at;
    const double len = (p_[j] - p_[i]).norm();
    const double sig = worst == 0 ? 0 : len > kLengthEpsMm ? worst / len : kInf;
    pieces.push_back({i, j, at, sig, worst > eps_ || soft});
    return static_cast<int>(pieces.size()) - 1;
  };
  add(a, limit);
  // Top down: pieces are split until they are single moves, or short enough and inside.
  for (size_t n = 0; n < pieces.size(); ++n) {
    const Piece pc = pieces[n];
    if (pc.j - pc.i <= 1 || (!pc.must_split && pc.j - pc.i <= kLoweMinMoves)) continue;
    const int l = add(pc.i, pc.at), r = add(pc.at, pc.j);
    pieces[n].left = l;
    pieces[n].right = r;
  }
  // Bottom up (children come after their parents): which pieces stand for themselves.
  for (size_t n = pieces.size(); n-- > 0;) {
    Piece& pc = pieces[n];
    pc.best = pc.significance;
    if (pc.left < 0) continue;
    const double below = std::min(pieces[pc.left].best, pieces[pc.right].best);
    pc.whole = !pc.must_split && pc.significance <= below;
    if (!pc.whole) pc.best = below;
  }
  std::vector<uint32_t> breaks{a};
  std::vector<int> todo{0};
  while (!todo.empty()) {
    const Piece& pc = pieces[todo.back()];
    todo.pop_back();
    if (pc.whole) {
      breaks.push_back(pc.j);
    } else {
      todo.push_back(pc.right);
      todo.push_back(pc.left);
    }
  }
  return breaks;
}

/// Seed 000: Lowe-style line detection, then arcs over runs of the lines. The breakpoints
/// come from lowe_breaks(); then, from each, a primitive grows over as many following
/// breakpoints as a line or the arc through both end points (centre on the chord's
/// bisector, least squares) keeps inside the band. Then the joints are made tangent where
/// the band allows (make_tangent()).
std::vector<Chosen> RunFitter::lowe_chain(uint32_t a, uint32_t limit, size_t& forced) const {
  std::vector<uint32_t> breaks = lowe_breaks(a, limit);
  std::vector<Chosen> chain;
  for (size_t k = 0; k + 1 < breaks.size();) {
    const uint32_t from = breaks[k];
    std::optional<Chosen> best = make_line(from, breaks[k + 1], Vec2(1, 0));
    if (!best) {  // a soft split that is not straight: the input's own moves
      best = input_move(from);
      breaks.insert(breaks.begin() + k + 1, from + 1);
    }
    size_t next = k + 1;
    for (size_t j = k + 2; j < breaks.size(); ++j) {
      if (soft_between(from, breaks[j])) break;
      std::optional<Chosen> c = make_line(from, breaks[j], best->end_tangent);
      if (!c) c = through_ends(from, breaks[j]);
      if (!c) break;
      best = c;
      next = j;
    }
    chain.push_back(*best);
    k = next;
  }
  make_tangent(a, chain, forced);
  return chain;
}

}  // namespace arcpress::fit_detail
