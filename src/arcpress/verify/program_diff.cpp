// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/verify/program_diff.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <tuple>

#include "arcpress/core/deviation.hpp"
#include "arcpress/core/error.hpp"
#include "arcpress/core/workers.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/verify/feed_path.hpp"
#include "arcpress/verify/feed_pairing.hpp"
#include "arcpress/verify/segment_index.hpp"

namespace arcpress {
namespace {

using Path = FeedPath;

/// Two arcs' centres this close (a share of the radius, and of 1 mm) are one centre: the
/// floating noise of reading the same numbers two ways, a floating-point epsilon.
constexpr double kSameCentreShare = 1e-12;
/// Segments of the longer path in each share of the path measure (see diff_programs()):
/// enough that the few points each share measures before its own maximum has grown cost
/// little, few enough that two or more threads have shares to take.
constexpr size_t kShareSegments = 65536;

/// Whether block `b` holds a keyword of its dialect (Sinumerik's `G642 SOFT`, `TRANS X10`,
/// `MCALL CYCLE81(...)`, whose call is in no word).
bool has_keyword(const Program& p, const Block& b) {
  if (p.rules.keywords.empty()) return false;
  for (auto* w = p.words_begin(b); w != p.words_end(b); ++w)
    if (w->letter == kKeywordLetter) return true;
  return false;
}

/// The key by which non-motion blocks are compared, written into `key`: their M, T, S
/// words, a dwell, and their comment (with `comments`), so that units, spacing and modal
/// G-codes do not count; for blocks that are not ordinary words (`%`, flow control, macros,
/// host commands) or that hold a keyword, their whole text.
void non_motion_key(const Program& p, const Block& b, bool comments, std::string& key) {
  key.clear();
  if ((b.kind != BlockKind::Code && b.kind != BlockKind::Empty) || has_keyword(p, b)) {
    // Tape marks, flow control, macros, host commands, blocks not understood: their text.
    std::string_view raw = p.raw(b);
    while (!raw.empty() && std::isspace(static_cast<unsigned char>(raw.back()))) raw.remove_suffix(1);
    while (!raw.empty() && std::isspace(static_cast<unsigned char>(raw.front()))) raw.remove_prefix(1);
    key.assign(raw);
    return;
  }
  bool dwell = false;
  for (auto* w = p.words_begin(b); w != p.words_end(b); ++w) {
    if (w->letter == 'G' && !w->is_expr && w->code10() == 40) dwell = true;
  }
  for (auto* w = p.words_begin(b); w != p.words_end(b); ++w) {
    if (w->letter == 'M' || w->letter == 'T' || w->letter == 'S' || (dwell && (w->letter == 'P' || w->letter == 'G'))) {
      if (!key.empty()) key += ' ';
      key += p.raw(b, *w);
    }
  }
  if (comments && b.has_comment) {
    std::string_view raw = p.raw(b);
    size_t c = std::min(raw.find('('), raw.find(';'));
    if (c != std::string_view::npos) {
      if (!key.empty()) key += ' ';
      key.append(raw.substr(c));
    }
  }
  for (char& c : key) c = char(std::toupper(static_cast<unsigned char>(c)));
}

/// Whether non_motion_key() of the block is not empty, without building it.
bool has_non_motion_key(const Program& p, const Block& b, bool comments) {
  if ((b.kind != BlockKind::Code && b.kind != BlockKind::Empty) || has_keyword(p, b))
    return p.raw(b).find_first_not_of(" \t\r\n\f\v") != std::string_view::npos;
  for (auto* w = p.words_begin(b); w != p.words_end(b); ++w)
    if (w->letter == 'M' || w->letter == 'T' || w->letter == 'S' ||
        (w->letter == 'G' && !w->is_expr && w->code10() == 40))
      return true;
  return comments && b.has_comment && p.raw(b).find_first_of("(;") != std::string_view::npos;
}

/// The non-motion blocks of a program in order, one at a time: a block's key is built, into
/// the same buffer each time, only when asked for.
class NonMotionBlocks {
 public:
  NonMotionBlocks(const Program& p, const Interpretation& in, bool comments) : p_(p), in_(in), comments_(comments) {}

  /// Moves to the next non-motion block: false past the last. Then key() and line() are its.
  bool next() {
    for (; bi_ < p_.blocks.size(); ++bi_) {
      const Block& b = p_.blocks[bi_];
      if (b.kind == BlockKind::Empty && !b.has_comment) continue;
      if (bi_ < in_.move_of_block.size() && in_.move_of_block[bi_] >= 0 && !b.has_comment) continue;
      // (arcpress's own header comment is no part of the program.)
      if (b.kind == BlockKind::Empty && is_arcpress_header(p_.raw(b))) continue;
      if (!has_non_motion_key(p_, b, comments_)) continue;
      block_ = &b;
      line_ = b.line;
      ++count_;
      ++bi_;
      return true;
    }
    return false;
  }
  const std::string& key() {
    non_motion_key(p_, *block_, comments_, key_);
    return key_;
  }
  /// Whether the block's key is `other`'s. Where the two blocks are the same bytes, without
  /// building either: the lexer makes a block from its bytes alone, but for a first line's
  /// byte-order mark.
  bool same_key(NonMotionBlocks& other) {
    const bool first_line = line_ == 1 || other.line_ == 1;
    return (!first_line && p_.raw(*block_) == other.p_.raw(*other.block_)) || key() == other.key();
  }
  uint32_t line() const { return line_; }
  /// The blocks next() has moved to.
  size_t count() const { return count_; }

 private:
  const Program& p_;
  const Interpretation& in_;
  bool comments_;
  size_t bi_ = 0;
  const Block* block_ = nullptr;
  std::string key_;
  uint32_t line_ = 0;
  size_t count_ = 0;
};

/// The largest distances found so far, at most `size` places with distinct line pairs,
/// largest first. Below floor() nothing can enter.
class TopPlaces {
 public:
  /// `least_mm`: distances at or below it are of no interest (DiffOptions::least_mm).
  explicit TopPlaces(size_t size, double least_mm = 0) : size_(std::max<size_t>(size, 1)), least_mm_(least_mm) {}

  double floor() const { return std::max(least_mm_, places_.size() < size_ ? 0.0 : places_.back().deviation_mm); }
  double max() const { return places_.empty() ? 0.0 : places_.front().deviation_mm; }
  /// What a bound must exceed to be worth splitting for: the maximum, or the least of interest.
  double reach() const { return std::max(least_mm_, max()); }

  void offer(const DiffPlace& p) {
    auto same = std::find_if(places_.begin(), places_.end(), [&](const DiffPlace& q) {
      return q.line_a == p.line_a && q.line_b == p.line_b;
    });
    if (same != places_.end()) {
      if (p.deviation_mm <= same->deviation_mm) return;
      *same = p;
    } else if (places_.size() < size_) {
      places_.push_back(p);
    } else if (p.deviation_mm > places_.back().deviation_mm) {
      places_.back() = p;
    } else {
      return;
    }
    std::sort(places_.begin(), places_.end(), [](const DiffPlace& x, const DiffPlace& y) {
      return x.deviation_mm != y.deviation_mm ? x.deviation_mm > y.deviation_mm
                                              : std::tie(x.line_a, x.line_b) < std::tie(y.line_a, y.line_b);
    });
  }

  std::vector<DiffPlace> take() { return std::move(places_); }

 private:
  size_t size_;
  double least_mm_;
  std::vector<DiffPlace> places_;
};

/// Measures the distance from every point of `from` to `to` (one direction). See the
/// header for why no point between evaluations can be farther.
///
/// Both paths usually run side by side in the same order, so each point is first measured
/// against the stretch of `to` around the previous answer (a walk along `to` while the
/// distance falls). That distance is an upper bound of the true one; only when it exceeds
/// `floor_mm` (the smallest distance that could still change the result: enter the worst
/// places, hence also raise the maximum) is the spatial index asked for the exact nearest
/// segment. Bounds below use any point of `to`, so they hold for either answer.
class Directed {
 public:
  Directed(const Path& from, const Path& to, const SegmentIndex& index, double precision_mm, const TopPlaces& top)
      : from_(from), to_(to), index_(index), precision_mm_(precision_mm), top_(top) {}

  /// `visit(from_segment, nearest, point)` for every evaluated point; `nearest` is exact
  /// when its distance exceeds the floor at the time of the visit.
  /// ... for `from`'s segments [begin, end), but those `repeats` marks: each is an earlier
  /// segment of `from` again, whose points lie exactly as far from `to`.
  template <class Visit>
  void run(size_t begin, size_t end, const std::vector<bool>& repeats, Visit&& visit) {
    if (index_.empty()) return;
    points_left_ = kPointsPerSegment * (end - begin) + kPointsBase;
    SegmentIndex::Nearest n0{};
    Vec3 last(NAN, NAN, NAN);
    for (size_t s = begin; s < end; ++s) {
      if (repeats[s]) continue;
      Vec3 p0 = from_.a(s), p1 = from_.b(s);
      if (!(p0 == last)) {
        n0 = locate(p0, n0.segment);
        visit(s, n0, p0);
      }
      SegmentIndex::Nearest n1 = locate(p1, n0.segment);
      visit(s, n1, p1);
      // Bounded by one segment of `to` where p0 lies as near it as it lies to its nearest (or
      // nearer than anything of interest): a vertex two segments share, on a path written
      // back as it was, then needs no split (a bound may use any point of `to`, nearest or not).
      SegmentIndex::Nearest b0 = n0;
      if (n0.segment != n1.segment) {
        const SegmentIndex::Nearest alt = on_segment(p0, n1.segment);
        if (alt.distance_mm <= std::max(n0.distance_mm, top_.floor())) b0 = alt;
      }
      refine(s, p0, b0, p1, n1, 0, visit);
      n0 = n1;
      last = p1;
    }
  }

 private:
  SegmentIndex::Nearest locate(const Vec3& p, uint32_t hint) const {
    SegmentIndex::Nearest near = walk_nearest(p, hint, top_.floor());
    return near.distance_mm <= top_.floor() ? near : index_.nearest(p, near.segment);
  }

  SegmentIndex::Nearest on_segment(const Vec3& p, uint32_t s) const {
    const Vec3 q = to_.nearest(s, p);
    return {(q - p).norm(), s, q};
  }

  /// The nearest of `to`'s segments reached from `hint` by stepping along `to` either way
  /// while the distance falls (a few steps of no gain are allowed, for zero-length pieces
  /// and small zig-zags); or the first found no farther than `enough_mm`, where nothing
  /// nearer matters (a point on a path written back as it was).
  SegmentIndex::Nearest walk_nearest(const Vec3& p, uint32_t hint, double enough_mm) const {
    constexpr int kMaxSteps = 256, kMaxMisses = 3;
    SegmentIndex::Nearest best = on_segment(p, hint);
    if (best.distance_mm <= enough_mm) return best;
    for (int dir : {+1, -1}) {
      int64_t s = hint;
      for (int steps = 0, misses = 0; steps < kMaxSteps && misses <= kMaxMisses; ++steps) {
        s += dir;
        if (s < 0 || s >= int64_t(to_.size())) break;
        SegmentIndex::Nearest n = on_segment(p, uint32_t(s));
        if (n.distance_mm < best.distance_mm) {
          best = n;
          if (best.distance_mm <= enough_mm) return best;
          misses = 0;
        } else {
          ++misses;
        }
      }
    }
    return best;
  }

  /// Splits `from`'s segment (or piece of an arc) s between p0 and p1 at its middle while
  /// the bound on the distance along it could still beat the maximum.
  template <class Visit>
  void refine(size_t s, const Vec3& p0, const SegmentIndex::Nearest& n0, const Vec3& p1,
              const SegmentIndex::Nearest& n1, int depth, Visit& visit) {
    const bool curved = from_.curved(s);
    double stray = 0, length = (p1 - p0).norm();
    if (curved) {
      const double r = from_.arc(s).radius_mm;
      stray = piece_sagitta_mm(from_.arc(s), p0, p1);
      length = 2 * r * std::asin(std::min(1.0, length / (2 * r)));
    }
    double bound = chain_bound(p0, n0, p1, n1, stray, length, curved ? &from_.arc(s) : nullptr);
    if (bound <= top_.reach() + precision_mm_ || depth > 40 || (p1 - p0).norm() <= precision_mm_) return;
    if (points_left_-- == 0)
      throw Error(kExitInput, fmt::format("measuring the paths would take more than {} points per segment near "
                                          "X{:.4f} Y{:.4f} Z{:.4f} (an arc far bigger than the band); measure with a "
                                          "larger tolerance",
                                          kPointsPerSegment, p0.x(), p0.y(), p0.z()));
    Vec3 m = curved ? point_on_piece(from_.arc(s), p0, p1, 0.5) : Vec3((p0 + p1) / 2);
    SegmentIndex::Nearest nm = locate(m, n0.segment);
    visit(s, nm, m);
    refine(s, p0, n0, m, nm, depth + 1, visit);
    refine(s, m, nm, p1, n1, depth + 1, visit);
  }

  /// Upper bound of the distance to `to_` along `from`'s path from p0 to p1, which runs
  /// `length_mm` and strays from the chord p0 -> p1 by `stray_mm` at most (a piece of an arc):
  /// pair the chord with the walk along `to_`'s path between their nearest points (both in one
  /// section); the pairing is linear between the walk's vertices, so the largest gap is at
  /// one of them, and where the walk follows an arc's pieces it strays from its chords by no
  /// more than their sagittas. Unpaired: Lipschitz.
  double chain_bound(const Vec3& p0, const SegmentIndex::Nearest& n0, const Vec3& p1,
                     const SegmentIndex::Nearest& n1, double stray_mm, double length_mm,
                     const FlatArc* from_arc = nullptr) const {
    double lipschitz = (n0.distance_mm + n1.distance_mm + length_mm) / 2;
    uint32_t i = n0.segment, j = n1.segment;
    if (to_.section_of[i] != to_.section_of[j]) return lipschitz;
    if (i == j) {
      // Distance to a segment is convex along p0 -> p1; to a piece of an arc it is bounded
      // where both ends face the piece.
      if (!to_.curved(i)) return std::min(std::max(n0.distance_mm, n1.distance_mm) + stray_mm, lipschitz);
      // A piece of an arc about the same centre, in the same plane, facing the piece: every
      // point of it lies as far from it as the radii and heights differ (an arc written back
      // as it was is no distance from itself, however big).
      const FlatArc& to_arc = to_.arc(i);
      if (from_arc && from_arc->plane == to_arc.plane &&
          (project(from_arc->center, to_arc.plane) - project(to_arc.center, to_arc.plane)).norm() <=
              kSameCentreShare * std::max(1.0, to_arc.radius_mm) &&
          in_wedge(to_arc, to_.a(i), to_.b(i), p0) && in_wedge(to_arc, to_.a(i), to_.b(i), p1)) {
        const int normal = axes_of(to_arc.plane).normal;
        const double apart = (project(from_arc->center, to_arc.plane) - project(to_arc.center, to_arc.plane)).norm();
        return std::min(
            std::hypot(from_arc->radius_mm - to_arc.radius_mm, from_arc->center[normal] - to_arc.center[normal]) + apart,
            lipschitz);
      }
      const auto bound = segment_to_piece_bound(to_arc, to_.a(i), to_.b(i), p0, p1);
      return bound ? std::min(*bound + stray_mm, lipschitz) : lipschitz;
    }
    if ((i < j ? j - i : i - j) > kMaxChain) return lipschitz;
    // The walk along `to_` from one nearest point to the other. Where it runs far longer
    // than the stretch it is paired with (it goes round a loop the path retraces, or back
    // and forth), the pairing bounds nothing the Lipschitz bound does not: it stops there,
    // so its cost follows the stretch's own length, never the distance between the two
    // nearest segments' places in the path.
    const double longest = 2 * (length_mm + n0.distance_mm + n1.distance_mm) + precision_mm_;
    walk_.clear();
    walk_.push_back(n0.point);
    double stray = to_.sagitta(j), total = 0;
    for (uint32_t k = i; k != j; k = i < j ? k + 1 : k - 1) {
      walk_.push_back(i < j ? to_.b(k) : to_.a(k));
      stray = std::max(stray, to_.sagitta(k));
      total += (walk_.back() - walk_[walk_.size() - 2]).norm();
      if (total > longest) return lipschitz;
    }
    walk_.push_back(n1.point);
    total += (walk_.back() - walk_[walk_.size() - 2]).norm();
    double run = 0, bound = std::max(n0.distance_mm, n1.distance_mm);
    for (size_t k = 1; k + 1 < walk_.size(); ++k) {
      run += (walk_[k] - walk_[k - 1]).norm();
      double t = total > 0 ? run / total : 0.5;
      bound = std::max(bound, (p0 + t * (p1 - p0) - walk_[k]).norm());
    }
    return std::min(bound + stray + stray_mm, lipschitz);
  }

  static constexpr uint32_t kMaxChain = 4096;
  const Path& from_;
  const Path& to_;
  const SegmentIndex& index_;
  double precision_mm_;
  const TopPlaces& top_;
  mutable std::vector<Vec3> walk_;
  /// The points the splitting may still measure: no input makes it run on. A segment needs
  /// a few dozen where a path meets another at a narrow angle; the base pays for a few
  /// segments that need far more.
  static constexpr size_t kPointsPerSegment = 256, kPointsBase = size_t(1) << 22;
  size_t points_left_ = 0;
};

/// The feed paths' distance both ways, into `d` (see diff_programs()).
void measure_paths(const Program& a, const Interpretation& ia, const Path& pa, const Program& b,
                   const Interpretation& ib, const Path& pb, const DiffOptions& opt, double precision_mm,
                   ProgramDiff& d) {
  // Feed paths, both ways: the maximum, the worst places, and each B move's deviation.
  // Both paths are cut into the same number of contiguous shares, set by their lengths
  // alone; each share measures its part of both directions with its own worst places (its
  // running maximum, which decides which stretches it splits, starts from nothing), and the
  // threads take shares in turn, each keeping its own per-move deviations. The shares'
  // places are merged after: what is measured, and so the result, is the same for any
  // number of threads.
  auto pieces = [](const Path& p) {
    return p.arcs.empty() ? SegmentIndex::NearestOnPiece{}
                          : SegmentIndex::NearestOnPiece([&p](const Vec3& q, uint32_t s) { return p.nearest(s, q); });
  };
  // A path traced again adds nothing: its repeated segments are neither searched nor measured.
  const std::vector<uint32_t> distinct_a = pa.distinct_segments(), distinct_b = pb.distinct_segments();
  auto repeats = [](const Path& p, const std::vector<uint32_t>& distinct) {
    std::vector<bool> r(p.size(), true);
    for (uint32_t s : distinct) r[s] = false;
    return r;
  };
  const std::vector<bool> repeats_a = repeats(pa, distinct_a), repeats_b = repeats(pb, distinct_b);
  SegmentIndex index_a(pa.points, pa.first, pieces(pa), pa.max_sagitta_mm, distinct_a),
      index_b(pb.points, pb.first, pieces(pb), pb.max_sagitta_mm, distinct_b);
  bool spindle_differs = false;
  if (pa.size() > 0 && pb.size() > 0) {
    const size_t share_count = (std::max(pa.size(), pb.size()) + kShareSegments - 1) / kShareSegments;
    const size_t workers = worker_count(opt.threads, share_count);
    std::vector<TopPlaces> shares(share_count, TopPlaces(opt.top, opt.least_mm));
    std::vector<std::vector<double>> deviation_of_b(workers, std::vector<double>(ib.moves.size(), 0.0));
    std::atomic<size_t> next_share{0};
    auto measure = [&](size_t w) {
      for (size_t k; (k = next_share++) < share_count;) {
        TopPlaces& top = shares[k];
        auto note = [&](uint32_t move_a, uint32_t move_b, double dist, const Vec3& at) {
          deviation_of_b[w][move_b] = std::max(deviation_of_b[w][move_b], dist);
          if (dist > top.floor())
            top.offer({dist, at, a.blocks[ia.moves[move_a].block].line, b.blocks[ib.moves[move_b].block].line});
        };
        Directed(pa, pb, index_b, precision_mm, top)
            .run(pa.size() * k / share_count, pa.size() * (k + 1) / share_count, repeats_a,
                 [&](size_t s, const SegmentIndex::Nearest& n, const Vec3& p) {
                   note(pa.move_of[s], pb.move_of[n.segment], n.distance_mm, p);
                 });
        Directed(pb, pa, index_a, precision_mm, top)
            .run(pb.size() * k / share_count, pb.size() * (k + 1) / share_count, repeats_b,
                 [&](size_t s, const SegmentIndex::Nearest& n, const Vec3& p) {
                   note(pa.move_of[n.segment], pb.move_of[s], n.distance_mm, p);
                 });
      }
    };
    run_workers(workers, measure);
    for (size_t k = 1; k < share_count; ++k)
      for (const DiffPlace& p : shares[k].take()) shares[0].offer(p);
    for (const auto& dev : deviation_of_b)
      for (size_t m = 0; m < d.deviation_of_b.size(); ++m) d.deviation_of_b[m] = std::max(d.deviation_of_b[m], dev[m]);
    d.max_deviation_mm = shares[0].max();
    d.worst = shares[0].take();
    auto feed_at = [&](const Move& ma, const Move& mb, const Vec3& at) {
      if (d.extra_axes_compared) {
        const size_t i = size_t(&ma - ia.moves.data()), j = size_t(&mb - ib.moves.data());
        const auto [off, ax] = extra_axes_gap(ia, i, at, extra_axes_at(ib, j, at), kCheckNearShare * opt.tolerance_mm);
        if (off > d.max_extra_axis) {
          d.max_extra_axis = off;
          d.extra_axis = ax;
          d.worst_extra_axis = {off, at, a.blocks[ma.block].line, b.blocks[mb.block].line};
        }
      }
      double pct = 100.0 * std::abs(mb.feed_mm_min - ma.feed_mm_min) / ma.feed_mm_min;
      if (pct > d.max_feed_difference_pct) {
        d.max_feed_difference_pct = pct;
        d.worst_feed = {0, at, a.blocks[ma.block].line, b.blocks[mb.block].line};
      }
      if (ma.spindle != mb.spindle && !spindle_differs) {
        spindle_differs = true;
        d.findings.push_back(fmt::format("S (spindle speed or laser power) differs along the path: A line {} S{}, "
                                         "B line {} S{}",
                                         a.blocks[ma.block].line, ma.spindle, b.blocks[mb.block].line, mb.spindle));
      }
    };
    if (opt.feed) {
      const FeedCompared fc = compare_feed(pa, ia, pb, ib, index_a, opt.tolerance_mm, feed_at);
      d.feed_compared_share = fc.share;
      d.feed_unpaired_mm = fc.unpaired_mm;
      if (fc.unpaired_move != UINT32_MAX) d.feed_unpaired_line_b = b.blocks[ib.moves[fc.unpaired_move].block].line;
    }
  } else if ((pa.size() == 0) != (pb.size() == 0)) {
    d.findings.push_back(fmt::format("only {} has feed moves", pa.size() == 0 ? "B" : "A"));
  }
  // (No feed path in B: nothing of it went uncompared.)
  if (pb.size() == 0) d.feed_compared_share = 1.0;
}

}  // namespace

ProgramDiff diff_programs(const Program& a, const Interpretation& ia, const Program& b, const Interpretation& ib,
                          const DiffOptions& opt) {
  // The measure's searches end at a share of the band: a band that is no positive number,
  // or one far below any machine's resolution, would keep them splitting for ever.
  if (!(opt.tolerance_mm >= kMinToleranceMm && opt.tolerance_mm <= kMaxToleranceMm))
    throw std::invalid_argument(fmt::format("diff tolerance must be from {} to {} mm, got {}", kMinToleranceMm,
                                            kMaxToleranceMm, opt.tolerance_mm));
  if (!opt.measure_path && opt.feed)
    throw std::invalid_argument("diff: the feed is compared along the path measure, which is off");
  ProgramDiff d;
  d.arc_chord_mm = std::max(opt.tolerance_mm * kReadingShare / 2, 1e-7);
  d.extra_axes_compared = extra_axes_move(ia) || extra_axes_move(ib);
  const double precision_mm = opt.tolerance_mm * kReadingShare / 2;
  // (Without the path measure, no segments: what the rest compares is kept without them.)
  Path pa = feed_path(ia, d.arc_chord_mm, opt.tolerance_mm, opt.measure_path),
       pb = feed_path(ib, d.arc_chord_mm, opt.tolerance_mm, opt.measure_path);
  auto summary = [](const Program& p, const Interpretation& in, const Path& path) {
    ProgramSummary s;
    s.unmeasured_arcs = path.rough_arcs;
    if (path.rough_arcs > 0) s.first_unmeasured_line = p.blocks[in.moves[path.first_rough_move].block].line;
    s.far_moves = path.far_moves;
    if (path.far_moves > 0) s.first_far_line = p.blocks[in.moves[path.first_far_move].block].line;
    for (const UnplacedMove& u : in.unplaced) {
      const Move& m = in.moves[u.move];
      const bool entry = enters_from_unknown(m);
      size_t& count = entry ? s.entry_moves : s.unplaced_feed_moves;
      if (count++ > 0) continue;
      std::string why = describe(m.unfit);
      if (u.cause_line > 0 && is_position_unknown(m.unfit)) why += fmt::format(" at line {}", u.cause_line);
      (entry ? s.first_entry_line : s.first_unplaced_line) = p.blocks[m.block].line;
      (entry ? s.entry_reason : s.unplaced_reason) = std::move(why);
    }
    s.blocks = p.blocks.size();
    s.bytes = p.text.size();
    s.feed_moves = path.feed_moves;
    s.rapids = path.rapids.size();
    s.sections = path.section_length_mm.size();
    for (double l : path.section_length_mm) s.path_mm += l;
    return s;
  };
  d.a = summary(a, ia, pa);
  d.b = summary(b, ib, pb);
  // Moves the measure cannot follow, where both programs have exactly the same ones: each
  // lies on its twin, at no distance, so they are compared (a program equals itself,
  // whatever its numbers). Leaving them out of both paths only lengthens other distances.
  if (!pa.unmeasured.empty()) {
    std::sort(pa.unmeasured.begin(), pa.unmeasured.end());
    std::sort(pb.unmeasured.begin(), pb.unmeasured.end());
    if (pa.unmeasured == pb.unmeasured) {
      for (ProgramSummary* sum : {&d.a, &d.b}) {
        sum->identical_unmeasured = sum->unmeasured_arcs + sum->far_moves;
        sum->unmeasured_arcs = sum->far_moves = 0;
      }
      pa.chord_excess_mm = pb.chord_excess_mm = 0;
    }
  }
  // Both paths' chords may lie that much off their arcs: a distance read that much short.
  d.chord_excess_mm = 2 * std::max(pa.chord_excess_mm, pb.chord_excess_mm);
  d.arc_chord_mm += d.chord_excess_mm;
  if (opt.measure_path) {
    d.deviation_of_b.assign(ib.moves.size(), 0.0);
    measure_paths(a, ia, pa, b, ib, pb, opt, precision_mm, d);
  } else if ((pa.feed_moves == 0) != (pb.feed_moves == 0)) {
    d.findings.push_back(fmt::format("only {} has feed moves", pa.feed_moves == 0 ? "B" : "A"));
  }
  if (d.worst.size() > opt.top) d.worst.resize(opt.top);


  if (d.a.sections != d.b.sections)
    d.findings.push_back(fmt::format("cutting sections between rapids: {} in A, {} in B", d.a.sections, d.b.sections));

  // Rapids, and feed moves from an unknown position: end points in order (the extra axes
  // with them).
  auto end_points = [&](const std::vector<uint32_t>& in_a, const std::vector<uint32_t>& in_b, const char* what,
                        double& max_mm, DiffPlace& worst) {
    if (in_a.size() != in_b.size()) d.findings.push_back(fmt::format("{}: {} in A, {} in B", what, in_a.size(), in_b.size()));
    for (size_t k = 0; k < std::min(in_a.size(), in_b.size()); ++k) {
      const Move& ma = ia.moves[in_a[k]];
      const Move& mb = ib.moves[in_b[k]];
      double dist = (xyz(ma.to) - xyz(mb.to)).norm();
      if (dist > max_mm) {
        max_mm = dist;
        worst = {dist, xyz(ma.to), a.blocks[ma.block].line, b.blocks[mb.block].line};
      }
      if (const auto [off, ax] = extra_axes_apart(ma.to, mb.to); d.extra_axes_compared && off > d.max_extra_axis) {
        d.max_extra_axis = off;
        d.extra_axis = ax;
        d.worst_extra_axis = {off, xyz(ma.to), a.blocks[ma.block].line, b.blocks[mb.block].line};
      }
    }
  };
  end_points(pa.rapids, pb.rapids, "rapid moves", d.max_rapid_mm, d.worst_rapid);
  end_points(pa.entries, pb.entries, "feed moves from an unknown position", d.max_entry_mm, d.worst_entry);

  // Extrusion per section.
  constexpr double kExtrusionMm = 1e-4;  // E printed with 5 decimals: sums agree far closer
  bool extrusion_differs = false;
  for (size_t k = 0; k < std::min(pa.section_e.size(), pb.section_e.size()); ++k) {
    double ea = pa.section_e[k], eb = pb.section_e[k];
    d.max_extrusion_difference_mm = std::max(d.max_extrusion_difference_mm, std::abs(ea - eb));
    extrusion_differs = extrusion_differs || std::abs(ea - eb) > kExtrusionMm + pa.section_e_rounding_mm[k] +
                                                                    pb.section_e_rounding_mm[k];
    double la = pa.section_length_mm[k], lb = pb.section_length_mm[k];
    if (la > 0 && lb > 0 && std::abs(ea) > 0)
      d.max_extrusion_per_mm_difference_pct =
          std::max(d.max_extrusion_per_mm_difference_pct, 100.0 * std::abs(eb / lb - ea / la) / std::abs(ea / la));
  }
  if (extrusion_differs)
    d.findings.push_back(fmt::format("extrusion per section differs by up to {:.5f} mm of E", d.max_extrusion_difference_mm));
  constexpr double kFeedPct = 0.01;
  if (d.max_feed_difference_pct > kFeedPct)
    d.findings.push_back(fmt::format("feed differs by up to {:.3f} % (A line {}, B line {})", d.max_feed_difference_pct,
                                     d.worst_feed.line_a, d.worst_feed.line_b));

  // Everything that is not geometry, in order.
  NonMotionBlocks na(a, ia, opt.comments), nb(b, ib, opt.comments);
  d.comments_compared = opt.comments;
  bool first = true;
  bool more_a = na.next(), more_b = nb.next();
  for (; more_a && more_b; more_a = na.next(), more_b = nb.next()) {
    if (na.same_key(nb)) continue;
    ++d.non_motion_differences;
    if (first)
      d.findings.push_back(fmt::format("non-motion block differs: A line {} '{}', B line {} '{}'", na.line(),
                                       na.key(), nb.line(), nb.key()));
    first = false;
  }
  while (more_a) more_a = na.next();
  while (more_b) more_b = nb.next();
  d.a.non_motion = na.count();
  d.b.non_motion = nb.count();
  if (na.count() != nb.count()) {
    d.non_motion_differences += std::max(na.count(), nb.count()) - std::min(na.count(), nb.count());
    d.findings.push_back(fmt::format("non-motion blocks (M, T, S, dwell{}): {} in A, {} in B",
                                     opt.comments ? ", comments" : "", na.count(), nb.count()));
  }
  // The blocks A's jumps enter (JumpTargets), in order: each must be a block of B, with its
  // number or label, or the jump finds another place, or none.
  if (a.jumps) {
    struct Entered {
      uint64_t key;
      uint32_t line;
      std::string_view name;  // `N100`, `LOOP1:`
    };
    auto entered = [&](const Program& p) {
      std::vector<Entered> out;
      for (const Block& blk : p.blocks)
        for (const Word* w = p.words_begin(blk); w != p.words_end(blk) && (w->letter == 'N' || w->letter == kLabelLetter); ++w)
          if (const auto key = w->target_key(); key && a.jumps->enters(*key)) out.push_back({*key, blk.line, p.raw(blk, *w)});
      return out;
    };
    const auto ea = entered(a), eb = entered(b);
    for (size_t k = 0; k < std::max(ea.size(), eb.size()); ++k) {
      if (k < ea.size() && k < eb.size() && ea[k].key == eb[k].key) continue;
      d.findings.push_back(k < ea.size()
                               ? fmt::format("block {} (A line {}), which a jump enters, is not in B{}", ea[k].name,
                                             ea[k].line,
                                             k < eb.size() ? fmt::format(" (B line {} is {})", eb[k].line, eb[k].name)
                                                           : std::string())
                               : fmt::format("B line {} is a block {}, which a jump of A enters, where A has none",
                                             eb[k].line, eb[k].name));
      break;
    }
  }
  return d;
}

}  // namespace arcpress
