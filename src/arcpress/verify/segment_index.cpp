#include "arcpress/verify/segment_index.hpp"

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>

namespace arcpress {

namespace {
using K = CGAL::Simple_cartesian<double>;
using Point = K::Point_3;
using Segment = K::Segment_3;
using Iterator = std::vector<Segment>::const_iterator;
using Primitive = CGAL::AABB_segment_primitive<K, Iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

/// Zero-length segments are stretched by this much so the tree's projections stay defined;
/// far below any tolerance a user can give (a length epsilon, not a tolerance).
constexpr double kPointAsSegmentMm = 1e-9;

Vec3 vec(const Point& p) { return {p.x(), p.y(), p.z()}; }
Point point(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
}  // namespace

struct SegmentIndex::Impl {
  std::vector<Segment> segments;
  Tree tree;  ///< built by build() or at the first query: a caller that never needs it pays nothing
};

SegmentIndex::SegmentIndex(const std::vector<Vec3>& ends) : impl_(std::make_unique<Impl>()) {
  impl_->segments.reserve(ends.size() / 2);
  for (size_t i = 0; i + 1 < ends.size(); i += 2) {
    Vec3 a = ends[i], b = ends[i + 1];
    if ((b - a).norm() < kPointAsSegmentMm) b = a + Vec3(kPointAsSegmentMm, 0, 0);
    impl_->segments.emplace_back(point(a), point(b));
  }
  if (!impl_->segments.empty()) impl_->tree.insert(impl_->segments.cbegin(), impl_->segments.cend());
}

SegmentIndex::~SegmentIndex() = default;

bool SegmentIndex::empty() const { return impl_->segments.empty(); }

void SegmentIndex::build() const {
  if (!empty()) impl_->tree.build();
}

SegmentIndex::Nearest SegmentIndex::nearest(const Vec3& p, uint32_t hint) const {
  Nearest n;
  if (empty()) return n;
  // The hint's own nearest point bounds the search radius from the start.
  Iterator it = impl_->segments.cbegin() + std::min<size_t>(hint, impl_->segments.size() - 1);
  Vec3 a = vec(it->source()), d = vec(it->target()) - a;
  Vec3 on = a + std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) * d;
  auto [cp, id] = impl_->tree.closest_point_and_primitive(point(p), std::make_pair(point(on), it));
  n.segment = uint32_t(id - impl_->segments.cbegin());
  n.point = vec(cp);
  n.distance_mm = (n.point - p).norm();
  return n;
}

}  // namespace arcpress
