// SPDX-License-Identifier: GPL-3.0-or-later
// The range search (--method global): breadth first over (vertex, range of start tangents),
// for the fewest primitives; the chain read back from the end.
#include <climits>
#include <cmath>
#include <functional>

#include "arcpress/fit/angle_ranges.hpp"
#include "arcpress/fit/scan_ends.hpp"

namespace arcpress::fit_detail {

namespace {

double angle_of(const Vec2& d) { return std::atan2(d.y(), d.x()); }

Vec2 direction_at(double angle) { return Vec2(std::cos(angle), std::sin(angle)); }

}  // namespace

std::vector<Chosen> RunFitter::range_chain(uint32_t a, uint32_t limit, size_t max_primitives, double front_share) const {
  // The turn carried from one primitive's end tangents to the next one's starts (rad).
  const double joint = kJointShare * deg_to_rad(o_.g1_angle_deg);
  const double carried = kRangeJointShare * joint;
  struct State {
    uint32_t v;
    double lo, hi;       // the start tangents' angles (rad) it may leave with
    uint32_t reach = 0;  // the furthest end its scans reached (v if none it looked at), once expanded
  };
  std::vector<State> states;
  // Per vertex from `a`: the start angles the layers so far reached it with (merged).
  std::vector<std::vector<AngleRange>> taken(limit - a + 1);
  // The input's direction at v: angles at a vertex are kept within half a turn of it.
  auto reference = [&](uint32_t v) { return angle_of(q(std::min(v + 1, limit)) - q(v > a ? v - 1 : a)); };
  if (arrives_along(a)) {
    const double t = angle_of(*in_tangent_);
    states.push_back({a, t - carried, t + carried});
  } else {  // (a primitive turns by at most a quarter turn off its chord before it)
    const double r = reference(a);
    states.push_back({a, r - kPi / 2, r + kPi / 2});
  }
  auto samples = [](const State& s) {
    return std::clamp(int(std::ceil(rad_to_deg(s.hi - s.lo) * kRangeSamplesPerDeg)) + 1, 2, 1000);
  };
  auto sample = [](const State& s, int j, int count) { return s.lo + (s.hi - s.lo) * j / (count - 1); };
  const size_t max_states = kMaxStatesPerVertex * size_t(limit - a) + 16;
  std::vector<std::vector<int>> layers{{0}};
  // Per vertex from `a`, the end tangents (rad, as reached) the layer's primitives arrive
  // with, widened by the joint's turn; and the vertices with any, in the order reached.
  std::vector<std::vector<AngleRange>> arriving(limit - a + 1);
  std::vector<uint32_t> arrived;
  // Per end: the lowest and highest start angle (rad) that reaches it.
  constexpr std::pair<double, double> kNone{kInf, -kInf};
  std::vector<std::pair<double, double>> reached(limit - a + 1, kNone);
  std::vector<uint32_t> ends;
  std::vector<AngleRange> here;
  int found = -1;  // the state of the last layer whose primitive reaches `limit`
  double found_lo = 0, found_hi = 0;
  uint32_t front = a;  // the furthest vertex the layers so far reached
  while (found < 0 && !layers.back().empty() && layers.size() <= max_primitives) {
    uint32_t furthest = front;  // the furthest vertex the layer's primitives arrive at so far
    for (int id : layers.back()) {
      const State s = states[size_t(id)];
      // The ends short of the share of the layer's advance so far make no state (below):
      // they are not looked at.
      const uint32_t first_end = front + uint32_t(front_share * double(furthest - front));
      // The ends each sample of the range reaches; those a range of samples reaches.
      const int count = samples(s);
      ends.clear();
      uint32_t best_end = 0;  // the furthest any sample reaches
      // The samples in groups of at most kFanLanes, scanned together.
      const int groups = (count + kFanLanes - 1) / kFanLanes, per_group = (count + groups - 1) / groups;
      for (int j0 = 0; j0 < count; j0 += per_group) {
        const size_t sorted = ends.size();  // (each group reports its ends in order)
        const int lanes = std::min(per_group, count - j0);
        Vec2 T[kFanLanes];
        for (int l = 0; l < lanes; ++l) T[l] = direction_at(sample(s, j0 + l, count));
        fan_ends(s.v, T, lanes, limit, first_end, [&](int l, const Candidate& c) {
          auto& r = reached[c.e - a];
          if (r.second < r.first) ends.push_back(c.e);
          r.first = std::min(r.first, sample(s, j0 + l, count));
          r.second = std::max(r.second, sample(s, j0 + l, count));
          best_end = std::max(best_end, c.e);
        });
        std::inplace_merge(ends.begin(), ends.begin() + std::ptrdiff_t(sorted), ends.end());
      }
      // The furthest ends of long arcs are reached from ranges narrower than the samples'
      // spacing (plum at 0.005 mm: 44 blocks where the bound is 38, 39 with what follows).
      // Each end's starts in the band are known exactly (start_range()): the furthest end a
      // sample reached takes all those the state allows; past it, ends are tried by doubling
      // steps while some start the state allows reaches them, then by halving between the
      // last reached and the first not, and each one reached is taken. (They are kept only
      // where a scan along the middle of the furthest one's starts offers it: the scan holds
      // an end to every other limit, as the radius.)
      auto exact = [&](uint32_t e) { return starts_within(s.v, e, s.lo, s.hi); };
      if (best_end > 0) {
        if (const auto x = exact(best_end)) {
          auto& r = reached[best_end - a];
          r = {std::min(r.first, x->first), std::max(r.second, x->second)};
        }
        const size_t sampled = ends.size();
        auto take = [&](uint32_t e) {
          const auto x = exact(e);
          if (!x) return false;
          reached[e - a] = *x;
          ends.push_back(e);
          return true;
        };
        uint32_t good = best_end, step = 1;
        while (good + step <= limit && take(good + step)) good += step, step *= 2;
        uint32_t bad = std::min(good + step, limit + 1);
        while (bad - good > 1) {
          const uint32_t mid = good + (bad - good) / 2;
          (take(mid) ? good : bad) = mid;
        }
        std::sort(ends.begin() + std::ptrdiff_t(sampled), ends.end());
        if (ends.size() > sampled) {
          const uint32_t e = ends.back();
          bool offered = false;
          scan_ends(s.v, direction_at(0.5 * (reached[e - a].first + reached[e - a].second)), e,
                    [&](const Candidate& c) { offered = offered || c.e == e; });
          if (!offered) {
            for (size_t k = sampled; k < ends.size(); ++k) reached[ends[k] - a] = kNone;
            ends.resize(sampled);
          }
        }
      }
      states[size_t(id)].reach = ends.empty() ? s.v : ends.back();
      for (uint32_t e : ends) {
        auto& r = reached[e - a];
        double lo = r.first, hi = r.second;
        r = kNone;
        // An arc ends along its start tangent mirrored in the chord.
        const double chord = near_angle(angle_of(q(e) - q(s.v)), 0.5 * (lo + hi));
        const double end_lo = 2 * chord - hi, end_hi = 2 * chord - lo;
        if (e == limit) {
          if (out_tangent_) {  // the end tangent within the joint's turn of the move after
            const double o = near_angle(angle_of(*out_tangent_), 0.5 * (end_lo + end_hi));
            lo = std::max(lo, 2 * chord - o - carried);
            hi = std::min(hi, 2 * chord - o + carried);
            if (lo > hi) continue;
          }
          if (found < 0) {
            found = id;
            found_lo = lo;
            found_hi = hi;
          }
          continue;
        }
        if (arriving[e - a].empty()) arrived.push_back(e);
        furthest = std::max(furthest, e);
        arriving[e - a].push_back({end_lo - carried, end_hi + carried});
      }
      if (found >= 0) break;
    }
    if (found >= 0) break;
    // Per vertex, the union of the layer's arrivals less what earlier layers reached: each
    // piece left is a state of the next layer.
    std::sort(arrived.begin(), arrived.end());
    const uint32_t cut = front_share > 0 && !arrived.empty()
                             ? front + uint32_t(front_share * double(arrived.back() - front))
                             : front;
    std::vector<int> next;
    for (uint32_t e : arrived) {
      std::vector<AngleRange>& in = arriving[e - a];
      if (e >= cut) {
        const double ref = reference(e);
        here.clear();
        for (const AngleRange& r : in) {
          const double lo = near_angle(r.lo, ref);
          here.push_back({lo, lo + (r.hi - r.lo)});
        }
        for (const AngleRange& r : take_new(here, taken[e - a])) {
          states.push_back({e, r.lo, r.hi});
          next.push_back(int(states.size()) - 1);
        }
        front = std::max(front, e);
      }
      in.clear();
    }
    arrived.clear();
    if (states.size() > max_states) return {};
    layers.push_back(std::move(next));
  }
  if (found < 0) return {};
  // Read back from the end, depth first: for primitive i, a state of layer i that reached
  // the next joint, and a start in its range (nearest the middle of the starts whose end
  // meets the next primitive's start within the joint's turn first) whose primitive passes
  // the exact check and that joint.
  const size_t k = layers.size();
  std::vector<Chosen> chain(k);
  size_t checks = kRangeChecksPerPrimitive * k;
  std::function<bool(size_t, uint32_t, const std::optional<Vec2>&)> read_back = [&](size_t i, uint32_t to,
                                                                                    const std::optional<Vec2>& next) {
    const std::vector<int> last{found};
    for (int id : i + 1 == k ? last : layers[i]) {
      const State s = states[size_t(id)];
      if (s.v >= to || s.reach < to) continue;
      double lo = s.lo, hi = s.hi;
      if (i + 1 == k) {
        lo = found_lo;
        hi = found_hi;
      }
      if (next) {
        const double chord = near_angle(angle_of(q(to) - q(s.v)), 0.5 * (s.lo + s.hi));
        const double wanted = 2 * chord - near_angle(angle_of(*next), 2 * chord - 0.5 * (s.lo + s.hi));
        lo = std::max(lo, wanted - joint);
        hi = std::min(hi, wanted + joint);
        if (lo > hi) continue;
      }
      // The starts that reach `to` inside the band are known exactly (start_range()): their
      // middle first, where the state allows it, for the narrow ranges of long arcs.
      std::vector<double> starts;
      if (const auto r = starts_within(s.v, to, lo, hi)) starts.push_back(0.5 * (r->first + r->second));
      const size_t exact = starts.size();
      const int count = samples(s);
      const double mid = 0.5 * (lo + hi);
      starts.push_back(mid);
      for (int j = 0; j < count; ++j)
        if (const double t = sample(s, j, count); t >= lo && t <= hi) starts.push_back(t);
      std::sort(starts.begin() + std::ptrdiff_t(exact), starts.end(),
                [&](double x, double y) { return std::abs(x - mid) < std::abs(y - mid); });
      for (double t : starts) {
        if (checks == 0) return false;
        --checks;
        auto c = through(s.v, direction_at(t), to);
        if (!c || (next && !joint_cone_.holds(c->end_tangent, *next))) continue;
        if (i == 0) {
          if (in_tangent_ && !joint_cone_.holds(*in_tangent_, start_tangent(*c, a))) continue;
          chain[0] = *c;
          return true;
        }
        chain[i] = *c;
        if (read_back(i - 1, s.v, start_tangent(*c, s.v))) return true;
      }
    }
    return false;
  };
  if (!read_back(k - 1, limit, out_tangent_)) return {};
  return chain;
}

}  // namespace arcpress::fit_detail
