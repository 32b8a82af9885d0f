// SPDX-License-Identifier: GPL-3.0-or-later
// The default method's first search: depth first for a chain of as few primitives as a
// chain that may break its tangent at every joint needs (bound_start()), before the greedy
// walk and the beam.
#include "arcpress/fit/scan_ends.hpp"

namespace arcpress::fit_detail {

uint32_t RunFitter::bound_start(uint32_t a, uint32_t limit) const {
  // From the end back: the nearest vertex from which some circle reaches the end inside the
  // band (tangent free), then the nearest from which one reaches that vertex, and so on.
  // Where a circle that reaches a vertex also reaches every vertex between, a chain from
  // any vertex from the j-th of them up to the one before the (j-1)-th needs j primitives
  // or more. The vertices alone are held to the band, not the moves' middles: looser, so
  // still no more than a fit needs, and half the work.
  s_.bound_a = a;
  std::vector<uint32_t>& h = s_.bound_h;
  h.assign(limit - a + 1, 0);
  uint32_t count = 0;
  for (uint32_t e = limit; e > a; ++count) {
    if (count == kBoundMaxPrimitives) return count + 1;  // (not searched: see kBoundMaxPrimitives)
    auto reaches = [&](uint32_t back) {  // whether vertex e - back reaches e
      const uint32_t u = e - back;
      return !soft_between(u, e) && start_reaches(u, e, false);
    };
    // (A move on its own is always a primitive: the input's line.)
    const uint32_t from = e - furthest_reached(1, e - a, reaches);
    for (uint32_t v = from; v < e; ++v) h[v - a] = count + 1;
    e = from;
  }
  return count;
}

template <class Try>
bool RunFitter::any_joint_turn(uint32_t v, const Vec2& T, uint32_t limit, Try&& try_along) const {
  if (try_along(T)) return true;
  for (const Turn& turn : joint_turns_)
    if (try_along(turn(T))) return true;
  return straight_ahead(v, limit) && (try_along(half_left_(T)) || try_along(half_right_(T)));
}

bool RunFitter::finishes(uint32_t v, const Vec2& T, uint32_t limit) const {
  return any_joint_turn(v, T, limit, [&](const Vec2& Ti) { return finish_from(v, Ti, limit).has_value(); });
}

std::vector<Chosen> RunFitter::bound_chain(uint32_t a, uint32_t limit) const {
  std::vector<Chosen> chain;
  // Where a fixed move holds the direction at either end, or the stretch closes a loop, the
  // count says too little: it takes the ends' directions as free, and two primitives that
  // close a loop tangentially each turn half of it, joined exactly across the loop from its
  // start, where the input seldom has a vertex.
  if (in_tangent_ || out_tangent_ || (q(limit) - q(a)).squaredNorm() <= eps_ * eps_) return chain;
  // (Where one primitive may do, the greedy step finds it at no more cost, with the arc
  // through the input's own directions.)
  const size_t target = bound_start(a, limit);
  if (target < 2 || target > kBoundMaxPrimitives) return chain;
  std::unordered_map<uint64_t, uint32_t>& failed = s_.bound_failed;  // state -> shallowest depth it failed at
  failed.clear();
  std::vector<std::vector<BoundTry>>& tries = s_.bound_tries;
  if (tries.size() < target + 1) tries.resize(target + 1);
  size_t budget = kBoundChecksPerPrimitive * target;
  size_t deepest = 0;
  // Depth first: `chain` holds `depth` primitives ending at v, leaving along T. A chain that
  // fails two primitives short of the deepest one tried is not tried further: where no
  // chain of the count passes, it fails at a narrow place deep along the stretch, and
  // trying every way there costs more than the beam after it.
  auto search = [&](auto& self, uint32_t v, const Vec2& T, size_t depth) -> bool {
    deepest = std::max(deepest, depth);
    std::vector<BoundTry>& here = tries[depth];
    here.clear();
    const size_t left = target - depth - 1;  // primitives the chain may have after the next
    // Only ends after which the count leaves room; for the last primitive, the end of the
    // stretch alone, which a scan that stops at the first vertex off its circle tests.
    const std::vector<uint32_t>& h = s_.bound_h;
    auto collect = [&](const Vec2& from_T, const Vec2& Ti) {
      if (left == 0) {
        if (auto c = finish_from(v, Ti, limit)) here.push_back({*c, Ti, from_T});
        return;
      }
      scan_ends(v, Ti, limit, [&](const Candidate& c) {
        if (h[c.e - a] <= left) here.push_back({c, Ti, from_T});
      });
    };
    if (depth == 0) {
      roots(a, limit, s_.bound_roots);
      for (const Vec2& R : s_.bound_roots) collect(R, R);
    } else {
      any_joint_turn(v, T, limit, [&](const Vec2& Ti) {
        collect(T, Ti);
        return false;
      });
    }
    // Furthest end first, of two to one end a line first (where the straight side is a line,
    // an arc of large radius over it would bend the joint after it), else in the order found.
    std::stable_sort(here.begin(), here.end(), [](const BoundTry& x, const BoundTry& y) {
      if (x.c.line != y.c.line) return x.c.line;
      return x.c.e > y.c.e;
    });
    for (size_t i = 0; i < here.size(); ++i) {
      if (budget == 0) return false;
      const BoundTry t = here[i];
      // Before the one primitive left, an end from which none finishes along the tangent it
      // would leave with, turned at the joint or not, is not checked.
      if (left == 1 && !finishes(t.c.e, unchecked(v, t.T, t.c).end_tangent, limit)) continue;
      --budget;
      auto c = made_from(Node{{}, -1, v, t.from}, t.T, t.c);
      if (!c) continue;
      if (t.c.e >= limit) {
        chain.push_back(*c);
        return true;
      }
      // A state (end, tangent bin) that failed as deep or deeper is not tried again.
      const long bin = tangent_bin(c->end_tangent, kEndBinShare);
      const uint64_t key = uint64_t(t.c.e) << 32 | uint32_t(bin);
      if (auto it = failed.find(key); it != failed.end() && it->second <= depth + 1) continue;
      chain.push_back(*c);
      if (self(self, t.c.e, c->end_tangent, depth + 1)) return true;
      chain.pop_back();
      if (budget == 0 || depth + 1 < deepest) return false;
      auto [it, added] = failed.try_emplace(key, uint32_t(depth + 1));
      if (!added) it->second = std::min<uint32_t>(it->second, uint32_t(depth + 1));
    }
    return false;
  };
  if (!search(search, a, Vec2(1, 0), 0)) chain.clear();  // (the roots' tangents are free)
  return chain;
}

}  // namespace arcpress::fit_detail
