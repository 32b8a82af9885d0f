// SPDX-License-Identifier: GPL-3.0-or-later
// The greedy method (--method greedy), and the guide of the searches: one primitive at a
// time, the best-scoring of a few checked candidates, with a two-step look-ahead.
#include "arcpress/fit/run_fitter.hpp"

namespace arcpress::fit_detail {

RunFitter::Score RunFitter::score(const Chosen& c, uint32_t limit) const {
  return scored(c, reach_after(c.prim.end_vertex, c.end_tangent, limit));
}

/// The score of `c`, after which the chain reaches `reach`.
RunFitter::Score RunFitter::scored(const Chosen& c, uint32_t reach) const {
  Score sc;
  sc.end = c.prim.end_vertex;
  sc.reach = reach;
  if (const auto& t = heading_[sc.end]) sc.on_course = on_course_cone_.holds(*t, c.end_tangent);
  return sc;
}

/// score() of `c`, a candidate of scan `g`, with the reach the greedy step found when it
/// scored it too.
RunFitter::Score RunFitter::guide_score(const GuideScan& g, const Chosen& c, uint32_t limit) const {
  for (const auto& [e, reach] : g.reach)
    if (e == c.prim.end_vertex) return scored(c, reach);
  return score(c, limit);
}

/// Among the checked primitives from `a` along `T`, the one after which the chain reaches
/// furthest in the next step (two-step look-ahead over a few long candidates); ties go
/// to the longer primitive. A primitive after which the chain cannot go on tangentially
/// is taken only when there is no other. `scored`, where given, receives its score.
std::optional<Chosen> RunFitter::best_from(uint32_t a, const Vec2& T, uint32_t limit, Score* scored) const {
  // Scored first, checked exactly in the order of their scores: the first that passes
  // wins, so most steps check one primitive. (A candidate's end tangent is T reflected
  // about its chord, a line's the chord.)
  std::vector<Candidate>& cand = s_.best_cand;
  GuideScan* kept = pick(a, T, limit, kLookahead, cand);
  std::vector<Ranked>& ranked = s_.ranked;
  ranked.clear();
  for (size_t i = 0; i < cand.size(); ++i) ranked.push_back({i, score(unchecked(a, T, cand[i]), limit)});
  if (kept)
    for (const Ranked& r : ranked) kept->reach.emplace_back(cand[r.i].e, r.sc.reach);
  std::stable_sort(ranked.begin(), ranked.end(), [](const Ranked& x, const Ranked& y) { return x.sc > y.sc; });
  for (const Ranked& r : ranked)
    if (auto c = make(a, T, cand[r.i])) {
      if (scored) *scored = r.sc;
      return c;
    }
  // None of those passes the exact check: the walk that steps back over the rest.
  std::vector<Chosen>& made = s_.best_made;
  made.clear();
  checked_from(a, T, limit, kLookahead, made);
  std::optional<Chosen> best;
  Score best_score;
  for (const Chosen& c : made) {
    Score sc = score(c, limit);
    if (!best || sc > best_score) {
      best = c;
      best_score = sc;
    }
  }
  if (scored) *scored = best_score;
  return best;
}

/// The chain may turn by less than the G1 angle at a joint. When the exact tangent only
/// allows a short primitive (the incoming tangent is slightly off the input's), tangents
/// turned by up to 0.9 of that angle (near_turns_) are tried too, and the one reaching
/// furthest wins.
std::optional<Chosen> RunFitter::best_near(uint32_t a, const Vec2& T, uint32_t limit) const {
  // In the searches, this is the greedy chain's step, whose scans the beam takes again.
  struct Recording {
    bool& on;
    ~Recording() { on = false; }
  } recording{s_.guide_record = o_.method == FitOptions::Method::Arcs || o_.method == FitOptions::Method::Global};
  Score best_score;
  auto best = best_from(a, T, limit, &best_score);
  if (best) {
    if (best_score.on_course && (best->prim.end_vertex - a >= 4 || best->prim.end_vertex == limit)) return best;
  }
  for (size_t i = 0; i < near_turn_count_; ++i) consider(a, near_turns_[i](T), limit, best, best_score, &T);
  return best;
}

/// Keeps in `best` whichever of it and the best primitive along `T` scores higher. With
/// `incoming` (the tangent the chain arrives with, T being turned from it), a primitive
/// that leaves by more than kJointShare of the G1 angle from it is not taken: a line's chord
/// may lie off T by the line allowance, on top of the turn.
void RunFitter::consider(uint32_t a, const Vec2& T, uint32_t limit, std::optional<Chosen>& best, Score& best_score,
                         const Vec2* incoming) const {
  Score sc;
  auto c = best_from(a, T, limit, &sc);
  if (!c) return;
  // (An arc leaves along T itself.)
  if (incoming && !joint_cone_.holds(*incoming, start_tangent(*c, a))) return;
  if (!best || sc > best_score) {
    best = c;
    best_score = sc;
  }
}

/// Start of a smooth stretch (or after a forced kink): try a few start tangents read off
/// the input, and the one into the second move, and keep the one whose primitive reaches
/// furthest. (One that reaches `limit` on course scores what no later one can beat.)
Chosen RunFitter::best_free(uint32_t a, uint32_t limit) const {
  std::optional<Chosen> best;
  Score best_score;
  input_tangents(a, limit, s_.free_starts);
  if (auto T = into_next(a, limit)) s_.free_starts.push_back(*T);
  for (const Vec2& T : s_.free_starts) {
    consider(a, T, limit, best, best_score);
    if (best && best_score.on_course && best_score.reach >= limit && best_score.end >= limit) break;
  }
  if (best) return *best;
  return input_move(a);
}

}  // namespace arcpress::fit_detail
