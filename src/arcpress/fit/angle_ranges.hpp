// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Ranges of directions as angles, and the union of them a breadth-first search keeps per
// vertex: the G1 lower bound's (count_bound.cpp) and the range search's (range_search.cpp).
#include <algorithm>
#include <cmath>
#include <vector>

#include "arcpress/core/geometry.hpp"

namespace arcpress {

/// Directions from `lo` to `hi` (rad, lo <= hi; an empty range has lo > hi).
struct AngleRange {
  double lo, hi;
};

/// The angle `a` (rad) moved by whole turns into (ref - π, ref + π].
inline double near_angle(double a, double ref) { return ref + std::remainder(a - ref, 2 * kPi); }

/// `ranges` sorted, overlapping ones merged.
inline std::vector<AngleRange> merged(std::vector<AngleRange> ranges) {
  std::sort(ranges.begin(), ranges.end(), [](const AngleRange& x, const AngleRange& y) { return x.lo < y.lo; });
  std::vector<AngleRange> out;
  for (const AngleRange& r : ranges)
    if (!out.empty() && r.lo <= out.back().hi) out.back().hi = std::max(out.back().hi, r.hi);
    else out.push_back(r);
  return out;
}

/// `ranges` less `taken` (sorted and disjoint), the pieces left in order; they are added to
/// `taken`.
inline std::vector<AngleRange> take_new(std::vector<AngleRange> ranges, std::vector<AngleRange>& taken) {
  std::vector<AngleRange> fresh;
  for (AngleRange r : merged(std::move(ranges))) {
    for (const AngleRange& t : taken) {
      if (t.hi <= r.lo || t.lo >= r.hi) continue;
      if (t.lo > r.lo) fresh.push_back({r.lo, t.lo});
      r.lo = std::max(r.lo, t.hi);
      if (r.lo >= r.hi) break;
    }
    if (r.lo < r.hi) fresh.push_back(r);
  }
  taken.insert(taken.end(), fresh.begin(), fresh.end());
  taken = merged(std::move(taken));
  return fresh;
}

}  // namespace arcpress
