// SPDX-License-Identifier: GPL-3.0-or-later
// The layered search (the global method's, and the default's where its chain wiggles):
// breadth first over (vertex, tangent) states, one per tangent bin in each group of
// vertices, for the fewest primitives.
#include "arcpress/fit/scan_ends.hpp"

namespace arcpress::fit_detail {

/// The G1 chain from `a` to `limit` with the fewest primitives, found breadth first over
/// states (vertex, tangent leaving it): layer k holds the states k primitives reach, and
/// each is expanded, along its tangent and along it turned by the joint's whole allowance
/// either way, by every end its curvature scan allows, each end checked exactly once.
/// To stay near-linear, a layer keeps one state per tangent bin (kTangentBinShare of the
/// G1 angle) in each vertex group (the last layer's advance over kLayerGroups), only ends
/// at or beyond the layer's furthest vertex are taken (the layer before reached the
/// others with fewer primitives), and the search gives up past kMaxStatesPerVertex states
/// per vertex. Unlike the beam, no state is dropped for scoring lower, so a chain that
/// must pass a narrow place with the one right tangent is not lost. Empty when no chain
/// reaches `limit` tangentially.
std::vector<Chosen> RunFitter::layered_chain(uint32_t a, uint32_t limit) const {
  std::vector<Node> states;
  std::vector<int> layer, next;
  std::vector<Vec2> starts;
  // Where the tangent is free, from the input's own directions fanned out, not from the
  // beam's starts: those reach further in one primitive, and the later layers, which take
  // only ends at or past the furthest vertex reached, then lose the chains that started
  // shorter (plum at 0.01 mm with the global method: 37 blocks instead of 35).
  if (arrives_along(a)) {
    roots(a, limit, starts);
  } else {
    fanned_input_tangents(a, limit, starts);
    if (auto T = into_next(a, limit)) starts.push_back(*T);
  }
  for (const Vec2& T : starts) {
    states.push_back({{}, -1, a, T});
    layer.push_back(static_cast<int>(states.size()) - 1);
  }
  const size_t max_states = kMaxStatesPerVertex * (limit - a) + states.size();
  std::unordered_set<uint64_t> seen;
  std::vector<Candidate> cand;
  uint32_t front = a, advance = 0;  // the layer's furthest vertex, and how far it moved
  while (!layer.empty()) {
    next.clear();
    uint32_t next_front = front;
    // A state reached by a primitive goes on along its end tangent, or turned at the joint
    // by all of kJointShare of the G1 angle either way and by halves of it (joint_turns_; the turns between come in through
    // the states' own spread of tangents).
    for (int i : layer) {
      const size_t turns = states[i].parent < 0 ? 0 : joint_turns_.size();
      for (size_t t = 0; t <= turns; ++t) {
        const uint32_t v = states[i].v;
        const Vec2 T = t > 0 ? joint_turns_[t - 1](states[i].T) : states[i].T;
        cand.clear();  // only the ends at or beyond the front are taken
        scan_ends(v, T, limit, [&](const Candidate& c) {
          if (c.e >= front) cand.push_back(c);
        });
        for (size_t k = cand.size(); k-- > 0;) {  // furthest first
          const Candidate& c = cand[k];
          const uint32_t group = std::max<uint32_t>(1, std::max(advance, next_front - front) / kLayerGroups);
          const Vec2 end = unchecked(v, T, c).end_tangent;
          const long bin = tangent_bin(end, kTangentBinShare);
          const uint64_t key = (uint64_t(c.e - c.e % group) << 32) | uint32_t(bin);  // group's first vertex
          if (c.e < limit && seen.count(key)) continue;
          auto made = made_from(states[i], T, c);
          if (!made) continue;
          states.push_back({*made, i, c.e, made->end_tangent});
          const int id = static_cast<int>(states.size()) - 1;
          if (c.e >= limit) return chain_to(states, id);
          seen.insert(key);
          next.push_back(id);
          next_front = std::max(next_front, c.e);
        }
      }
      if (states.size() > max_states) return {};
    }
    advance = next_front - front;
    front = next_front;
    layer.swap(next);
  }
  return {};
}

std::vector<Chosen> RunFitter::chain_to(const std::vector<Node>& nodes, int id) {
  std::vector<Chosen> chain;
  for (; nodes[id].parent >= 0; id = nodes[id].parent) chain.push_back(nodes[id].last);
  std::reverse(chain.begin(), chain.end());
  return chain;
}

}  // namespace arcpress::fit_detail
