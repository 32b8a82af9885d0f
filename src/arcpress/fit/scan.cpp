// SPDX-License-Identifier: GPL-3.0-or-later
// The curvature-interval scan: for a start and a tangent, every end a line or arc can
// reach inside the band, in one linear pass; and the candidates the methods take from it.
#include "arcpress/fit/scan_ends.hpp"

namespace arcpress::fit_detail {

/// All ends e in (a, limit] for which the arc (or line) leaving `a` along `T` and passing
/// exactly through vertex e keeps every vertex in between inside the band. For a fixed
/// start and tangent, each vertex allows an interval of curvatures (exact for the full
/// circle), so the scan is linear and stops when the intervals no longer meet.
void RunFitter::scan(uint32_t a, const Vec2& T, uint32_t limit, std::vector<Candidate>& out) const {
  out.clear();
  scan_ends(a, T, limit, [&](const Candidate& c) { out.push_back(c); });
}

RunFitter::ScanLimits RunFitter::scan_limits() const {
  return {max_alpha_,
          min_alpha_,
          line_alpha_,
          1 / o_.max_radius_mm,
          1 / o_.min_radius_mm,
          o_.min_arc_length_mm,
          o_.min_arc_moves,
          arcs_,
          o_.helical,
          stretch_end_,
          out_tangent_ ? &*out_tangent_ : nullptr,
          o_.band_side};
}

/// How far the chain reaches in one more step from vertex `e` along `T`: the last end
/// the curvature scan allows (not yet checked exactly), or `e` itself when nothing fits.
/// A corner or the end of the stretch counts as reaching the end.
uint32_t RunFitter::reach_after(uint32_t e, const Vec2& T, uint32_t limit) const {
  if (e >= limit) return limit + 1;
  uint32_t reach = e;
  scan_ends(e, T, limit, [&](const Candidate& c) { reach = c.e; });
  return reach;
}

/// Up to `count` primitives from `a` along `T` that pass the exact check, spread over the
/// longer half of the scan's candidates, longest first. After a failure the walk steps
/// back by growing strides to bound the work, and still tries the shortest candidate.
void RunFitter::checked_from(uint32_t a, const Vec2& T, uint32_t limit, int count, std::vector<Chosen>& out) const {
  std::vector<Candidate>& cand = s_.checked_cand;
  scan(a, T, limit, cand);
  int checked = 0;
  size_t stride = 1;
  for (size_t i = cand.size(); i > 0 && checked < count;) {
    --i;
    if (auto c = make(a, T, cand[i])) {
      ++checked;
      out.push_back(*c);
      size_t step = std::max<size_t>(1, cand.size() / (2 * static_cast<size_t>(count)));
      i = i >= step ? i - step + 1 : 0;
      if (i == 0) break;
      continue;
    }
    if (i < stride) {
      if (i > 0 && stride > 1) {
        i = 1;
        stride = 1;
        continue;
      }
      break;
    }
    i -= stride - 1;
    stride *= 2;
  }
}

/// Up to `count` candidates from `a` along `T`, spread over the longer half of what the
/// scan allows, longest first; not yet checked exactly. With `next_to_longest`, also the
/// one before the longest: where a straight stretch turns into a fillet, the primitive
/// that ends at the turn, one vertex short of the furthest the band lets it overshoot, is
/// the one the next can follow (a rounded rectangle: 11 blocks without it, 8 with).
/// While a greedy step is taken in a search (s_.guide_record), the scan is kept as a
/// GuideScan; with `reuse` (the beam, expanding its guide), a greedy step's scan from `a`
/// along T is taken again when there is one. Returns that GuideScan, else null.
RunFitter::GuideScan* RunFitter::pick(uint32_t a, const Vec2& T, uint32_t limit, int count, std::vector<Candidate>& out,
                                      bool next_to_longest, bool reuse) const {
  GuideScan* kept = reuse ? guide_scan(a, T, limit) : nullptr;
  if (!kept && s_.guide_record) {
    kept = &s_.guide_scans[s_.guide_next++ % s_.guide_scans.size()];
    kept->stretch = stretch_id_;
    kept->a = a;
    kept->limit = limit;
    kept->T = T;
    kept->reach.clear();
    scan(a, T, limit, kept->ends);
  } else if (!kept) {
    scan(a, T, limit, s_.scanned);
  }
  const std::vector<Candidate>& all = kept ? kept->ends : s_.scanned;
  out.clear();
  const size_t n = all.size(), want = static_cast<size_t>(count);
  const size_t step = std::max<size_t>(1, n / (2 * want));
  for (size_t i = n; i > 0 && out.size() < want; i = i > step ? i - step : 0) out.push_back(all[i - 1]);
  if (next_to_longest && step > 1 && n >= 2) out.push_back(all[n - 2]);
  // Where those two end heading off the input by more than a joint can turn back (an arc
  // run on past the point where its fillet meets a straight side, which the band allows
  // for sqrt(2·R·band): 18 moves of 0.05 mm on a radius of 40 mm), also the longest that
  // ends heading along the input, or one before it while each heads closer still: the
  // input's direction just past a joint of the drawing still leans towards the other side.
  auto misses = [&](size_t i) {  // 1 - cos of the angle between end tangent and input
    const uint32_t e = all[i].e;
    return heading_[e] ? 1 - heading_[e]->dot(unchecked(a, T, all[i]).end_tangent) : 2.0;
  };
  if (next_to_longest && step > 2 && misses(n - 1) > joint_miss_ && misses(n - 2) > joint_miss_)
    for (size_t i = n - 2; i-- > n - step;)
      if (misses(i) <= joint_miss_) {
        while (i > n - step && misses(i - 1) < misses(i) - closer_miss_) --i;
        out.push_back(all[i]);
        break;
      }
  return kept;
}

/// The greedy steps' scan from `a` along exactly `T` in this stretch, or null.
RunFitter::GuideScan* RunFitter::guide_scan(uint32_t a, const Vec2& T, uint32_t limit) const {
  for (GuideScan& g : s_.guide_scans)
    if (g.stretch == stretch_id_ && g.a == a && g.limit == limit && g.T == T) return &g;
  return nullptr;
}

/// What candidate `c` from `a` along `T` would be, for scoring before the exact check: its
/// end vertex and end tangent (T reflected about the chord; a line's is the chord).
Chosen RunFitter::unchecked(uint32_t a, const Vec2& T, const Candidate& c) const {
  Chosen lite;
  lite.prim.end_vertex = c.e;
  Vec2 chord = q(c.e) - q(a);
  lite.end_tangent = !c.line ? reflected_end(a, T, c.e) : chord.norm() > 0 ? Vec2(chord.normalized()) : T;
  return lite;
}

}  // namespace arcpress::fit_detail
