// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/verify/segment_index.hpp"

#include <CGAL/AABB_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Simple_cartesian.h>

#include <boost/iterator/counting_iterator.hpp>
#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>

#include "arcpress/core/deviation.hpp"

namespace arcpress {

namespace {
using K = CGAL::Simple_cartesian<double>;
using Point = K::Point_3;
using Segment = K::Segment_3;

/// Zero-length segments are stretched by this much so the tree's projections stay defined;
/// far below any tolerance a user can give (a length epsilon, not a tolerance).
constexpr double kPointAsSegmentMm = 1e-9;

Vec3 vec(const Point& p) { return {p.x(), p.y(), p.z()}; }
Point point(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

/// The caller's points and where each segment starts among them.
struct Polylines {
  const std::vector<Vec3>* points = nullptr;
  const std::vector<uint32_t>* first = nullptr;
  const Vec3& a(uint32_t i) const { return (*points)[(*first)[i]]; }
  const Vec3& b(uint32_t i) const { return (*points)[(*first)[i] + 1]; }
};

/// A readable property map from a segment number to what `Read` makes of it, read when the
/// tree asks: the tree holds only segment numbers, so the points are stored once, by the caller.
template <class Value, class Read>
struct NumberMap {
  using key_type = uint32_t;
  using value_type = Value;
  using reference = Value;
  using category = boost::readable_property_map_tag;
  Polylines lines;
  friend Value get(const NumberMap& m, uint32_t i) { return Read{}(m.lines, i); }
};
/// Segment i (a zero-length one a little longer, as a point).
struct SegmentOf {
  Segment operator()(const Polylines& l, uint32_t i) const {
    const Vec3 &a = l.a(i), &b = l.b(i);
    return {point(a), point((b - a).norm() < kPointAsSegmentMm ? Vec3(a + Vec3(kPointAsSegmentMm, 0, 0)) : b)};
  }
};
/// Segment i's start, the point the tree reads off each primitive.
struct StartOf {
  Point operator()(const Polylines& l, uint32_t i) const { return point(l.a(i)); }
};
using SegmentMap = NumberMap<Segment, SegmentOf>;
using StartMap = NumberMap<Point, StartOf>;
using Primitive = CGAL::AABB_primitive<uint32_t, SegmentMap, StartMap, CGAL::Tag_true, CGAL::Tag_false>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

/// Two distances to segments that differ by less than this (relative to 1 mm and to their
/// size) may be the same distance computed two ways: a floating-point epsilon, not a tolerance.
constexpr double kSameDistanceMm = 1e-12;
/// Consecutive segments a linear scan takes together, behind their common bounding box, and
/// consecutive such chunks behind theirs.
constexpr uint32_t kChunkSegments = 32;
constexpr uint32_t kGroupChunks = 32;
/// Boxes the linear scans visit and segments they measure, per segment of the path, before
/// the tree pays for itself: building it costs about as much as this many per segment.
constexpr uint64_t kScanBudgetPerSegment = 64;

struct Box {
  Vec3 lo, hi;
  double squared_distance(const Vec3& p) const {
    const Vec3 d = (lo - p).cwiseMax(p - hi).cwiseMax(Vec3::Zero());
    return d.squaredNorm();
  }
};
}  // namespace

/// Queries go first to a linear scan over boxes of consecutive segments, in two levels
/// (built in one pass: a path's segments follow each other, so the boxes are tight), and to
/// CGAL's tree once the scans have done as much work as building it would: a self-check
/// whose walks along the path find almost every nearest point asks the index a few dozen
/// times, and a tree over hundreds of thousands of segments would take most of its time.
struct SegmentIndex::Impl {
  Polylines lines;
  uint32_t count = 0;
  NearestOnPiece on_piece;  ///< empty: the segments are the path
  double slack_mm = 0;
  std::vector<Box> chunks;  ///< kChunkSegments segments each
  std::vector<Box> groups;  ///< kGroupChunks chunks each
  std::vector<uint32_t> distinct;  ///< the segments the tree holds; empty: all
  std::atomic<uint64_t> scanned{0};  ///< boxes the linear scans have visited, and segments measured
  std::once_flag built;
  std::atomic<bool> tree_ready{false};
  Tree tree;
  Segment segment(uint32_t i) const { return get(SegmentMap{lines}, i); }
  /// The point of segment i (or of the piece it stands for) nearest to p.
  Vec3 nearest_point(const Vec3& p, uint32_t i) const {
    return on_piece ? on_piece(p, i) : nearest_on_segment(p, lines.a(i), lines.b(i));
  }

  /// Whether queries go to the tree now (building it, once, when the scans reach the budget).
  bool use_tree() {
    if (tree_ready.load(std::memory_order_acquire)) return true;
    if (scanned.load(std::memory_order_relaxed) < kScanBudgetPerSegment * count) return false;
    std::call_once(built, [&] {
      if (distinct.empty())
        tree.insert(boost::counting_iterator<uint32_t>(0), boost::counting_iterator<uint32_t>(count), SegmentMap{lines},
                    StartMap{lines});
      else
        tree.insert(distinct.begin(), distinct.end(), SegmentMap{lines}, StartMap{lines});
      tree.build();
      tree_ready.store(true, std::memory_order_release);
    });
    return true;
  }

  /// The segments that cross the cube of half-side `half_mm` (mm) about p, from the tree
  /// (a buffer of the calling thread's, valid until its next call).
  const std::vector<uint32_t>& in_box(const Vec3& p, double half_mm) const {
    const Vec3 h(half_mm, half_mm, half_mm);
    thread_local std::vector<uint32_t> near;
    near.clear();
    tree.all_intersected_primitives(K::Iso_cuboid_3(point(p - h), point(p + h)), std::back_inserter(near));
    return near;
  }

  /// Calls visit(i, nearest point, distance) for every segment within `reach_mm` (mm) of p,
  /// by a scan over the chunks; `visit` may narrow the reach as it goes (below 0: no further).
  template <class Visit>
  void scan(const Vec3& p, const double& reach_mm, Visit&& visit) {
    uint64_t boxes = groups.size();
    for (uint32_t g = 0; g < groups.size() && reach_mm >= 0; ++g) {
      if (groups[g].squared_distance(p) > reach_mm * reach_mm) continue;
      const uint32_t last_chunk = std::min<uint32_t>(uint32_t(chunks.size()), (g + 1) * kGroupChunks);
      for (uint32_t c = g * kGroupChunks; c < last_chunk && reach_mm >= 0; ++c) {
        ++boxes;
        if (chunks[c].squared_distance(p) > reach_mm * reach_mm) continue;
        const uint32_t end = std::min(count, (c + 1) * kChunkSegments);
        boxes += end - c * kChunkSegments;  // (each segment measured costs as much as a box)
        for (uint32_t i = c * kChunkSegments; i < end && reach_mm >= 0; ++i) {
          const Vec3 q = nearest_on_segment(p, lines.a(i), lines.b(i));
          const double dist = (q - p).norm();
          if (dist <= reach_mm) visit(i, q, dist);
        }
      }
    }
    scanned.fetch_add(boxes, std::memory_order_relaxed);
  }
};

SegmentIndex::SegmentIndex(const std::vector<Vec3>& points, const std::vector<uint32_t>& first)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.lines = Polylines{&points, &first};
  m.count = uint32_t(first.size());
  for (uint32_t i = 0; i < m.count; ++i) {
    if (i % kChunkSegments == 0) m.chunks.push_back({m.lines.a(i), m.lines.a(i)});
    Box& box = m.chunks.back();
    for (const Vec3& v : {m.lines.a(i), m.lines.b(i)}) {
      box.lo = box.lo.cwiseMin(v);
      box.hi = box.hi.cwiseMax(v);
    }
  }
  for (uint32_t c = 0; c < m.chunks.size(); ++c) {
    if (c % kGroupChunks == 0) m.groups.push_back(m.chunks[c]);
    m.groups.back().lo = m.groups.back().lo.cwiseMin(m.chunks[c].lo);
    m.groups.back().hi = m.groups.back().hi.cwiseMax(m.chunks[c].hi);
  }
}

SegmentIndex::SegmentIndex(const std::vector<Vec3>& points, const std::vector<uint32_t>& first,
                           NearestOnPiece on_piece, double slack_mm)
    : SegmentIndex(points, first) {
  impl_->on_piece = std::move(on_piece);
  impl_->slack_mm = slack_mm;
}

SegmentIndex::SegmentIndex(const std::vector<Vec3>& points, const std::vector<uint32_t>& first,
                           NearestOnPiece on_piece, double slack_mm, std::vector<uint32_t> distinct)
    : SegmentIndex(points, first, std::move(on_piece), slack_mm) {
  if (distinct.size() < impl_->count) impl_->distinct = std::move(distinct);
}

SegmentIndex::~SegmentIndex() = default;

bool SegmentIndex::empty() const { return impl_->count == 0; }

SegmentIndex::Nearest SegmentIndex::nearest(const Vec3& p, uint32_t hint) const {
  Nearest n;
  if (empty()) return n;
  Impl& m = *impl_;
  // Every candidate is measured by the same function and the nearest kept, ties to the lower
  // index, whether the scans or the tree find the candidates: the answer does not depend on
  // how many queries came before, nor on which thread asked them.
  auto keep = [&](uint32_t i, const Vec3& q, double dist) {
    if (dist < n.distance_mm || (dist == n.distance_mm && i < n.segment)) n = {dist, i, q};
  };
  auto offer = [&](uint32_t i) {
    const Vec3 q = m.nearest_point(p, i);
    keep(i, q, (q - p).norm());
  };
  // A piece lies within the slack of its chord: every piece that could beat the nearest so far
  // has its chord within that distance and the slack.
  auto reach = [&] { return n.distance_mm + m.slack_mm; };
  n.distance_mm = HUGE_VAL;
  const uint32_t h = std::min(hint, m.count - 1);
  offer(h);  // the hint's distance bounds the search from the start
  if (!m.use_tree()) {
    double until = reach();
    m.scan(p, until, [&](uint32_t i, const Vec3& q, double dist) {
      // (The scan measured the segment itself already; a piece is measured here.)
      if (m.on_piece) {
        offer(i);
      } else {
        keep(i, q, dist);
      }
      until = reach();
    });
    return n;
  }
  // The nearest chord, then every chord within the slack of the nearest so far (for
  // segments, within rounding of it: those that tie).
  const Segment hs = m.segment(h);
  const Vec3 on = nearest_on_segment(p, vec(hs.source()), vec(hs.target()));
  const uint32_t id = m.tree.closest_point_and_primitive(point(p), std::make_pair(point(on), h)).second;
  offer(id);
  for (uint32_t i : m.in_box(p, reach() + kSameDistanceMm * (1 + n.distance_mm))) offer(i);
  return n;
}

}  // namespace arcpress
