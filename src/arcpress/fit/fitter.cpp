// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/fit/fitter.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <tuple>
#include <unordered_set>

#include "arcpress/fit/run_fitter.hpp"

namespace arcpress {

using fit_detail::Chosen;
using fit_detail::FixedMove;
using fit_detail::RunFitter;

double normal_axis_spread_mm(const FitOptions& o) {
  // A vertex and the height carried between two vertices of the stretch both lie within its
  // spread, so the height check of make_arc() holds at every vertex.
  return o.helical ? o.tolerance_mm * (1.0 - rounding_reserve_share(o)) * fit_detail::kHeightShare : 0.0;
}

namespace {

std::vector<FitResult> fit_chain_once(const Interpretation& in, const RunChain& chain, std::span<const Run> runs,
                                      const std::function<FitOptions(const Run&)>& options_for) {
  std::span<const Run> own(&runs[chain.first_run], chain.run_count);
  // The keep method: every move its own line, with none of the fit's preparation (the
  // corner rule, the vertices where a primitive must end), so that the pipeline it times is
  // the one without the fitter.
  if (chain.run_count > 0 && options_for(own[0]).method == FitOptions::Method::Keep) {
    std::vector<FitResult> kept(own.size());
    for (size_t r = 0; r < own.size(); ++r)
      for (uint32_t v = 1; v <= own[r].move_count; ++v) kept[r].prims.push_back({v, Primitive::Kind::Line});
    return kept;
  }
  const Move& lead = in.moves[chain.first_move];
  auto base = [&](size_t r) { return own[r].first_move - chain.first_move; };
  auto direction = [](const Vec2& d) -> std::optional<Vec2> {
    if (d.norm() <= kLengthEpsMm) return std::nullopt;
    return Vec2(d.normalized());
  };
  // The ends of each run's fit once made: the chain's vertices of its first and of its last
  // primitive, where that primitive is a line (an arc in another plane leaves the joint
  // unmeasured, as the verifier does).
  struct LineEnds {
    uint32_t from, to;
  };
  std::vector<std::optional<LineEnds>> first_line(own.size()), last_line(own.size());
  std::vector<uint8_t> done(own.size(), 0);
  std::vector<FitResult> out(own.size());

  // The runs in `plane` fitted together, every other move of the chain left as it is: lone
  // moves and input arcs with their own directions, runs already fitted with the directions
  // of their end lines, runs still to be fitted (in another plane) with none.
  auto fit_plane = [&](Plane plane) {
    Run all;  // the chain as one run in `plane`
    all.first_move = chain.first_move;
    all.move_count = chain.move_count;
    all.frame = lead.frame;
    all.plane = plane;
    all.feed_mm_min = lead.feed_mm_min;
    const auto ax = axes_of(plane);
    auto at = [&](uint32_t v) {  // vertex v of the chain in the plane
      const auto& p = all.vertex(in, v);
      return Vec2(p[ax.first], p[ax.second]);
    };
    std::vector<FixedMove> fixed(chain.move_count);
    std::vector<uint8_t> pinned(chain.move_count + 1, 0);
    for (uint32_t m = 0; m < chain.move_count; ++m) fixed[m].fixed = true;
    for (size_t r = 0; r < own.size(); ++r)
      if (own[r].plane == plane)
        for (uint32_t m = base(r); m < base(r) + own[r].move_count; ++m) fixed[m].fixed = false;
    // (The directions of the moves fitted here are not read.)
    for (uint32_t m = 0; m < chain.move_count; ++m) {
      if (!fixed[m].fixed) continue;
      const Move& mv = in.moves[chain.first_move + m];
      if (!is_arc(mv.kind)) {
        fixed[m].start = fixed[m].end = direction(at(m + 1) - at(m));
      } else if (mv.plane == plane) {
        const Vec2 c(mv.center[ax.first], mv.center[ax.second]);
        auto along = [&](const Vec2& radius) -> std::optional<Vec2> {
          if (radius.norm() <= kLengthEpsMm) return std::nullopt;
          return arc_tangent(radius, mv.kind == MoveKind::ArcCCW);
        };
        fixed[m].start = along(at(m) - c);
        fixed[m].end = along(at(m + 1) - c);
      }
    }
    for (size_t r = 0; r < own.size(); ++r) {
      const uint32_t b = base(r), last = b + own[r].move_count - 1;
      pinned[b] = pinned[last + 1] = 1;
      if (own[r].plane == plane) continue;
      for (uint32_t m = b; m < last; ++m) fixed[m].end = fixed[m + 1].start = std::nullopt;
      fixed[b].start = fixed[last].end = std::nullopt;
      if (!done[r]) continue;
      // (A line that stands for one move that goes somewhere is that move: its joints are the input's.)
      auto several = [&](const LineEnds& l) {
        return in.moves_going(chain.first_move + l.from, chain.first_move + l.to) > 1;
      };
      if (const auto& l = first_line[r]) {
        fixed[b].start = direction(at(l->to) - at(l->from));
        fixed[b].fitted_start = fixed[b].start && several(*l);
      }
      if (const auto& l = last_line[r]) {
        fixed[last].end = direction(at(l->to) - at(l->from));
        fixed[last].fitted_end = fixed[last].end && several(*l);
      }
    }
    for (uint32_t m = 0; m < chain.move_count; ++m)
      if (fixed[m].fixed) pinned[m] = pinned[m + 1] = 1;
    std::vector<Chosen> fitted = RunFitter(in, all, options_for(all), fixed, std::move(pinned)).fit();
    // Back to each run's own vertices. A tangent break at the start of a fixed move is the
    // joint at the end of the run before it, or at the start of the run it begins.
    size_t r = 0;  // the first run that does not end at or before `from`
    uint32_t from = 0;
    for (const Chosen& c : fitted) {
      while (r < own.size() && base(r) + own[r].move_count <= from) ++r;
      if (!fixed[from].fixed) {
        if (!first_line[r] && from == base(r) && c.prim.kind == Primitive::Kind::Line)
          first_line[r] = LineEnds{from, c.prim.end_vertex};
        if (c.prim.end_vertex == base(r) + own[r].move_count)
          last_line[r] =
              c.prim.kind == Primitive::Kind::Line ? std::optional(LineEnds{from, c.prim.end_vertex}) : std::nullopt;
        Primitive p = c.prim;
        p.end_vertex -= base(r);
        out[r].prims.push_back(p);
        if (c.kinked) out[r].forced_at.push_back(from - base(r));
      } else if (c.kinked && r > 0 && base(r - 1) + own[r - 1].move_count == from) {
        out[r - 1].forced_at.push_back(own[r - 1].move_count);
      } else if (c.kinked && r < own.size() && base(r) == from) {
        out[r].forced_at.push_back(0);
      }
      from = c.prim.end_vertex;
    }
    for (size_t k = 0; k < own.size(); ++k) done[k] = done[k] || own[k].plane == plane;
  };
  // Runs in other planes than the chain's first, plane by plane, then the chain's plane,
  // which meets their end lines tangentially.
  for (size_t r = 0; r < own.size(); ++r)
    if (!done[r] && own[r].plane != lead.plane) fit_plane(own[r].plane);
  fit_plane(lead.plane);
  // The passes report a run's joints in their own order, a joint beside another plane's run
  // possibly twice.
  for (FitResult& f : out) {
    std::sort(f.forced_at.begin(), f.forced_at.end());
    f.forced_at.erase(std::unique(f.forced_at.begin(), f.forced_at.end()), f.forced_at.end());
  }
  return out;
}

/// The direction a primitive of a run leaves vertex `from` (start) or arrives at `to` (end),
/// in the run's plane; zero where it goes nowhere there.
Vec2 primitive_tangent(const Primitive& p, const Vec2& from, const Vec2& to, bool at_end) {
  if (p.kind == Primitive::Kind::Arc) return arc_tangent((at_end ? to : from) - p.center, p.ccw);
  const Vec2 d = to - from;
  return d.norm() > kLengthEpsMm ? Vec2(d.normalized()) : Vec2(0, 0);
}

/// Takes out of `fits`' forced kinks those that turn by no more than the fitter's own joint
/// turn under `options_for`'s G1 angle (a fit made under a narrower angle may have broken
/// the tangent by less than a wider one allows; a kink at a run's end, beside what is no
/// primitive of it, stays), and returns the kinks left and the primitives, the order fits
/// are weighed in: fewer kinks first (a kink breaks the tangency the fit promises where it
/// can), then fewer primitives.
std::pair<size_t, size_t> keep_real_kinks(const Interpretation& in, const RunChain& chain, std::span<const Run> runs,
                                          std::vector<FitResult>& fits,
                                          const std::function<FitOptions(const Run&)>& options_for) {
  size_t kinks = 0, prims = 0;
  for (size_t k = 0; k < fits.size(); ++k) {
    FitResult& f = fits[k];
    const Run& run = runs[chain.first_run + k];
    prims += f.prims.size();
    if (f.forced_at.empty()) continue;
    const double g1_angle_deg = options_for(run).g1_angle_deg;
    auto at = [&](uint32_t v) {
      const Vec3 p = in_plane(run.vertex(in, v), run.plane);
      return Vec2(p.x(), p.y());
    };
    auto allowed = [&](uint32_t v) {
      size_t i = 0;  // the primitive ending at v
      while (i < f.prims.size() && f.prims[i].end_vertex < v) ++i;
      if (v == 0 || v >= run.move_count || i + 1 >= f.prims.size() || f.prims[i].end_vertex != v) return false;
      const uint32_t start = i == 0 ? 0 : f.prims[i - 1].end_vertex;
      const Vec2 arrive = primitive_tangent(f.prims[i], at(start), at(v), true);
      const Vec2 leave = primitive_tangent(f.prims[i + 1], at(v), at(f.prims[i + 1].end_vertex), false);
      const double turn_deg = rad_to_deg(std::atan2(std::abs(cross2(arrive, leave)), arrive.dot(leave)));
      return turn_deg <= fit_detail::kJointShare * g1_angle_deg;  // (the turn the fitter itself makes at most)
    };
    f.forced_at.erase(std::remove_if(f.forced_at.begin(), f.forced_at.end(), allowed), f.forced_at.end());
    kinks += f.forced_at.size();
  }
  return {kinks, prims};
}

}  // namespace

std::vector<FitResult> fit_chain(const Interpretation& in, const RunChain& chain, std::span<const Run> runs,
                                 const std::function<FitOptions(const Run&)>& options_for,
                                 const std::function<FitOptions(const Run&)>& baseline_for) {
  std::vector<FitResult> out = fit_chain_once(in, chain, runs, options_for);
  // The searches turn by other angles and reach other chains under looser limits, and may
  // miss one the tighter limits found.
  if (!baseline_for || chain.run_count == 0) return out;
  bool looser = false;
  for (uint32_t r = chain.first_run; r < chain.first_run + chain.run_count && !looser; ++r)
    looser = !(baseline_for(runs[r]) == options_for(runs[r]));
  if (!looser) return out;
  std::vector<FitResult> tight = fit_chain_once(in, chain, runs, baseline_for);
  // (The looser fit's own kinks are the fitter's, under the looser angle already.)
  size_t out_kinks = 0, out_prims = 0;
  for (const FitResult& f : out) {
    out_kinks += f.forced_at.size();
    out_prims += f.prims.size();
  }
  if (keep_real_kinks(in, chain, runs, tight, options_for) < std::pair(out_kinks, out_prims)) out = std::move(tight);
  return out;
}

}  // namespace arcpress
