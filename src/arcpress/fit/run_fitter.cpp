// SPDX-License-Identifier: GPL-3.0-or-later
// RunFitter's run: its vertices (past moves that go nowhere), the corner rule and the
// vertices where a primitive must end, the stretches between corners, and the method each
// stretch is fitted with (fit_kept()).
#include "arcpress/fit/run_fitter.hpp"

namespace arcpress::fit_detail {

/// `run` spans the moves to fit; `fixed` (per move, empty: none) says which stay as they
/// are, and `pinned` (per vertex, empty: none) where a primitive must end (where one run
/// meets the next or a fixed move), the tangent going on there.
RunFitter::RunFitter(const Interpretation& in, const Run& run, const FitOptions& o, const std::vector<FixedMove>& fixed,
                     std::vector<uint8_t> pinned)
    : FitAngles(FitAngles::of(o)), o_(o) {
  vertices_kept(in, run, fixed, pinned, at_);
  n_ = uint32_t(at_.size() - 1);
  if (!pinned.empty())
    for (uint32_t v = 0; v <= n_; ++v) pinned[v] = pinned[at_[v]];
  fixed_.clear();
  for (uint32_t v = 0; v < n_; ++v) fixed_.push_back(fixed.empty() ? FixedMove{} : fixed[at_[v]]);
  auto vertex = [&](uint32_t v) -> const AxisValues& { return run.vertex(in, at_[v]); };
  auto ax = axes_of(run.plane);
  p_.resize(n_ + 1);
  q_.resize(n_ + 1);
  middle_.resize(n_);
  // (With the extra axes (A/B/C, U/V/W) that move in the run, bit by axis.)
  unsigned moving = 0;
  for (uint32_t v = 0; v <= n_; ++v) {
    const auto& a = vertex(v);
    p_[v] = Vec3(a[ax.first], a[ax.second], a[ax.normal]);
    q_[v] = Vec2(a[ax.first], a[ax.second]);
    if (v > 0) {
      const auto& before = vertex(v - 1);
      for (int x = kA; x < kE; ++x) moving |= unsigned(a[x] != before[x]) << x;
    }
  }
  for (uint32_t v = 0; v < n_; ++v) middle_[v] = 0.5 * (q_[v] + q_[v + 1]);
  // Level: no vertex lies above or below another by more than the scans' test of a climb.
  const auto [low, high] =
      std::minmax_element(p_.begin(), p_.end(), [](const Vec3& x, const Vec3& y) { return x.z() < y.z(); });
  level_ = high->z() - low->z() <= kLengthEpsMm;
  // The extra axes that move in the run, and their values at each vertex.
  for (int x = kA; x < kE; ++x)
    if (moving >> x & 1) extra_.push_back(x);
  extra_values_.clear();
  for (uint32_t v = 0; v <= n_ && !extra_.empty(); ++v)
    for (int x : extra_) extra_values_.push_back(vertex(v)[x]);
  arcs_ = o.arcs && (o.extra_axes || extra_.empty());
  eps_ = o.tolerance_mm * (1.0 - rounding_reserve_share(o));
  hard_.assign(n_ + 1, 0);
  heading_.assign(n_ + 1, std::nullopt);
  soft_.assign(n_ + 1, 0);
  auto corner = [&](uint32_t a, uint32_t b, uint32_t c) {
    return is_corner(p_[a], p_[b], p_[c], o.tolerance_mm, o.corner_angle_deg);
  };
  // Seed 004's spikes (option): a lone vertex where the path jags out and back, within half
  // the band of its neighbours' chord, with the path smooth once it is skipped. Noise, not
  // a corner; the fitted path still passes within the band of it.
  std::vector<uint8_t>& spike = b_.spike;
  spike.assign(n_ + 1, 0);
  for (uint32_t v = 2; o.spikes && v + 2 <= n_; ++v)
    spike[v] = !spike[v - 1] && corner(v - 1, v, v + 1) &&
               point_segment_distance(p_[v], p_[v - 1], p_[v + 1]) <= 0.5 * o.tolerance_mm &&
               !corner(v - 2, v - 1, v + 1) && !corner(v - 1, v + 1, v + 2);
  // Moves that go nowhere and stay (fixed ones, or those between two vertices that must
  // stay): the corner rule steps past them, as the verifier does.
  std::vector<uint8_t>& nowhere = b_.nowhere;
  nowhere.assign(n_, 0);
  for (uint32_t v = 0; v < n_; ++v)
    nowhere[v] = in.moves_going(run.first_move + at_[v], run.first_move + at_[v + 1]) == 0;
  // The same corner rule, with the same band, as the verifier uses to judge joints (with
  // spikes skipped when asked): first each vertex alone, then with its neighbours' corners.
  // A vertex's neighbours are the nearest vertices elsewhere, past spikes when skipped.
  auto corners = [&](const std::vector<uint8_t>& skipped, std::vector<uint8_t>& hard) {
    auto before = [&](uint32_t v, bool past_spikes) {
      uint32_t u = v - 1;
      while (u > 0 && (nowhere[u] || (past_spikes && skipped[u]))) --u;
      return u;
    };
    auto after = [&](uint32_t v, bool past_spikes) {
      uint32_t u = v + 1;
      while (u < n_ && (nowhere[u - 1] || (past_spikes && skipped[u]))) ++u;
      return u;
    };
    std::vector<uint8_t>& alone = b_.alone;
    alone.assign(n_ + 1, 0);
    hard.assign(n_ + 1, 0);
    for (uint32_t v = 1; v < n_; ++v) alone[v] = !skipped[v] && corner(before(v, true), v, after(v, true));
    for (uint32_t v = 1; v < n_; ++v) {
      const uint32_t b = before(v, true), a = after(v, true);
      hard[v] =
          alone[v] || (!skipped[v] && is_corner_beside_corner(b > 0 ? &p_[before(b, false)] : nullptr, p_[b], p_[v],
                                                              p_[a], a < n_ ? &p_[after(a, false)] : nullptr, alone[b],
                                                              alone[a], o.tolerance_mm));
    }
  };
  corners(spike, hard_);
  // The verifier knows no spikes: a joint it calls smooth that only skipping a spike made a
  // corner is reported where the tangent breaks there (see report_spike_corners()).
  plain_hard_.clear();
  if (std::find(spike.begin(), spike.end(), 1) != spike.end()) {
    b_.none.assign(n_ + 1, 0);
    corners(b_.none, plain_hard_);
  }
  for (uint32_t v = 1; v < n_; ++v) {
    double l1 = (p_[v] - p_[v - 1]).norm(), l2 = (p_[v + 1] - p_[v]).norm();
    // Extrusion and the extra axes per mm must stay (nearly) constant inside one primitive:
    // a primitive ends where one starts or stops moving or changes its rate.
    auto rate_changes = [&](int x) {
      double d1 = vertex(v)[x] - vertex(v - 1)[x];
      double d2 = vertex(v + 1)[x] - vertex(v)[x];
      double r1 = d1 / l1, r2 = d2 / l2;
      return (d1 == 0) != (d2 == 0) || std::abs(r1 - r2) > o.extrusion_variance * std::max(std::abs(r1), std::abs(r2));
    };
    if (rate_changes(kE)) soft_[v] = 1;
    for (int x : extra_)
      if (rate_changes(x)) soft_[v] = 1;
    if (!pinned.empty() && pinned[v]) soft_[v] = 1;
  }
  // E per mm of each move, where E moves in the run (the primitives' own rate is held to it).
  e_values_.clear();
  e_rate_.clear();
  bool e_moves = false;
  for (uint32_t v = 1; v <= n_ && !e_moves; ++v) e_moves = vertex(v)[kE] != vertex(v - 1)[kE];
  if (e_moves) {
    for (uint32_t v = 0; v <= n_; ++v) e_values_.push_back(vertex(v)[kE]);
    for (uint32_t v = 0; v < n_; ++v) {
      const double len = (p_[v + 1] - p_[v]).norm();
      e_rate_.push_back(len > kLengthEpsMm ? std::abs(e_values_[v + 1] - e_values_[v]) / len : 0.0);
    }
  }
  next_soft_.assign(n_ + 1, n_ + 1);
  for (uint32_t v = n_; v-- > 0;) next_soft_[v] = soft_[v + 1] ? v + 1 : next_soft_[v + 1];
}

/// The primitives over all moves (fixed moves as themselves), each marked `kinked` where
/// the tangent breaks at a smooth joint because the band allows nothing tangent there.
/// Their end vertices are the run's.
std::vector<Chosen> RunFitter::fit() {
  std::vector<Chosen> out = fit_kept();
  for (Chosen& c : out) c.prim.end_vertex = at_[c.prim.end_vertex];
  return out;
}

/// The run's vertices the fitter works on: all, less those that only repeat the one before
/// (after a move that goes nowhere: no direction, so no corner either), which the
/// primitive over their neighbours steps over. Where such a vertex must stay
/// (the run's end, a pinned vertex) the one it repeats goes instead, unless that must stay
/// too. (The keep method never gets here: fit_chain() keeps every move itself.)
void RunFitter::vertices_kept(const Interpretation& in, const Run& run, const std::vector<FixedMove>& fixed,
                              const std::vector<uint8_t>& pinned, std::vector<uint32_t>& at) {
  const uint32_t n = run.move_count;
  auto must_stay = [&](uint32_t v) { return v == 0 || v == n || (!pinned.empty() && pinned[v]); };
  at.assign(1, 0);
  for (uint32_t v = 1; v <= n; ++v) {
    const bool nowhere = (fixed.empty() || !fixed[v - 1].fixed) && in.goes_nowhere(run.first_move + v - 1);
    if (!nowhere)
      at.push_back(v);
    else if (must_stay(v) && !must_stay(at.back()))
      at.back() = v;
    else if (must_stay(v))
      at.push_back(v);
  }
}

std::vector<Chosen> RunFitter::fit_kept() {
  if (n_ < 2) return keep();
  std::vector<Chosen> out;
  out.reserve(n_);  // at most one primitive per move
  // Stretches run from corner to corner, or to a fixed move; the tangent is free at a
  // corner and follows the fixed move's direction where the path is smooth.
  bool after_fitted = false;  // the last primitive in `out` was fitted, not fixed
  for (uint32_t a = 0; a < n_;) {
    if (fixed_[a].fixed) {
      Chosen m = input_move(a);
      if (fixed_[a].end) m.end_tangent = *fixed_[a].end;
      const auto& dir = fixed_[a].start;
      m.kinked = made_joint(a, !after_fitted) && !hard_[a] && dir && !out.empty() &&
                 !joint_cone_.holds(out.back().end_tangent, *dir);
      out.push_back(m);
      after_fitted = false;
      ++a;
      continue;
    }
    uint32_t limit = a + 1;
    while (limit < n_ && !hard_[limit] && !fixed_[limit].fixed) ++limit;
    in_tangent_ = a > 0 && fixed_[a - 1].fixed && !hard_[a] ? fixed_[a - 1].end : std::nullopt;
    out_tangent_ = limit < n_ && fixed_[limit].fixed && !hard_[limit] ? fixed_[limit].start : std::nullopt;
    stretch_start_ = a;
    stretch_end_ = limit;
    lim_ = scan_limits();
    stretch_id_ = ++s_.stretches;
    after_fitted = true;
    if (limit == a + 1) {  // one move: its own answer, or the arc over it that meets a fixed move
      Chosen m = one_move(a);
      m.kinked = in_tangent_ && !g1_cone_.holds(*in_tangent_, start_tangent(m, a));
      out.push_back(m);
      a = limit;
      continue;
    }
    // The chain is searched with both ends held to the directions of the fixed moves around
    // the stretch. Where it kinks all the same, it is searched again with the end, the start,
    // and both free: a kink may then be taken there instead. Held, the last primitive could
    // only be a move left as it was (two moves between an arc and a move of another width: two
    // lines and three kinks, where one arc over both kinks twice); after a lone line, the
    // chain along it could only go on as the input's moves. The chain with fewer kinks, those
    // at its ends included, then fewer primitives, wins.
    // The input's directions inside the stretch, which the searches aim for, are the same
    // whichever end is held.
    const bool search = o_.method == FitOptions::Method::Arcs || o_.method == FitOptions::Method::Global;
    if (search || o_.method == FitOptions::Method::Greedy)
      for (uint32_t v = a + 1; v < limit; ++v)
        heading_[v] = search ? sided_tangent(v, a, limit) : input_tangent(v, a, limit);
    const std::optional<Vec2> before = in_tangent_, after = out_tangent_;
    struct Tried {
      std::vector<Chosen> chain;
      size_t kinks = 0;  // forced, those at the ends included
    };
    auto attempt = [&](bool free_start, bool free_end) {
      in_tangent_.reset();
      out_tangent_.reset();
      if (before && !free_start) in_tangent_ = *before;
      if (after && !free_end) out_tangent_ = *after;
      lim_ = scan_limits();
      stretch_id_ = ++s_.stretches;
      Tried t;
      t.chain = fit_stretch(a, limit, t.kinks);
      if (t.chain.empty()) return t;
      if (free_start && !joint_cone_.holds(*before, start_tangent(t.chain.front(), a))) {
        t.chain.front().kinked = true;
        ++t.kinks;
      }
      if (after && !joint_cone_.holds(t.chain.back().end_tangent, *after)) ++t.kinks;
      return t;
    };
    Tried best = attempt(false, false);
    auto weigh = [&](Tried t) {
      if (!t.chain.empty() && std::pair(t.kinks, t.chain.size()) < std::pair(best.kinks, best.chain.size())) best = std::move(t);
    };
    if (best.kinks > 0)
      for (const auto& [free_start, free_end] : {std::pair(false, true), std::pair(true, false), std::pair(true, true)})
        if ((!free_start || before) && (!free_end || after)) weigh(attempt(free_start, free_end));
    in_tangent_ = before;
    out_tangent_ = after;
    out.insert(out.end(), best.chain.begin(), best.chain.end());
    a = limit;
  }
  report_spike_corners(out);
  return out;
}

std::vector<Chosen> RunFitter::fit_stretch(uint32_t a, uint32_t limit, size_t& forced) {
  bool search = o_.method == FitOptions::Method::Arcs || o_.method == FitOptions::Method::Global;
  std::vector<Chosen> chain;
  bool bounded = false;
  if (o_.method == FitOptions::Method::Stream) {
    chain = stream_chain(a, limit, forced);
  } else if (o_.method == FitOptions::Method::Lowe) {
    chain = lowe_chain(a, limit, forced);
  } else if (search && o_.bound_search && !(chain = bound_chain(a, limit)).empty()) {
    // A chain of as few primitives as one that may break its tangent at every joint needs
    // (bound_chain()): no search after it finds fewer, and the greedy walk and the beam are
    // not needed.
    bounded = true;
    forced = 0;
  } else {
    // The greedy chain is the answer for stretches it covers in one or two primitives
    // joined tangentially; longer ones, and those it could only cover with a forced
    // kink, are searched again, and the chain with fewer kinks, then fewer primitives,
    // wins. The greedy chain is walked only as far as the search and that choice need.
    // The greedy method takes the greedy chain, but where it wiggles (see untangle()): its
    // look-ahead, a primitive deep, can lead it into a narrow place (plum's inner tips at
    // 0.01 mm with 1 % of the band kept back) that it leaves only by S-bends, or by a kink of
    // 36° once untangled. There the stretch is fitted as the default fits it, aiming for the
    // input's directions read from each side (sided_tangent()).
    GreedyWalk greedy(*this, a, limit);
    if (o_.method == FitOptions::Method::Greedy) {
      greedy.finish();
      search = wiggles(greedy.chain);
      if (search) {
        for (uint32_t v = a + 1; v < limit; ++v) heading_[v] = sided_tangent(v, a, limit);
        greedy.restart(a);
      }
    }
    const bool searched = search && o_.beam_width > 1 && (greedy.longer_than(2) || greedy.kinks() > 0);
    size_t beam_forced = 0;
    std::vector<Chosen> b;
    if (searched) b = beam_stretch(a, limit, greedy, beam_forced);
    // A beam chain of k primitives without kinks is taken over a greedy chain of k or more
    // (which the greedy walk, as far as it went, may already show without another step).
    const bool beam_shorter =
        searched && beam_forced == 0 && (b.size() <= greedy.at_least() || greedy.longer_than(b.size() - 1));
    if (!beam_shorter) greedy.finish();
    if (beam_shorter || (searched && std::pair(beam_forced, b.size()) < std::pair(greedy.kinks(), greedy.length()))) {
      chain.swap(b);
      forced = beam_forced;
    } else {
      chain = std::move(greedy.chain);
      forced = greedy.kinks();
    }
  }
  if (search && o_.merge) tighten_between_kinks(a, chain);
  // (The count holds where reaching further never costs, which the band does not quite
  // promise: after the chain at the count, the merges still save a block here and there,
  // ps233 at 0.005 mm: 23, but the searches below find none.)
  if (bounded) return chain;
  // Where the chain wiggles, and with the global method for every stretch the chain does
  // not cover with one primitive, every (vertex, tangent) state is searched layer by layer;
  // with the global method every (vertex, range of tangents) state too. A chain found is
  // kept when, merged too, it has fewer kinks, or as few and fewer primitives.
  auto consider = [&](std::vector<Chosen> g) {
    if (!g.empty() && o_.merge) tighten(a, g, in_tangent_);
    if (!g.empty() && std::pair(size_t(0), g.size()) < std::pair(forced, chain.size())) {
      chain.swap(g);
      forced = 0;
    }
  };
  const bool global = o_.method == FitOptions::Method::Global;
  // Where the beam's primitives are long, ranges of tangents are searched too, the far part
  // of each layer's advance (see kRangeMovesPerPrimitive); decided on the beam's chain, so
  // that the global method runs every search the default does.
  const bool long_primitives = search && forced == 0 && chain.size() >= kRangeMinPrimitives &&
                               chain.size() <= kRangeMaxPrimitives &&
                               double(limit - a) >= kRangeMovesPerPrimitive * double(chain.size());
  if ((search && wiggles(chain)) || (global && chain.size() > 1)) consider(layered_chain(a, limit));
  // (The global method's search goes on past the chain's length: a chain without a forced
  // kink is taken over one with, however long, and one longer may still lose primitives to
  // the merges. Where the default searches, the chain has no kink, and longer ones found
  // merge no shorter on Xu's curves or the corpus.)
  if (global && chain.size() > 1) consider(range_chain(a, limit, SIZE_MAX));
  if (long_primitives) consider(range_chain(a, limit, chain.size() - 1, kRangeFrontShare));
  if ((search || o_.method == FitOptions::Method::Greedy) && wiggles(chain)) untangle(a, limit, chain, forced, search);
  if (search && o_.method == FitOptions::Method::Greedy)  // (the stretch's other attempts walk as the greedy method does)
    for (uint32_t v = a + 1; v < limit; ++v) heading_[v] = input_tangent(v, a, limit);
  return chain;
}

/// Whether the joint at vertex v, after a move that is fixed or not, is one the fit made:
/// between two moves left as they are it is the input's own, unless one side is a line
/// that replaced several moves in another plane.
bool RunFitter::made_joint(uint32_t v, bool fixed_before) const {
  return !fixed_[v].fixed || !fixed_before || fixed_[v].fitted_start || (v > 0 && fixed_[v - 1].fitted_end);
}

std::vector<Chosen> RunFitter::keep() const {
  std::vector<Chosen> out;
  for (uint32_t v = 0; v < n_; ++v) out.push_back(input_move(v));
  return out;
}

RunFitter::Scratch& RunFitter::thread_scratch() {
  thread_local Scratch s;
  return s;
}

/// A stretch of the one move from vertex a: the move itself, or, where a fixed move's
/// direction is to be met at either end (in_tangent_, out_tangent_), the arc over it that
/// meets both within the joint's turn, when the band and the options allow it. (The input
/// turns there by less than a corner; kept as a line, the joint would break.)
Chosen RunFitter::one_move(uint32_t a) const {
  const uint32_t e = a + 1;
  std::optional<Vec2> T;
  if (in_tangent_) {
    T = aimed(a, *in_tangent_, e, out_tangent_);
  } else if (out_tangent_) {
    T = reflected_end(a, *out_tangent_, e);
  }
  if (T)
    if (auto c = through(a, *T, e); c && (!in_tangent_ || joint_cone_.holds(*in_tangent_, start_tangent(*c, a))) &&
                                    (!out_tangent_ || joint_cone_.holds(c->end_tangent, *out_tangent_)))
      return *c;
  return input_move(a);
}

/// The input's own move from vertex a to a + 1 as a line: always inside the band.
Chosen RunFitter::input_move(uint32_t a) const {
  Vec2 chord = q(a + 1) - q(a);
  Chosen line;
  line.prim = {a + 1, Primitive::Kind::Line};
  line.end_tangent = chord.norm() > kLengthEpsMm ? Vec2(chord.normalized()) : Vec2(1, 0);
  return line;
}

}  // namespace arcpress::fit_detail
