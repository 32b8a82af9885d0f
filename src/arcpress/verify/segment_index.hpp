// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Nearest-segment queries over a path: a linear scan over boxes of consecutive segments for
// the first queries, then CGAL's AABB tree over 3D segments once the scans have cost what
// building it would, behind a small interface so the CGAL headers are compiled in one
// place. A segment may stand for a curved piece (an arc's) that lies within a known
// distance of it: the scans and the tree find the candidates by their chords, and the
// piece's own distance decides.
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "arcpress/core/geometry.hpp"

namespace arcpress {

class SegmentIndex {
 public:
  struct Nearest {
    double distance_mm = 0;
    uint32_t segment = 0;  ///< index into the segments given to the constructor
    Vec3 point{0, 0, 0};   ///< the closest point on that segment
  };

  /// Segment i runs from points[first[i]] to points[first[i] + 1] (polylines share their
  /// points). Zero-length segments are kept as points. The index reads both vectors where
  /// they lie (it keeps no copy), so they must outlive it, unchanged.
  SegmentIndex(const std::vector<Vec3>& points, const std::vector<uint32_t>& first);
  /// The point of piece i nearest p, exactly.
  using NearestOnPiece = std::function<Vec3(const Vec3& p, uint32_t i)>;
  /// As above, where the segments stand for pieces (of arcs): `on_piece` measures them, and
  /// none lies farther than `slack_mm` (mm) from its segment. Empty `on_piece`: segments.
  SegmentIndex(const std::vector<Vec3>& points, const std::vector<uint32_t>& first, NearestOnPiece on_piece,
               double slack_mm);
  /// As above, where only the segments `distinct` (ascending) need be searched: each other
  /// one repeats an earlier one exactly (a path traced again), so it is never nearer and, of
  /// ties, never the lowest-numbered. A path traced n times then costs each query as one
  /// trace does, not n times that.
  SegmentIndex(const std::vector<Vec3>& points, const std::vector<uint32_t>& first, NearestOnPiece on_piece,
               double slack_mm, std::vector<uint32_t> distinct);
  ~SegmentIndex();
  SegmentIndex(const SegmentIndex&) = delete;
  SegmentIndex& operator=(const SegmentIndex&) = delete;

  bool empty() const;
  /// The nearest segment (or piece) to p. The search starts from segment `hint`'s distance,
  /// so it is fast when the hint is near p (e.g. the answer of the previous query along a
  /// path). Of several as near, the lowest-numbered: the answer is the same whatever came
  /// before. Safe to call from several threads at once.
  Nearest nearest(const Vec3& p, uint32_t hint) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace arcpress
