#include "arcpress/verify/segment_index.hpp"

#include <CGAL/AABB_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Simple_cartesian.h>

#include <boost/iterator/counting_iterator.hpp>
#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <cmath>

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
}  // namespace

struct SegmentIndex::Impl {
  Polylines lines;
  uint32_t count = 0;
  NearestOnPiece on_piece;  ///< empty: the segments are the path
  double slack_mm = 0;
  Tree tree;  ///< built by build() or at the first query: a caller that never needs it pays nothing
  Segment segment(uint32_t i) const { return get(SegmentMap{lines}, i); }
};

SegmentIndex::SegmentIndex(const std::vector<Vec3>& points, const std::vector<uint32_t>& first)
    : impl_(std::make_unique<Impl>()) {
  impl_->lines = Polylines{&points, &first};
  impl_->count = uint32_t(first.size());
  if (impl_->count > 0)
    impl_->tree.insert(boost::counting_iterator<uint32_t>(0), boost::counting_iterator<uint32_t>(impl_->count),
                       SegmentMap{impl_->lines}, StartMap{impl_->lines});
}

SegmentIndex::SegmentIndex(const std::vector<Vec3>& points, const std::vector<uint32_t>& first,
                           NearestOnPiece on_piece, double slack_mm)
    : SegmentIndex(points, first) {
  impl_->on_piece = std::move(on_piece);
  impl_->slack_mm = slack_mm;
}

SegmentIndex::~SegmentIndex() = default;

bool SegmentIndex::empty() const { return impl_->count == 0; }

void SegmentIndex::build() const {
  if (!empty()) impl_->tree.build();
}

SegmentIndex::Nearest SegmentIndex::nearest(const Vec3& p, uint32_t hint) const {
  Nearest n;
  if (empty()) return n;
  // The hint's own nearest point bounds the search radius from the start.
  const uint32_t h = std::min(hint, impl_->count - 1);
  const Segment hs = impl_->segment(h);
  const Vec3 on = nearest_on_segment(p, vec(hs.source()), vec(hs.target()));
  auto [cp, id] = impl_->tree.closest_point_and_primitive(point(p), std::make_pair(point(on), h));
  n.segment = id;
  n.point = vec(cp);
  n.distance_mm = (n.point - p).norm();
  if (!impl_->on_piece) return n;
  // Pieces: the nearest chord's piece, then every piece whose chord comes within the slack
  // of beating it (a piece lies within the slack of its chord), each measured itself.
  auto offer = [&](uint32_t i) {
    const Vec3 q = impl_->on_piece(p, i);
    const double dist = (q - p).norm();
    if (dist < n.distance_mm || (dist == n.distance_mm && i < n.segment)) n = {dist, i, q};
  };
  n.distance_mm = HUGE_VAL;
  offer(id);
  offer(h);
  const double reach = n.distance_mm + impl_->slack_mm;
  const K::Iso_cuboid_3 box(point(p - Vec3(reach, reach, reach)), point(p + Vec3(reach, reach, reach)));
  thread_local std::vector<uint32_t> near;
  near.clear();
  impl_->tree.all_intersected_primitives(box, std::back_inserter(near));
  for (uint32_t i : near) offer(i);
  return n;
}

}  // namespace arcpress
