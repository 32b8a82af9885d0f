// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/verify/feed_pairing.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "arcpress/core/geometry.hpp"

namespace arcpress {

FeedCompared compare_feed(const FeedPath& pa, const Interpretation& ia, const FeedPath& pb, const Interpretation& ib,
                          const SegmentIndex& index_a, double tolerance_mm, const FeedVisit& visit) {
  constexpr size_t kWindow = 4096;  // A segments searched ahead of the cursor
  constexpr size_t kWindowFirst = 64;  // ... before asking whether any lies within the band
  const double along = std::cos(deg_to_rad(45)), same_way = std::cos(deg_to_rad(10));
  auto cosine = [&](size_t sa, const Vec3& db) {
    Vec3 da = pa.b(sa) - pa.a(sa);
    return da.norm() > kLengthEpsMm ? db.normalized().dot(da.normalized()) : -1.0;
  };
  // Where both paths have as many sections, a B segment's counterpart lies in the A section
  // of the same number (one that retraces an earlier section is not taken for it), and the
  // search starts no earlier than that section.
  const size_t sections = pa.section_length_mm.size();
  const bool same_sections = sections == pb.section_length_mm.size();
  std::vector<size_t> section_start(sections + 1, pa.size());
  for (size_t k = pa.size(); k-- > 0;) section_start[pa.section_of[k]] = k;
  // A move that extrudes is paired only with one that extrudes, a travel only with a travel:
  // in a band as wide as a printed line, a travel crosses the lines printed after it.
  auto prints = [](const Interpretation& in, uint32_t i) { return in.moves[i].to[kE] > in.from(i)[kE]; };
  auto may_pair = [&](size_t k, size_t sb) {
    return (!same_sections || pa.section_of[k] == pb.section_of[sb]) &&
           prints(ia, pa.move_of[k]) == prints(ib, pb.move_of[sb]);
  };
  // (An arc's closing step has no direction of its own: it is nobody's counterpart.)
  auto directed = [&](size_t k) { return pa.arc_of[k] != FeedPath::kClosingStep; };
  // A's segments in chunks of kChunk, each with the box its pieces lie in: a chunk whose box
  // lies farther than the band from a point holds no segment within the band of it, so the
  // window's scan passes it by (in a band as wide as a print's lines, most of the window).
  constexpr size_t kChunk = 64;
  struct Box {
    Vec3 lo, hi;
  };
  std::vector<Box> boxes((pa.size() + kChunk - 1) / kChunk,
                         Box{Vec3::Constant(HUGE_VAL), Vec3::Constant(-HUGE_VAL)});
  for (size_t k = 0; k < pa.size(); ++k) {
    const double off = pa.sagitta(k);  // a piece lies within its sagitta of its chord
    Box& b = boxes[k / kChunk];
    b.lo = b.lo.cwiseMin(pa.a(k).cwiseMin(pa.b(k)) - Vec3::Constant(off));
    b.hi = b.hi.cwiseMax(pa.a(k).cwiseMax(pa.b(k)) + Vec3::Constant(off));
  }
  auto box_within = [&](size_t chunk, const Vec3& p, double radius_mm) {
    const Box& b = boxes[chunk];
    return (p - p.cwiseMax(b.lo).cwiseMin(b.hi)).norm() <= radius_mm;
  };
  // How far along its path each segment starts (mm), on A and on B. B's path follows A's in
  // order, a little shorter or longer where it cuts a corner or rounds one: where the last
  // pair lay along both paths tells where along A the next B piece's counterpart lies.
  auto along_path = [](const FeedPath& p) {
    std::vector<double> at(p.size() + 1, 0.0);
    for (size_t k = 0; k < p.size(); ++k) at[k + 1] = at[k] + (p.b(k) - p.a(k)).norm();
    return at;
  };
  const std::vector<double> along_a = along_path(pa), along_b = along_path(pb);
  // Where along A's path its feed rate or S changes between two feed moves, in order. Which
  // of the two moves a point within a band's width of such a joint, along the path, stands
  // for is ambiguous: its feed is not compared. (Only A's: where A's feed is the same all
  // round a point, any other feed B has there differs, however short the B move that sets
  // it. Along the path, not in space: a piece is paired in program order, so a change the
  // path passed long before is no nearer for lying beside it.)
  std::vector<double> changes_a;
  for (size_t k = 1; k < pa.size(); ++k) {
    const Move& m0 = ia.moves[pa.move_of[k - 1]];
    const Move& m1 = ia.moves[pa.move_of[k]];
    if (pa.section_of[k] == pa.section_of[k - 1] && pa.move_of[k] != pa.move_of[k - 1] &&
        (m0.feed_mm_min != m1.feed_mm_min || m0.spindle != m1.spindle))
      changes_a.push_back(along_a[k]);
  }
  auto near_change = [&](double at_mm) {
    const auto c = std::lower_bound(changes_a.begin(), changes_a.end(), at_mm - tolerance_mm);
    return c != changes_a.end() && *c <= at_mm + tolerance_mm;
  };
  double shift_mm = 0;  // along A less along B, at the last pair (or the section's start)
  size_t cursor = 0;
  uint32_t near_hint = 0;  // the last nearest A segment: B's next middle lies near it
  size_t met = 0;           // the A segment at whose start a B move started last
  // Two programs' points are the same within the digits either prints (or a tenth of the band).
  const double same_point_mm = std::min(1e-3, tolerance_mm / 10);
  // B's pieces of the move met last, [move_first, move_last]: found once a move, not per piece.
  uint32_t range_move = UINT32_MAX;
  size_t move_first = 0, move_last = 0;
  double length_mm = 0, compared_mm = 0;  // of B's pieces, all and those whose feed was compared
  FeedCompared result;
  auto unpaired = [&](size_t sb, double mm) {
    result.unpaired_mm += mm;
    result.unpaired_move = std::min(result.unpaired_move, pb.move_of[sb]);
  };
  for (size_t sb = 0; sb < pb.size(); ++sb) {
    Vec3 db = pb.b(sb) - pb.a(sb);
    // (An arc's closing step is measured with the arc's pieces, which carry its feed.)
    if (db.norm() <= kLengthEpsMm || pb.arc_of[sb] == FeedPath::kClosingStep) continue;
    length_mm += db.norm();
    if (same_sections && (sb == 0 || pb.section_of[sb] != pb.section_of[sb - 1])) {
      const size_t start_a = section_start[pb.section_of[sb]];
      size_t start_b = sb;
      while (start_b > 0 && pb.section_of[start_b - 1] == pb.section_of[sb]) --start_b;
      cursor = std::max(cursor, start_a);
      met = std::max(met, start_a);
      shift_mm = along_a[std::min(start_a, pa.size())] - along_b[start_b];
    }
    // Where a B move starts on a vertex of A (as the compressor's moves all do), at or after
    // the last such vertex, the two paths are at the same place: the pairing goes on from
    // there, back too where a piece was taken for a later pass's, and the count along both
    // starts again. (Where B cuts a slicer's zig-zag infill short in a band many lines wide,
    // counting on from the last pair falls behind A's longer path, and the window's search
    // ahead finds a line of the next layer.) Of A's vertices there (a loop that closes meets
    // its start twice), the one nearest to where the count along both expects it.
    if (sb == 0 || pb.move_of[sb - 1] != pb.move_of[sb]) {
      const Vec3 start = pb.a(sb);
      const double expected = along_b[sb] + shift_mm;
      size_t at = pa.size();
      for (size_t k = met; k < std::min(pa.size(), met + kWindow); ++k) {
        if (at < pa.size() && along_a[k] - expected > std::abs(along_a[at] - expected)) break;
        if (k % kChunk == 0 && !box_within(k / kChunk, start, same_point_mm)) {
          k += kChunk - 1;
          continue;
        }
        if ((pa.a(k) - start).norm() <= same_point_mm && may_pair(k, sb) &&
            (at == pa.size() || std::abs(along_a[k] - expected) < std::abs(along_a[at] - expected)))
          at = k;
      }
      if (at < pa.size()) {
        met = cursor = at;
        shift_mm = along_a[at] - along_b[sb];
      }
    }
    Vec3 mid = pb.middle(sb);
    const double mid_along_b = along_b[sb] + db.norm() / 2;
    size_t found = pa.size();
    auto search = [&](size_t from, size_t to) {
      for (size_t k = from; k < std::min(pa.size(), to) && found == pa.size(); ++k) {
        if (k % kChunk == 0 && !box_within(k / kChunk, mid, tolerance_mm)) {
          k += kChunk - 1;
          continue;
        }
        if (may_pair(k, sb) && directed(k) && (pa.nearest(k, mid) - mid).norm() <= tolerance_mm &&
            cosine(k, db) >= along)
          found = k;
      }
    };
    auto within = [&](size_t k, const Vec3& p) { return (pa.nearest(k, p) - p).norm() <= tolerance_mm; };
    // First, of the segments within a band's width along A of where the piece lies along B,
    // the one nearest that place that lies within the band and does not run against the
    // piece, else the nearest that lies within the band: an arc that rounds a corner of
    // moves shorter than the band heads far off each of them (and may cross them), and the
    // first segment ahead that runs its way may be the next move, or a line printed a layer
    // or a pass later; a travel that leaves where the piece ends may lie nearer in space than
    // the piece's own move, but runs another way. (Taken outward from that place, so that
    // where moves are far shorter than the band the search still ends at once.)
    {
      const double expected = mid_along_b + shift_mm;
      const size_t last = std::min(pa.size(), cursor + kWindow);  // past the window's last
      size_t k = cursor;
      while (k + 1 < last && along_a[k + 1] <= expected) ++k;
      auto gap = [&](size_t c) {  // how far along A segment c lies from `expected`
        return along_a[c] > expected ? along_a[c] - expected : std::max(0.0, expected - along_a[c + 1]);
      };
      constexpr size_t kNone = SIZE_MAX;
      size_t down = k < last ? k : kNone, up = k + 1, against = kNone;
      while (found == pa.size()) {
        const bool can_down = down != kNone && gap(down) <= tolerance_mm;
        const bool can_up = up < last && gap(up) <= tolerance_mm;
        if (!can_down && !can_up) break;
        const bool take_down = can_down && (!can_up || gap(down) <= gap(up));
        const size_t c = take_down ? down : up;
        if (take_down)
          down = down > cursor ? down - 1 : kNone;
        else
          ++up;
        if (!may_pair(c, sb) || !directed(c) || !within(c, mid)) continue;
        if (cosine(c, db) >= 0)
          found = c;
        else if (against == kNone)
          against = c;
      }
      if (found == pa.size() && against != kNone) found = against;
    }
    // Else the segment paired last, and the next; then, where a piece of a B arc runs off
    // both by more than the window's angle, the one the whole arc lies over (both its ends
    // within the band of it), unless the piece runs against it: an arc over a short move
    // heads up to 90° off it inside the band, and a later pass that crosses the arc at its
    // own heading is not the move it stands for.
    if (found == pa.size()) search(cursor, cursor + 2);
    // B's pieces of its move, and whether p lies within the band of one of them.
    if (const uint32_t move = pb.move_of[sb]; move != range_move) {
      range_move = move;
      move_first = move_last = sb;
      while (move_first > 0 && pb.move_of[move_first - 1] == move) --move_first;
      while (move_last + 1 < pb.size() && pb.move_of[move_last + 1] == move) ++move_last;
    }
    auto near_move = [&](const Vec3& p) {
      for (size_t s = move_first; s <= move_last; ++s)
        if ((pb.nearest(s, p) - p).norm() <= tolerance_mm) return true;
      return false;
    };
    if (found == pa.size() && pb.curved(sb)) {
      const uint32_t arc = pb.move_of[sb];
      const Vec3 from = xyz(ib.from(arc)), to = xyz(ib.moves[arc].to);
      // Both ways: the arc within the band of the move, and the move within the band of the
      // arc (a small arc beside a long plunge, in a band wider than the arc, is not that
      // plunge's).
      for (size_t k = cursor; k < std::min(pa.size(), cursor + 2) && found == pa.size(); ++k)
        if (may_pair(k, sb) && directed(k) && cosine(k, db) >= 0 && within(k, mid) && within(k, from) &&
            within(k, to) && near_move(pa.a(k)) && near_move(pa.b(k)))
          found = k;
    }
    // The first steps of the window, then whether any segment lies within the band at all:
    // where none does (B strays from A there), the rest of the window holds no counterpart.
    if (found == pa.size()) search(cursor + 2, cursor + kWindowFirst);
    if (found == pa.size()) {
      const SegmentIndex::Nearest n = index_a.nearest(mid, near_hint);
      near_hint = n.segment;
      if (n.distance_mm > tolerance_mm) continue;  // (B strays from A: the path measure tells)
      search(cursor + kWindowFirst, cursor + kWindow);
      if (found == pa.size() && n.segment >= cursor && may_pair(n.segment, sb) && directed(n.segment) &&
          cosine(n.segment, db) >= same_way)
        found = n.segment;
    }
    // Last, the stretch of A from the last pair on (or the segment after it) that lies within
    // the band of B's move, which that move stands for: of its segments within the band of
    // the piece, the nearest (a plunge written for a helix narrower than the band: A's path
    // runs round while B's runs down, and as far along each).
    if (found == pa.size()) {
      double nearest_mm = tolerance_mm;
      for (size_t k = cursor; k < std::min(pa.size(), cursor + kWindow); ++k) {
        if (!near_move(pa.a(k)) || !near_move(pa.b(k))) {
          if (k == cursor) continue;
          break;
        }
        const double dist = (pa.nearest(k, mid) - mid).norm();
        if (may_pair(k, sb) && directed(k) && dist <= nearest_mm) {
          nearest_mm = dist;
          found = k;
        }
      }
      if (found == pa.size()) {
        unpaired(sb, db.norm());
        continue;
      }
    }
    cursor = found;
    const double into_mm = (pa.nearest(found, mid) - pa.a(found)).norm();  // along the A segment
    const double paired_along_a = along_a[found] + std::min(into_mm, along_a[found + 1] - along_a[found]);
    shift_mm = paired_along_a - mid_along_b;
    uint32_t move_a = pa.move_of[found], move_b = pb.move_of[sb];
    if (near_change(paired_along_a)) continue;
    if (ia.moves[move_a].feed_mm_min <= 0) continue;
    visit(ia.moves[move_a], ib.moves[move_b], mid);
    compared_mm += db.norm();
  }
  result.share = length_mm > 0 ? compared_mm / length_mm : 1.0;
  return result;
}

}  // namespace arcpress
