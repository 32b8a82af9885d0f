#include "arcpress/verify/segment_index.hpp"

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Simple_cartesian.h>

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
}  // namespace

struct SegmentIndex::Impl {
  std::vector<Segment> segments;
  Tree tree;
};

SegmentIndex::SegmentIndex(const std::vector<Vec3>& ends) : impl_(std::make_unique<Impl>()) {
  impl_->segments.reserve(ends.size() / 2);
  for (size_t i = 0; i + 1 < ends.size(); i += 2) {
    Vec3 a = ends[i], b = ends[i + 1];
    if ((b - a).norm() < kPointAsSegmentMm) b = a + Vec3(kPointAsSegmentMm, 0, 0);
    impl_->segments.emplace_back(Point(a.x(), a.y(), a.z()), Point(b.x(), b.y(), b.z()));
  }
  if (!impl_->segments.empty()) {
    impl_->tree.insert(impl_->segments.cbegin(), impl_->segments.cend());
    impl_->tree.build();
    impl_->tree.accelerate_distance_queries();
  }
}

SegmentIndex::~SegmentIndex() = default;

bool SegmentIndex::empty() const { return impl_->segments.empty(); }

SegmentIndex::Nearest SegmentIndex::nearest(const Vec3& p) const {
  Nearest n;
  if (empty()) return n;
  Point q(p.x(), p.y(), p.z());
  auto [cp, id] = impl_->tree.closest_point_and_primitive(q);
  n.segment = uint32_t(id - impl_->segments.cbegin());
  n.point = Vec3(cp.x(), cp.y(), cp.z());
  n.distance_mm = (n.point - p).norm();
  return n;
}

}  // namespace arcpress
