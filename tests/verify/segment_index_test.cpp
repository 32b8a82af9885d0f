// SPDX-License-Identifier: GPL-3.0-or-later
// The nearest-segment index the diff asks when a walk along the other path cannot find the
// nearest point: its answers are the nearest of all segments (or pieces), whatever the hint,
// and whether any lies within a distance, whether its linear scans answer or, after enough
// queries, its tree, and from two threads.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <thread>

#include "arcpress/core/deviation.hpp"
#include "arcpress/verify/segment_index.hpp"

using namespace arcpress;

namespace {

/// A path of `count` segments: a random walk of steps up to 2 mm, with a jump of up to
/// 40 mm every 50 segments (travel between islands), in a few layers 0.2 mm apart.
struct Walk {
  std::vector<Vec3> points;
  std::vector<uint32_t> first;
};
Walk random_walk(std::mt19937& rng, uint32_t count) {
  std::uniform_real_distribution<double> step(-2, 2), jump(-40, 40);
  Walk w;
  Vec3 p(0, 0, 0);
  w.points.push_back(p);
  for (uint32_t i = 0; i < count; ++i) {
    if (i % 50 == 49) {
      p += Vec3(jump(rng), jump(rng), 0);
      w.points.push_back(p);  // a new polyline starts here: no segment across the jump
    }
    if (i % 400 == 399) p.z() += 0.2;
    p += Vec3(step(rng), step(rng), 0);
    w.first.push_back(uint32_t(w.points.size() - 1));
    w.points.push_back(p);
  }
  return w;
}

/// Piece i bulges off its chord at the middle by `bulge` (mm, along y): two segments.
Vec3 nearest_on_piece(const Walk& w, uint32_t i, double bulge, const Vec3& p) {
  const Vec3 &a = w.points[w.first[i]], &b = w.points[w.first[i] + 1];
  const Vec3 m = 0.5 * (a + b) + Vec3(0, bulge, 0);
  const Vec3 q1 = nearest_on_segment(p, a, m), q2 = nearest_on_segment(p, m, b);
  return (q1 - p).norm() <= (q2 - p).norm() ? q1 : q2;
}

}  // namespace

TEST_CASE("the index answers with the nearest segment of all, from any hint, and whether one lies within a distance, before and after it builds its tree") {
  std::mt19937 rng(7);
  const Walk w = random_walk(rng, 600);
  SegmentIndex index(w.points, w.first);
  std::uniform_real_distribution<double> coord(-60, 60), height(-1, 2);
  std::uniform_int_distribution<uint32_t> any(0, 599);
  // 600 segments in 19 boxes: the scans reach the tree's budget (64 boxes a segment) after
  // about 2 000 queries, so these 6 000 ask both.
  size_t wrong = 0;
  for (int k = 0; k < 6000; ++k) {
    const Vec3 p(coord(rng), coord(rng), height(rng));
    double best = HUGE_VAL;
    for (uint32_t i = 0; i < w.first.size(); ++i)
      best = std::min(best, (nearest_on_segment(p, w.points[w.first[i]], w.points[w.first[i] + 1]) - p).norm());
    const SegmentIndex::Nearest n = index.nearest(p, any(rng));
    const Vec3 on = nearest_on_segment(p, w.points[w.first[n.segment]], w.points[w.first[n.segment] + 1]);
    const bool right = std::abs(n.distance_mm - best) <= 1e-9 && (n.point - on).norm() <= 1e-9 &&
                       std::abs((n.point - p).norm() - n.distance_mm) <= 1e-9;
    if (!right) ++wrong;
  }
  CHECK(wrong == 0);
}

TEST_CASE("the index measures pieces that bulge off their chords, and may be asked from two threads at once") {
  std::mt19937 rng(11);
  const Walk w = random_walk(rng, 500);
  const double bulge = 0.3;
  SegmentIndex index(
      w.points, w.first, [&](const Vec3& p, uint32_t i) { return nearest_on_piece(w, i, bulge, p); }, bulge);
  std::vector<Vec3> queries;
  std::uniform_real_distribution<double> coord(-60, 60), height(-1, 2);
  for (int k = 0; k < 6000; ++k) queries.emplace_back(coord(rng), coord(rng), height(rng));
  std::vector<size_t> wrong(2, 0);
  auto ask = [&](size_t t) {
    for (size_t k = t; k < queries.size(); k += 2) {
      const Vec3& p = queries[k];
      double best = HUGE_VAL;
      for (uint32_t i = 0; i < w.first.size(); ++i) best = std::min(best, (nearest_on_piece(w, i, bulge, p) - p).norm());
      const SegmentIndex::Nearest n = index.nearest(p, uint32_t(k % w.first.size()));
      const Vec3 on = nearest_on_piece(w, n.segment, bulge, p);
      if (std::abs(n.distance_mm - best) > 1e-9 || (n.point - on).norm() > 1e-9) ++wrong[t];
    }
  };
  std::thread other(ask, 1);
  ask(0);
  other.join();
  CHECK(wrong[0] == 0);
  CHECK(wrong[1] == 0);
}
