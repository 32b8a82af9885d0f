// SPDX-License-Identifier: GPL-3.0-or-later
// The default method (--method arcs): a beam search over chains of tangent primitives,
// layer k holding the best chains of k primitives, guided by the greedy chain.
#include "arcpress/fit/scan_ends.hpp"

namespace arcpress::fit_detail {

/// The G1 chain from `a` to `limit` with the fewest primitives a beam search finds. Layer k
/// holds the chains of k primitives, at most `beam_width` of them, those reaching furthest
/// (in the next step, or with this one) with distinct end tangents; each is extended along
/// its end tangent and along it turned by the whole joint allowance (kJointShare of the G1
/// angle) each way, and by half of it where the input runs straight ahead (for lines): the
/// chains' own spread of tangents covers the arcs' turns between. The first chain reaching
/// `limit` wins. Where the tangent at `a` is free, the roots are start_tangents(). The
/// greedy chain (read off `greedy` up to its first kink, or chosen again when null) is
/// always kept. When no chain goes on tangentially, the one reaching furthest is
/// returned (empty when none leaves `a`), and the caller takes a kink there.
std::vector<Chosen> RunFitter::beam_chain(uint32_t a, uint32_t limit, GreedyWalk* greedy,
                                          std::span<const Seed> seeds) const {
  std::vector<Node>& nodes = s_.nodes;
  std::vector<int>& layer = s_.layer;
  std::vector<int>& next = s_.next;
  std::vector<std::pair<int, uint32_t>>& root_seeds = s_.root_seeds;
  nodes.clear();
  layer.clear();
  root_seeds.clear();
  if (seeds.empty()) {
    roots(a, limit, s_.roots);
    for (const Vec2& T : s_.roots) nodes.push_back({{}, -1, a, T});
    for (int i = 0; i < static_cast<int>(nodes.size()); ++i) layer.push_back(i);
  }
  // Seeds join the beam in the layer of their prefix's length; the greedy chain starts from
  // the last (-3: not yet).
  size_t depth = seeds.empty() ? 0 : seeds.front().prefix.size();
  size_t next_seed = 0;
  int guide_root = seeds.empty() ? 0 : -1;
  auto join = [&] {
    for (; next_seed < seeds.size() && seeds[next_seed].prefix.size() == depth; ++next_seed) {
      roots(seeds[next_seed].v, limit, s_.roots);
      if (next_seed + 1 == seeds.size() && !s_.roots.empty()) guide_root = static_cast<int>(nodes.size());
      for (const Vec2& T : s_.roots) {
        root_seeds.push_back({static_cast<int>(nodes.size()), uint32_t(next_seed)});
        layer.push_back(static_cast<int>(nodes.size()));
        nodes.push_back({{}, -1, seeds[next_seed].v, T});
      }
    }
  };
  // The chain that ends at node `id`, with its seed's prefix.
  auto whole = [&](int id) {
    std::vector<Chosen> c = chain_to(nodes, id);
    if (seeds.empty() || c.empty()) return c;
    int root = id;
    while (nodes[root].parent >= 0) root = nodes[root].parent;
    const auto at = std::lower_bound(root_seeds.begin(), root_seeds.end(), std::pair(root, uint32_t(0)));
    const std::vector<Chosen>& prefix = seeds[at->second].prefix;
    c.front().kinked = true;
    c.insert(c.begin(), prefix.begin(), prefix.end());
    return c;
  };
  const size_t width = o_.beam_width;
  // Candidates are scored first and checked exactly only when the beam keeps them.
  std::vector<Made>& made = s_.made;
  std::vector<Candidate>& out = s_.beam_out;
  std::vector<SeenEnd>& seen = s_.seen;
  std::vector<std::pair<uint64_t, uint64_t>>& keys = s_.keys;
  std::vector<uint64_t>& packed_keys = s_.packed_keys;
  std::vector<std::pair<uint32_t, Vec2>>& expanded = s_.expanded;
  std::vector<uint64_t>& order = s_.order;
  std::vector<int8_t>& straight = s_.straight;  // per vertex from `a`: straight_ahead(), -1 not yet known
  straight.assign(limit - a + 1, -1);
  int furthest = -1;
  int guide = seeds.empty() ? -1 : -3;  // the node the greedy chain would be at: the beam never does worse
  size_t step = 0;
  while (!layer.empty() || next_seed < seeds.size()) {
    join();
    if (guide == -3 && guide_root >= 0) guide = -1;
    made.clear();
    // The greedy chain's next primitive: read off `greedy` (whose first kink ends it) when
    // given, else chosen again.
    std::optional<Chosen> g;
    if (guide == -1) {
      guide = guide_root;
      const uint32_t v = nodes[guide].v;
      if (greedy) {
        if (const Chosen* c = greedy->at(0); c && !c->kinked) g = *c;
      } else {
        g = arrives_along(v) ? best_near(v, *in_tangent_, limit) : std::optional<Chosen>(best_free(v, limit));
      }
    } else if (guide >= 0) {
      if (greedy) {
        if (const Chosen* c = greedy->at(step); c && !c->kinked) g = *c;
      } else {
        g = best_near(nodes[guide].v, nodes[guide].T, limit);
      }
    }
    ++step;
    // Each chain goes on along its end tangent or turned by all of the joint allowance
    // either way, and where the input runs straight ahead by half of it too: a line's chord
    // lies within a quarter of the G1 angle of the tangent scanned, so whole turns alone
    // would offer no line whose chord lies between. A tangent another chain at the same
    // vertex follows already is not followed twice.
    expanded.clear();
    for (int i : layer) {
      const Node nd = nodes[i];
      // (Roots take no turns; whether the input runs straight is worked out once a vertex.)
      int8_t& memo = straight[nd.v - a];
      if (nd.parent >= 0 && memo < 0) memo = straight_ahead(nd.v, limit);
      const bool straight_on = nd.parent >= 0 && memo > 0;
      const size_t turns = nd.parent < 0 ? 0 : joint_turns_.size() + (straight_on ? 2 : 0);
      for (size_t t = 0; t <= turns; ++t) {
        const Turn* turn = t == 0                         ? nullptr
                           : t <= joint_turns_.size() ? &joint_turns_[t - 1]
                           : t == turns - 1           ? &half_left_
                                                      : &half_right_;
        const Vec2 T = turn ? (*turn)(nd.T) : nd.T;
        auto same = [&](const auto& x) { return x.first == nd.v && same_tangent_cone_.holds(x.second, T); };
        if (std::any_of(expanded.begin(), expanded.end(), same)) continue;
        expanded.push_back({nd.v, T});
        const GuideScan* kept = pick(nd.v, T, limit, o_.beam_branch, out, true, i == guide);
        for (const Candidate& cd : out) {
          if (cd.e >= limit) {
            if (auto c = made_from(nd, T, cd)) {
              nodes.push_back({*c, i, c->prim.end_vertex, c->end_tangent});
              return whole(static_cast<int>(nodes.size()) - 1);
            }
            continue;
          }
          made.push_back({i, T, cd, unchecked(nd.v, T, cd), kept});
        }
      }
    }
    // Half the beam goes to the chains whose next step reaches furthest, two places to
    // those whose primitive itself ends furthest, the rest to those heading where the input
    // heads (then reaching furthest): each alone loses chains the others find. (A chain
    // that must pass a narrow place, plum's inner tips, with the one arc that fits there
    // reaches least after its primitive ends at the entrance, and the chains that turn in
    // sooner with a longer reach get stuck past it: 53 blocks for plum at 0.003 mm, 49 with
    // the two places.)
    next.clear();
    seen.clear();
    if (g) {
      nodes.push_back({*g, guide, g->prim.end_vertex, g->end_tangent});
      guide = static_cast<int>(nodes.size()) - 1;
      if (g->prim.end_vertex >= limit) return whole(guide);
      next.push_back(guide);
      if (furthest < 0 || nodes[furthest].v < g->prim.end_vertex) furthest = guide;
    } else if (guide != -3) {
      guide = -2;
    }
    // A chain one primitive short of `limit` along its own end tangent ends the search in the
    // next layer. Ranking this layer would first scan ahead from every candidate, while the
    // test of the one end fails at the first vertex off its circle; so such a chain is looked
    // for first, in the order the next layer would try it: the greedy chain's, then those
    // ending furthest. (Chains that finish only with a turn at the joint are still found the
    // usual way, a layer on.)
    auto finish = [&](int id) -> std::optional<std::vector<Chosen>> {
      const Node nd = nodes[id];
      const auto cd = finish_from(nd.v, nd.T, limit);
      if (!cd) return std::nullopt;
      auto c = made_from(nd, nd.T, *cd);
      if (!c) return std::nullopt;
      nodes.push_back({*c, id, c->prim.end_vertex, c->end_tangent});
      return whole(static_cast<int>(nodes.size()) - 1);
    };
    if (guide >= 0)
      if (auto done = finish(guide)) return *done;
    // Furthest end first, ties in the order made: one integer each, sorted in place.
    order.clear();
    for (uint32_t k = 0; k < made.size(); ++k)
      order.push_back(uint64_t(UINT32_MAX - made[k].c.prim.end_vertex) << 32 | k);
    std::sort(order.begin(), order.end());
    for (uint64_t key : order) {
      Made& m = made[uint32_t(key)];
      if (!finish_from(m.c.prim.end_vertex, m.c.end_tangent, limit)) continue;
      auto c = made_from(nodes[m.from], m.T, m.cand);
      if (!c) {
        m.from = -1;  // (failed: not checked again when ranked)
        continue;
      }
      nodes.push_back({*c, m.from, c->prim.end_vertex, c->end_tangent});
      if (auto done = finish(static_cast<int>(nodes.size()) - 1)) return *done;
      nodes.pop_back();
    }
    for (Made& m : made)
      if (m.from >= 0) m.sc = m.guide ? guide_score(*m.guide, m.c, limit) : score(m.c, limit);
    // A layer keeps few of its candidates, so most are never put in order: each ranking
    // packs its keys into integers and takes them best first from a heap, ties in the order
    // made. A tangent's bin is worked out only when another kept chain ends at its vertex.
    // Keeps made[k] when it passes the exact check and no kept chain ends at its vertex
    // with a tangent in the same bin.
    auto take = [&](uint32_t k) {
      Made& m = made[k];
      const uint32_t e = m.c.prim.end_vertex;
      std::optional<long> bin;
      for (SeenEnd& s : seen) {
        if (s.v != e) continue;
        if (!bin) bin = tangent_bin(m.c.end_tangent, kEndBinShare);
        if (!s.bin) s.bin = tangent_bin(s.T, kEndBinShare);
        if (*s.bin == *bin) return;
      }
      auto c = made_from(nodes[m.from], m.T, m.cand);
      const int from = m.from;
      m.from = -1;
      if (!c) return;
      seen.push_back({e, m.c.end_tangent, bin});
      nodes.push_back({*c, from, e, c->end_tangent});
      int id = static_cast<int>(nodes.size()) - 1;
      if (furthest < 0 || nodes[furthest].v < e) furthest = id;
      next.push_back(id);
    };
    // A ranking orders by (flag, x, y) from each score, then by the order made. Where the
    // vertices and the candidates fit in 21 bits each, as they do but on runs of more than
    // two million moves, the key is one 64-bit integer; else two.
    const bool packed = limit + 2 < (uint32_t(1) << kKeyBits) && made.size() < (size_t(1) << kKeyBits);
    constexpr uint64_t kIndexMask = (uint64_t(1) << kKeyBits) - 1;
    // One ranking in `heap`: key_of(fields, k) makes a key, place_of(key) reads k back.
    auto rank = [&](auto& heap, size_t count, auto fields, auto key_of, auto place_of) {
      heap.clear();
      for (uint32_t k = 0; k < made.size(); ++k)
        if (made[k].from >= 0) heap.push_back(key_of(fields(made[k].sc), k));  // not yet kept, nor failed
      std::make_heap(heap.begin(), heap.end());
      for (auto end = heap.end(); end != heap.begin() && next.size() < count; --end) {
        std::pop_heap(heap.begin(), end);
        take(place_of(*(end - 1)));
      }
    };
    auto keep_best = [&](size_t count, auto fields) {
      if (packed) {
        rank(
            packed_keys, count, fields,
            [&](const auto& f, uint32_t k) {
              const auto [flag, x, y] = f;
              return uint64_t(flag) << (3 * kKeyBits) | uint64_t(x) << (2 * kKeyBits) | uint64_t(y) << kKeyBits |
                     (kIndexMask - k);
            },
            [&](uint64_t key) { return uint32_t(kIndexMask - (key & kIndexMask)); });
      } else {
        rank(
            keys, count, fields,
            [](const auto& f, uint32_t k) {
              const auto [flag, x, y] = f;
              return std::pair(uint64_t(flag) << 32 | x, uint64_t(y) << 32 | (UINT32_MAX - k));
            },
            [](const std::pair<uint64_t, uint64_t>& key) { return UINT32_MAX - uint32_t(key.second); });
      }
    };
    using Fields = std::tuple<uint32_t, uint32_t, uint32_t>;
    keep_best(width / 2, [](const Score& x) { return Fields{0, x.reach, x.end}; });
    keep_best(width / 2 + kFurthestEnds, [](const Score& x) { return Fields{0, x.end, x.reach}; });
    keep_best(width, [](const Score& x) { return Fields{x.on_course, x.reach, x.end}; });
    layer.swap(next);
    ++depth;
  }
  return furthest < 0 ? std::vector<Chosen>{} : whole(furthest);
}

/// The one-primitive finish from vertex `v` along exactly `T` to `limit`, as the scan
/// offers it (not yet checked exactly), or nothing.
std::optional<Candidate> RunFitter::finish_from(uint32_t v, const Vec2& T, uint32_t limit) const {
  if (v >= limit || !through_candidate(v, T, limit)) return std::nullopt;
  // (The scan holds the end to the options' limits and to a fixed move after it.)
  std::optional<Candidate> last;
  scan_ends(v, T, limit, [&](const Candidate& c) { last = c; });
  if (!last || last->e != limit) return std::nullopt;
  return last;
}

/// Whether the input runs straight from vertex v for kStraightAheadMm (or to `limit`): every
/// vertex up to there within the band of the chord there.
bool RunFitter::straight_ahead(uint32_t v, uint32_t limit) const {
  uint32_t e = v + 1;
  while (e < limit && e - v < kLocalMoves && (q(e) - q(v)).squaredNorm() < kStraightAheadMm * kStraightAheadMm) ++e;
  const Vec2 chord = q(e) - q(v);
  const double len = chord.norm();
  if (len <= kLengthEpsMm) return false;
  for (uint32_t m = v + 1; m < e; ++m)
    if (std::abs(cross2(chord, q(m) - q(v))) > eps_ * len) return false;
  return true;
}

/// Candidate `cd` from node `nd` along `T` (its tangent, or that turned at the joint),
/// checked exactly, and held to the joint allowance: a line's chord may lie off T by the
/// line allowance, on top of the turn. (The beam's and the layered search's.)
std::optional<Chosen> RunFitter::made_from(const Node& nd, const Vec2& T, const Candidate& cd) const {
  auto c = make(nd.v, T, cd);
  if (c && !joint_cone_.holds(nd.T, start_tangent(*c, nd.v))) return std::nullopt;
  return c;
}

/// The beam search's chain from `a` to `limit`. Where no chain goes on tangentially, the
/// tangent breaks and the search starts again from the seeds kink_seeds() finds.
std::vector<Chosen> RunFitter::beam_stretch(uint32_t a, uint32_t limit, GreedyWalk& greedy, size_t& forced) const {
  std::vector<Chosen> part = beam_chain(a, limit, &greedy);
  if (part.empty()) {  // (the first part breaks the tangent only when nothing leaves along it)
    part.push_back(best_free(a, limit));
    part.front().kinked = arrives_along(a);
    forced += part.front().kinked;
  }
  std::vector<Seed> seeds, next;
  // The primitives every seed's prefix starts with, moved here once rather than copied with
  // each seed at each kink (prefixes, and `part`, are what follows them).
  std::vector<Chosen> settled;
  auto same = [](const Chosen& x, const Chosen& y) {
    return x.prim.end_vertex == y.prim.end_vertex && x.prim.kind == y.prim.kind && x.prim.ccw == y.prim.ccw &&
           x.prim.center == y.prim.center && x.end_tangent == y.end_tangent && x.kinked == y.kinked;
  };
  while (part.back().prim.end_vertex < limit) {
    kink_seeds(part, seeds, next);
    seeds.swap(next);
    ++forced;
    size_t common = seeds.front().prefix.size();
    for (const Seed& sd : seeds) {
      size_t k = 0;
      while (k < common && k < sd.prefix.size() && same(sd.prefix[k], seeds.front().prefix[k])) ++k;
      common = k;
    }
    settled.insert(settled.end(), seeds.front().prefix.begin(), seeds.front().prefix.begin() + long(common));
    for (Seed& sd : seeds) sd.prefix.erase(sd.prefix.begin(), sd.prefix.begin() + long(common));
    uint32_t lowest = limit;
    for (const Seed& sd : seeds) lowest = std::min(lowest, sd.v);
    std::vector<Chosen> after = beam_chain(lowest, limit, nullptr, seeds);
    if (after.empty()) {  // nothing leaves any seed: the one where the chain stalled
      after = seeds.back().prefix;
      after.push_back(best_free(seeds.back().v, limit));
      after.back().kinked = true;
    }
    part.swap(after);
  }
  settled.insert(settled.end(), part.begin(), part.end());
  return settled;
}

void RunFitter::kink_seeds(const std::vector<Chosen>& part, std::span<const Seed> seeds, std::vector<Seed>& out) const {
  const std::vector<Node>& nodes = s_.nodes;
  const uint32_t end = part.back().prim.end_vertex;
  const uint32_t from = end > kKinkSeedMoves ? end - kKinkSeedMoves : 0;
  // Per node, its chain's length with the prefix of its seed, and the root it grew from.
  std::vector<size_t>& length = s_.chain_length;
  std::vector<int>& root = s_.root_of;
  std::vector<int>& shortest = s_.shortest;  // per vertex from `from`: the node with the shortest chain
  length.resize(nodes.size());
  root.resize(nodes.size());
  shortest.assign(end - from, -1);
  for (size_t i = 0; i < nodes.size(); ++i) {
    const Node& nd = nodes[i];
    if (nd.parent < 0) {
      root[i] = int(i);
      length[i] = 0;
      if (!seeds.empty()) {
        const auto at = std::lower_bound(s_.root_seeds.begin(), s_.root_seeds.end(), std::pair(int(i), uint32_t(0)));
        length[i] = seeds[at->second].prefix.size();
      }
      continue;
    }
    root[i] = root[nd.parent];
    length[i] = length[nd.parent] + 1;
    if (nd.v < from || nd.v >= end || length[i] > part.size()) continue;
    int& s = shortest[nd.v - from];
    if (s < 0 || length[i] < length[size_t(s)]) s = int(i);
  }
  out.clear();
  for (int id : shortest) {
    if (id < 0) continue;
    Seed sd{nodes[id].v, {}};
    if (!seeds.empty()) {
      const auto at = std::lower_bound(s_.root_seeds.begin(), s_.root_seeds.end(), std::pair(root[id], uint32_t(0)));
      sd.prefix = seeds[at->second].prefix;
    }
    std::vector<Chosen> own = chain_to(nodes, id);
    if (!seeds.empty()) own.front().kinked = true;  // (it left its seed after a kink)
    sd.prefix.insert(sd.prefix.end(), own.begin(), own.end());
    out.push_back(std::move(sd));
  }
  // Shortest prefixes first; where the chain stalled, last (the greedy chain starts there).
  std::stable_sort(out.begin(), out.end(), [](const Seed& x, const Seed& y) { return x.prefix.size() < y.prefix.size(); });
  out.push_back({end, part});
}

}  // namespace arcpress::fit_detail
