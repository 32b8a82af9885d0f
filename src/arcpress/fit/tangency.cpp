// SPDX-License-Identifier: GPL-3.0-or-later
// Tangency repair: seed 000's G1 adjustment of a chain fitted without regard to its joints,
// local merging of neighbouring primitives (tighten()), and breaking the tangent where a
// chain can only follow the path in S-bends (untangle()).
#include <algorithm>

#include "arcpress/fit/run_fitter.hpp"

namespace arcpress::fit_detail {

/// A chain that still wiggles may be paying with S-bends, all the way along, for one joint
/// the path cannot pass tangentially: a hook, where the input turns at a vertex by more
/// than a primitive ending there can follow within the band (a pass clipped to the floor it
/// meets), so every chain that keeps the tangent leaves that vertex heading off the path.
/// The tangent breaks instead at the joint where the first wiggle starts, or at the one
/// before or after it, when that at least halves the primitives after the joint and saves
/// kKinkWorth of them for each kink it adds; the break is a forced kink. The chain after
/// the break may meet such a joint again further on (the next of plum's inner tips), so
/// it is mended the same way, up to kUntangleDepth joints deep, before it is weighed:
/// mended only at its first wiggle, a greedy chain over plum crept through the rest in
/// S-bends (sampled with 6 000 points and turned by 0.7 rad, at 0.005 mm: 667 blocks; 59
/// now, with two kinks).
void RunFitter::untangle(uint32_t a, uint32_t limit, std::vector<Chosen>& chain, size_t& forced, bool search) const {
  std::vector<Restart> restarts;
  untangle_at(a, limit, chain, forced, search, 0, restarts);
}

void RunFitter::untangle_at(uint32_t a, uint32_t limit, std::vector<Chosen>& chain, size_t& forced, bool search,
                            int depth,
                            std::vector<Restart>& restarts) const {
  const size_t first = wiggle_start(chain);
  std::vector<Chosen> best;
  size_t best_forced = forced;
  // Each forced kink counts as kKinkWorth primitives.
  size_t best_cost = chain.size() + kKinkWorth * forced;
  for (size_t k = std::max<size_t>(first, 2) - 1; k <= first + 1 && k < chain.size(); ++k) {
    const uint32_t v = chain[k - 1].prim.end_vertex;  // the joint at the start of primitive k
    if (chain[k].kinked || hard_[v]) continue;
    auto known = std::find_if(restarts.begin(), restarts.end(), [&](const Restart& r) { return r.v == v; });
    if (known == restarts.end()) {
      Restart r{v, {}, 0};
      GreedyWalk greedy(*this, v, limit);
      greedy.tangent.reset();
      if (!search) {
        greedy.finish();
        r.chain = std::move(greedy.chain);
        r.forced = greedy.kinks();
      } else {
        r.chain = beam_stretch(v, limit, greedy, r.forced);
      }
      restarts.push_back(std::move(r));
      known = restarts.end() - 1;
    }
    std::vector<Chosen> rest = known->chain;
    size_t rest_forced = known->forced;
    if (rest.empty()) continue;
    if (depth < kUntangleDepth && wiggles(rest)) untangle_at(v, limit, rest, rest_forced, search, depth + 1, restarts);
    const size_t after = chain.size() - k;
    // (Where the chain after the joint has as many kinks as the restart brings, no kink is
    // added: fewer primitives are enough.)
    const size_t kinks_after = size_t(std::count_if(chain.begin() + static_cast<long>(k), chain.end(),
                                                    [](const Chosen& c) { return c.kinked; }));
    const bool adds_kink = 1 + rest_forced > kinks_after;
    if (adds_kink && (2 * rest.size() > after || rest.size() + kKinkWorth > after)) continue;
    rest.front().kinked = true;
    std::vector<Chosen> made(chain.begin(), chain.begin() + static_cast<long>(k));
    made.insert(made.end(), rest.begin(), rest.end());
    if (o_.merge && search) tighten_between_kinks(a, made);
    size_t made_forced = 0;
    for (const Chosen& c : made) made_forced += c.kinked;
    if (made.size() + kKinkWorth * made_forced < best_cost) {
      best_cost = made.size() + kKinkWorth * made_forced;
      best.swap(made);
      best_forced = made_forced;
    }
  }
  if (best.empty()) return;
  chain.swap(best);
  forced = best_forced;
}

/// The index of the first primitive of the first wiggle in `chain` (see wiggles()), or
/// its size when none.
size_t RunFitter::wiggle_start(const std::vector<Chosen>& chain) const {
  int run = 0;
  for (size_t i = 1; i < chain.size(); ++i) {
    const Primitive &p = chain[i].prim, &before = chain[i - 1].prim;
    const bool back = p.kind == Primitive::Kind::Arc && before.kind == Primitive::Kind::Arc && p.ccw != before.ccw;
    run = back ? run + 1 : 0;
    if (run >= kWiggleArcs) return i - static_cast<size_t>(run);
  }
  return chain.size();
}

/// Marks as kinked the joints of `chain` (the whole fit) that are corners only because a
/// spike next to them was skipped, where the tangent breaks there: the verifier, which
/// skips no spikes, judges them as smooth joints.
void RunFitter::report_spike_corners(std::vector<Chosen>& chain) const {
  if (plain_hard_.empty()) return;
  for (size_t i = 1; i < chain.size(); ++i) {
    const uint32_t before = i > 1 ? chain[i - 2].prim.end_vertex : 0, from = chain[i - 1].prim.end_vertex;
    if (!hard_[from] || plain_hard_[from] || chain[i].kinked || !made_joint(from, fixed_[before].fixed)) continue;
    const std::optional<Vec2> dir =
        fixed_[from].fixed ? fixed_[from].start : std::optional<Vec2>(start_tangent(chain[i], from));
    if (dir && !joint_cone_.holds(chain[i - 1].end_tangent, *dir)) chain[i].kinked = true;
  }
}

/// Seed 000's G1 adjustment of a chain from `a` fitted without regard to its joints, joint
/// by joint from the start. Where the tangent breaks at a smooth joint, the primitive after
/// it is replaced, where the band allows, by the one through the same end vertex that
/// leaves along the tangent arriving there, turned within kTurnShare of the G1 angle to
/// meet the primitive after it (the seed moves the arc's centre so that the tangents
/// agree); failing that, the two primitives on either side are split again at another
/// vertex, joined tangentially, leaving the joint before them as the first did and
/// meeting the one after them (the joint moves, which fixes arcs that overshot it).
/// Joints that stay broken are marked kinked and counted in `forced`.
void RunFitter::make_tangent(uint32_t a, std::vector<Chosen>& chain, size_t& forced) const {
  auto from_of = [&](size_t i) { return i == 0 ? a : chain[i - 1].prim.end_vertex; };
  // The tangent arriving at the start of primitive i, where that joint is smooth and unbroken.
  auto arriving = [&](size_t i) -> std::optional<Vec2> {
    if (hard_[from_of(i)] || chain[i].kinked) return std::nullopt;
    return i == 0 ? in_tangent_ : std::optional<Vec2>(chain[i - 1].end_tangent);
  };
  // The tangent primitive i must meet at its end, if any.
  auto leaving = [&](size_t i) -> std::optional<Vec2> {
    const uint32_t to = chain[i].prim.end_vertex;
    if (i + 1 < chain.size()) return start_tangent(chain[i + 1], to);
    return to == stretch_end_ ? out_tangent_ : std::nullopt;
  };
  std::vector<Vec2> starts;
  for (size_t i = 0; i < chain.size(); ++i) {
    const uint32_t from = from_of(i), to = chain[i].prim.end_vertex;
    const std::optional<Vec2> in = arriving(i);
    if (!in || joint_cone_.holds(*in, start_tangent(chain[i], from))) continue;
    const std::optional<Vec2> out = leaving(i);
    std::optional<Chosen> one;
    for (const std::optional<Vec2>& T : {aimed(from, *in, to, out), in})
      if (!one && T && (one = through(from, *T, to)) && !joint_cone_.holds(*in, start_tangent(*one, from))) one.reset();
    if (one) {
      chain[i] = *one;
      continue;
    }
    std::optional<std::pair<Chosen, Chosen>> two;
    if (i > 0) {
      const uint32_t before = from_of(i - 1);
      starts.clear();
      if (auto arrive = arriving(i - 1)) {
        starts = {*arrive, half_left_(*arrive), half_right_(*arrive)};
      } else {
        start_tangents(before, to, starts);
      }
      for (const Vec2& T : starts)
        if ((two = split_through(before, T, to, out, SIZE_MAX))) break;
    }
    if (two) {
      two->first.kinked = chain[i - 1].kinked;
      chain[i - 1] = two->first;
      chain[i] = two->second;
    } else {
      chain[i].kinked = true;
      ++forced;
    }
  }
}

/// Two primitives from `from` to `to`, the first leaving along T, joined tangentially, the
/// second turned within kTurnShare of the G1 angle to meet `out` (where given) within it.
/// Splits whose second primitive can meet `out` are tried longest first; at most `tries`
/// of them, spread evenly, are checked exactly. (Inlined: tighten() calls it in its
/// innermost loop, where a call costs 0.3 % of all instructions on the corpus.)
[[gnu::always_inline]] inline std::optional<std::pair<Chosen, Chosen>> RunFitter::split_through(
    uint32_t from, const Vec2& T, uint32_t to, const std::optional<Vec2>& out, size_t tries) const {
  std::vector<Candidate>& cand = s_.tighten_cand;
  std::vector<size_t>& split = s_.split;
  scan(from, T, to - 1, cand);
  split.clear();
  for (size_t k = cand.size(); k-- > 0;)
    if (aimed(cand[k].e, reflected_end(from, T, cand[k].e), to, out)) split.push_back(k);
  const double stride = std::max(1.0, double(split.size()) / double(tries));
  for (double x = 0; x < double(split.size()); x += stride) {
    const Candidate& c = cand[split[size_t(x)]];
    // The second primitive's own cheap test first: it fails far more often.
    auto T2_lite = aimed(c.e, unchecked(from, T, c).end_tangent, to, out);
    if (!T2_lite || (out && !near_turn_cone_.holds(end_along(c.e, *T2_lite, to), *out))) continue;
    const auto lite = through_candidate(c.e, *T2_lite, to);
    // (The second checked exactly along it before the first: where the split fails, that is
    // nearly always where, on a helix over a whole turn in the plane, say.)
    if (!lite) continue;
    std::optional<Chosen> second = make(c.e, *T2_lite, *lite);
    if (!second) continue;
    auto first = make(from, T, c);
    if (!first) continue;
    auto T2 = aimed(c.e, first->end_tangent, to, out);
    if (!T2) continue;
    // Along the first's own end tangent; where that is the estimate's (a line's chord), the
    // second is the one just checked.
    if (*T2 != *T2_lite) {
      const auto cand2 = through_candidate(c.e, *T2, to);
      if (!cand2 || (out && !near_turn_cone_.holds(unchecked(c.e, *T2, *cand2).end_tangent, *out))) continue;
      second = make(c.e, *T2, *cand2);
    }
    if (second && (!out || turn_cone_.holds(second->end_tangent, *out))) return std::pair(*first, *second);
  }
  return std::nullopt;
}

/// tighten() on each tangent-continuous part of a chain that starts at `a`: a forced kink
/// frees the tangent on both sides of it, as a corner does.
void RunFitter::tighten_between_kinks(uint32_t a, std::vector<Chosen>& chain) const {
  std::vector<Chosen> out, part;
  for (size_t i = 0; i < chain.size(); ++i) {
    part.push_back(chain[i]);
    if (i + 1 < chain.size() && !chain[i + 1].kinked) continue;
    const bool kinked = part.front().kinked;
    tighten(a, part, out.empty() && !kinked ? in_tangent_ : std::nullopt);
    part.front().kinked = kinked;
    a = part.back().prim.end_vertex;
    out.insert(out.end(), part.begin(), part.end());
    part.clear();
  }
  chain.swap(out);
}

/// Local merging after the search: wherever two consecutive primitives can become one, or
/// three can become two, that leave the joint before them and meet the joint after them
/// within the turn allowed at a joint, they are replaced, and the joint before is tried again.
/// The tangent at the start is `incoming` (free when none) and at the end free, or a fixed
/// move's direction where the chain ends at one. Turning an arc's
/// start tangent by φ turns its end tangent by -φ (the end tangent is the start tangent
/// reflected about the chord), so the turn that meets the next joint is solved for, and
/// only primitives that can meet it are checked exactly. Where they end in an arc and a
/// line follows, they are also tried ending up to kLineShiftMoves earlier or later, the
/// line starting there instead. The start of a single primitive is also taken from the
/// range of those that reach its end (starts_within()), within the joint's turn.
void RunFitter::tighten(uint32_t a, std::vector<Chosen>& chain, const std::optional<Vec2>& incoming) const {
  std::vector<Vec2>& starts = s_.starts;
  std::vector<Vec2>& firsts = s_.firsts;
  std::vector<Chosen> repl;
  // w primitives as w - 1 from vertex `from`, arriving there along `in` (free when none), to
  // vertex `to`, there meeting `out` (free when none), into `repl`: whether they were found.
  auto merged_from = [&](uint32_t from, const std::optional<Vec2>& in, size_t w, uint32_t to,
                         const std::optional<Vec2>& out) {
    auto meets = [&](const Chosen& c) { return !out || turn_cone_.holds(c.end_tangent, *out); };
    // Start tangents: the incoming one (turned below), or at the stretch's start the
    // input's own directions; with a fixed next joint, the one ending exactly on it.
    starts.clear();
    size_t aimed_starts = SIZE_MAX;  // starts from here on are taken as they are
    if (in) {
      starts.push_back(*in);
      // A line leaves along its chord, which may turn from the arriving tangent by a
      // joint's turn (two lines along a straight side, after an arc that ran on past its
      // fillet with the first of them turned back towards the side).
      const Vec2 chord = q(to) - q(from);
      aimed_starts = starts.size();
      if (w == 2 && chord.squaredNorm() > kLengthEpsMm * kLengthEpsMm && joint_cone_.holds(*in, chord.normalized()))
        starts.push_back(chord.normalized());
    } else if (w == 2) {
      // One primitive from `from` to `to`: its start lies in the range that reaches `to`
      // (the chord first where the line does).
      if (out) starts.push_back(reflected_end(from, *out, to));
      if (const auto [lo, hi] = start_range(from, to); lo <= hi) {
        if (lo <= 0 && 0 <= hi) starts.push_back((q(to) - q(from)).normalized());
        for (double share : {0.5, kStartRangeInset, 1 - kStartRangeInset})
          starts.push_back(range_start(from, {to, lo, hi}, share));
      }
    } else {
      start_tangents(from, to, starts);
    }
    repl.clear();
    // One primitive from `from` along T to `to`, into `repl` where it meets the joint after.
    auto one = [&](const Vec2& T) {
      // (Where it would end heading first: most merges fail to meet the joint after.)
      if (out && !near_turn_cone_.holds(end_along(from, T, to), *out)) return false;
      const auto cand = through_candidate(from, T, to);
      if (!cand) return false;
      auto c = make(from, T, *cand);
      // (A line leaves along its chord, which may lie off T by a line's allowance: it must
      // still leave within the joint's turn of the arriving tangent.)
      if (c && meets(*c) && (!in || joint_cone_.holds(*in, start_tangent(*c, from)))) repl = {*c};
      return !repl.empty();
    };
    for (size_t k = 0; k < starts.size(); ++k) {
      const Vec2 T0 = starts[k];
      if (w == 2) {
        std::optional<Vec2> T = in && k < aimed_starts ? aimed(from, T0, to, out) : std::optional<Vec2>(T0);
        if (!T || (!in && out && !turn_line_cone_.holds(reflected_end(from, T0, to), *out))) continue;
        one(*T);
      } else {
        firsts.clear();
        if (in) {
          firsts.push_back(T0);
          firsts.push_back(half_left_(T0));
          firsts.push_back(half_right_(T0));
        } else {
          firsts.push_back(T0);
        }
        for (const Vec2& T : firsts)
          if (auto two = split_through(from, T, to, out, kSplitsTried)) {
            repl = {two->first, two->second};
            break;
          }
      }
      if (!repl.empty()) return true;
    }
    // A long arc reaches `to` only from a narrow range of starts, which the arriving tangent,
    // and the turn aimed at the joint after, may both miss by less than a joint may turn (a 2
    // mm arc, then one of 40 mm over 90° in 0.05 mm moves printed to 3 decimals: its starts
    // lie within 0.04° of the circle's tangent, and the 2 mm arc ends 0.05° off it). Last,
    // the start in that range nearest its middle that the joint before allows (kTurnShare of
    // the G1 angle where the joint after is to be met too, else kJointShare).
    if (w == 2 && in) {
      const double turn = deg_to_rad(o_.g1_angle_deg) * (out ? kTurnShare : kJointShare);
      const double at = std::atan2(in->y(), in->x());
      if (const auto r = starts_within(from, to, at - turn, at + turn)) {
        const double t = 0.5 * (r->first + r->second);
        if (one(Vec2(std::cos(t), std::sin(t)))) return true;
      }
    }
    return false;
  };
  // The tangent the chain leaves vertex `v` along with chain[k]: its start, or past the
  // chain's end a fixed move's direction where the stretch ends there (free when none).
  auto leaving = [&](size_t k, uint32_t v) -> std::optional<Vec2> {
    if (k < chain.size()) return start_tangent(chain[k], v);
    return v == stretch_end_ ? out_tangent_ : std::nullopt;
  };
  // The primitives from chain[i] on merged into `repl`: how many of them it replaces (0: none
  // merge). They start where chain[i] starts, along the tangent arriving there (the previous
  // primitive's, or at the start `incoming`).
  auto merge_at = [&](size_t i) -> size_t {
    const uint32_t from = i == 0 ? a : chain[i - 1].prim.end_vertex;
    const std::optional<Vec2> in = i > 0 ? std::optional<Vec2>(chain[i - 1].end_tangent) : incoming;
    for (size_t w : {size_t(2), size_t(3)}) {
      if (i + w > chain.size()) break;
      const uint32_t to = chain[i + w - 1].prim.end_vertex;
      if (merged_from(from, in, w, to, leaving(i + w, to))) return w;
    }
    // Where the window ends in an arc and a line follows, the arc may have run on past the
    // end of its fillet along the straight side (the band lets it, for sqrt(2·R·band)), and
    // no merge reaches back to the fillet while the window's far end stays there (a line, a
    // fillet and a line in moves of 0.05 mm printed to 3 decimals, R = 20 mm at 0.025 mm: 4
    // blocks, the second arc 4 moves past the fillet's end): the window is tried ending
    // earlier, the line starting there instead, for as far back as the line keeps the band.
    // Then later, the line starting later: the arc may as well have stopped short of the
    // fillet's end (R = 10 mm at 0.0095 mm: the line one move into the fillet, an arc from
    // there that cannot follow it to its end, and a second arc two moves short of it).
    for (size_t w : {size_t(2), size_t(3)}) {
      if (i + w >= chain.size()) break;
      const Chosen& line = chain[i + w];
      if (line.prim.kind != Primitive::Kind::Line || chain[i + w - 1].prim.kind != Primitive::Kind::Arc) continue;
      const uint32_t to = chain[i + w - 1].prim.end_vertex, end = line.prim.end_vertex;
      const uint32_t last_start = chain[i + w - 2].prim.end_vertex;
      // The joint after the line, which a line turned by starting elsewhere must still meet.
      const std::optional<Vec2> after = leaving(i + w + 1, end);
      for (const bool earlier : {true, false})
        for (uint32_t k = 1; k <= kLineShiftMoves; ++k) {
          const uint32_t t = earlier ? to - k : to + k;
          if (earlier ? t <= last_start + 1 : t + 1 >= end) break;
          const Vec2 chord = q(end) - q(t);
          if (chord.squaredNorm() <= kLengthEpsMm * kLengthEpsMm) break;
          const std::optional<Chosen> line_on = through(t, chord.normalized(), end);
          if (!line_on || line_on->prim.kind != Primitive::Kind::Line) break;  // past the straight side
          if (after && !joint_cone_.holds(line_on->end_tangent, *after)) continue;
          if (!merged_from(from, in, w, t, start_tangent(*line_on, t))) continue;
          repl.push_back(*line_on);
          return w + 1;
        }
    }
    return 0;
  };
  // After a merge at i, the joint before it may merge too: step back one.
  for (size_t i = 0; i + 1 < chain.size();) {
    const size_t replaced = merge_at(i);
    if (replaced) {
      chain.erase(chain.begin() + i, chain.begin() + i + replaced);
      chain.insert(chain.begin() + i, repl.begin(), repl.end());
      i = i > 0 ? i - 1 : 0;
    } else {
      ++i;
    }
  }
}

}  // namespace arcpress::fit_detail
