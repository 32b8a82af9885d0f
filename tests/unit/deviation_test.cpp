// SPDX-License-Identifier: GPL-3.0-or-later
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "arcpress/core/deviation.hpp"

using namespace arcpress;

namespace {

/// Seeded numbers in [lo, hi].
struct Seeded {
  uint64_t state;
  double operator()(double lo, double hi) {
    state ^= state << 13, state ^= state >> 7, state ^= state << 17;
    return lo + (hi - lo) * double(state % 1000001) / 1000000.0;
  }
};

/// Points along `arc` at `count` + 1 shares of its sweep, each pushed off it in the plane by
/// up to `noise_mm`, and along the normal too unless `in_plane`; the ends stay exactly on it.
std::vector<Vec3> along(const ArcGeom& arc, int count, double noise_mm, bool in_plane, Seeded& rnd) {
  std::vector<Vec3> pts;
  for (int k = 0; k <= count; ++k) {
    Vec3 p = arc.point_at(double(k) / count);
    if (k > 0 && k < count) {
      const double dx = rnd(-noise_mm, noise_mm), dy = rnd(-noise_mm, noise_mm);
      p += Vec3(dx, dy, in_plane ? 0.0 : rnd(-noise_mm, noise_mm));
    }
    pts.push_back(p);
  }
  return pts;
}

/// The largest distance from `samples` points spread along `arc` to the polyline `pts`
/// (each to its nearest segment): what the measure must reach at least.
double sampled_arc_to_polyline(const ArcGeom& arc, const std::vector<Vec3>& pts, int samples) {
  double worst = 0;
  for (int k = 0; k <= samples; ++k) {
    const Vec3 a = arc.point_at(double(k) / samples);
    double nearest = HUGE_VAL;
    for (size_t m = 0; m + 1 < pts.size(); ++m)
      nearest = std::min(nearest, point_segment_distance(a, pts[m], pts[m + 1]));
    worst = std::max(worst, nearest);
  }
  return worst;
}

/// The largest distance from points spread along the polyline `pts` to `arc` (each to the
/// arc's nearest of `samples` points, refined by golden sections between its neighbours).
double sampled_polyline_to_arc(const ArcGeom& arc, const std::vector<Vec3>& pts, int samples) {
  std::vector<Vec3> on_arc;
  for (int k = 0; k <= samples; ++k) on_arc.push_back(arc.point_at(double(k) / samples));
  double worst = 0;
  for (size_t m = 0; m + 1 < pts.size(); ++m)
    for (int j = 0; j <= 12; ++j) {
      const Vec3 x = pts[m] + (pts[m + 1] - pts[m]) * (j / 12.0);
      int best = 0;
      for (int k = 1; k <= samples; ++k)
        if ((on_arc[k] - x).squaredNorm() < (on_arc[best] - x).squaredNorm()) best = k;
      double lo = std::max(0, best - 1) / double(samples), hi = std::min(samples, best + 1) / double(samples);
      for (int it = 0; it < 40; ++it) {
        const double a = lo + (hi - lo) * 0.382, b = lo + (hi - lo) * 0.618;
        if ((arc.point_at(a) - x).norm() < (arc.point_at(b) - x).norm()) hi = b; else lo = a;
      }
      worst = std::max(worst, std::min((arc.point_at(lo) - x).norm(), (on_arc[best] - x).norm()));
    }
  return worst;
}

/// A seeded arc and a polyline along it: flat arcs with the input in their plane or off it,
/// and helices; sweeps from a few degrees to almost a turn, radii from 0.5 to 50 mm, in 1 to
/// 61 moves, the input up to 0.02 mm off the arc. Every fourth case is almost a turn in one
/// or two moves, where the arc runs round the back of the input, which only the measure of
/// the arc's pieces, not that of the input's vertices and moves, sees.
struct Case {
  ArcGeom arc;
  std::vector<Vec3> pts;
  bool helix;
};
Case make_case(int trial, Seeded& rnd) {
  const bool round_the_back = trial % 4 == 0;
  const double r = round_the_back ? rnd(0.5, 2.0) : rnd(0.5, 50.0);
  const double sweep = (trial % 2 ? 1 : -1) * (round_the_back ? rnd(5.8, 6.2) : rnd(0.05, 6.2));
  const double climb = trial % 3 == 0 ? 0.0 : rnd(-3.0, 3.0);
  const Vec2 centre(rnd(-10, 10), rnd(-10, 10));
  const double start = rnd(-kPi, kPi);
  const Vec3 s(centre.x() + r * std::cos(start), centre.y() + r * std::sin(start), 1.0);
  const Vec3 e(centre.x() + r * std::cos(start + sweep), centre.y() + r * std::sin(start + sweep), 1.0 + climb);
  const ArcGeom arc = ArcGeom::through(s, e, centre, sweep > 0);
  const int count = round_the_back ? 1 + int(rnd(0, 1) * 2) : 2 + int(rnd(0, 1) * 60);
  return {arc, along(arc, count, rnd(0.0, 0.02), trial % 6 == 0, rnd), climb != 0};
}

}  // namespace

TEST_CASE("the arc measure is never less than the distance from the arc to the input, nor from the input to the "
          "arc, helices and input off the arc's plane included",
          "[deviation]") {
  // The measure skips what bounds show cannot raise its maximum; off the plane it takes the
  // largest gap between matched points of the input and the arc. Either way it must reach
  // both distances, here sampled finely, or an arc could leave the band unseen.
  Seeded rnd{0x9e3779b97f4a7c15ull};
  size_t helices = 0, off_plane = 0;
  for (int trial = 0; trial < 1200; ++trial) {
    const Case c = make_case(trial, rnd);
    const Deviation full = arc_deviation(c.pts, c.arc);
    if (!full.ordered) continue;
    const double arc_to_input = sampled_arc_to_polyline(c.arc, c.pts, 1000);
    const double input_to_arc = sampled_polyline_to_arc(c.arc, c.pts, 200);
    INFO("trial " << trial << ": measured " << full.max_mm << " mm, arc to input " << arc_to_input
                  << " mm, input to arc " << input_to_arc << " mm, " << c.pts.size() << " points");
    REQUIRE(full.max_mm >= arc_to_input - 1e-9);
    REQUIRE(full.max_mm >= input_to_arc - 1e-9);
    // Nor far above them where the arc climbs less than 1 in 10, as a helical entry does
    // (on a steeper helix a vertex's nearest point lies well off its own angle, where the
    // measure takes the distance).
    const double slope = std::abs(c.arc.h1 - c.arc.h0) / (c.arc.radius_mm * std::abs(c.arc.sweep));
    if (slope < 0.1) REQUIRE(full.max_mm <= 1.01 * std::max(arc_to_input, input_to_arc));
    helices += c.helix;
    off_plane += !c.helix && trial % 6 != 0;
  }
  CHECK(helices > 600);
  CHECK(off_plane > 120);
}

TEST_CASE("with a stop, the arc measure fails exactly the arcs whose whole measure exceeds it", "[deviation]") {
  // With a stop the measure leaves out what cannot reach it; the fitter and the emitter
  // only ask whether an arc passes.
  Seeded rnd{0x2545f4914f6cdd1dull};
  size_t passed = 0, failed = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Case c = make_case(trial, rnd);
    const Deviation full = arc_deviation(c.pts, c.arc);
    const Deviation by_angles = arc_deviation_by_angles(c.pts, c.arc);
    for (const double stop : {0.005, 0.01, 0.02}) {
      INFO("trial " << trial << ", stop " << stop << " mm: measured " << full.max_mm << " mm");
      const bool passes = full.ordered && full.max_mm <= stop;
      const Deviation stopped = arc_deviation(c.pts, c.arc, stop);
      REQUIRE((stopped.ordered && stopped.max_mm <= stop) == passes);
      const Deviation stopped_by_angles = arc_deviation_by_angles(c.pts, c.arc, stop);
      REQUIRE((stopped_by_angles.ordered && stopped_by_angles.max_mm <= stop) ==
              (by_angles.ordered && by_angles.max_mm <= stop));
      (passes ? passed : failed) += 1;
    }
  }
  // Both outcomes, or the check proves nothing.
  CHECK(passed > 500);
  CHECK(failed > 500);
}

TEST_CASE("the chords a firmware moves along are bounded from the polyline both ways, no less than the distance found "
          "by dense sampling and little more",
          "[deviation][executed]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  // Two-sided distance between two polylines, sampled every `step` mm along each.
  auto sampled = [](const std::vector<Vec3>& a, const std::vector<Vec3>& b, double step) {
    auto one_way = [&](const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
      double worst = 0;
      for (size_t i = 0; i + 1 < from.size(); ++i) {
        const int n = std::max(1, int(std::ceil((from[i + 1] - from[i]).norm() / step)));
        for (int k = 0; k <= n; ++k) {
          const Vec3 p = from[i] + (from[i + 1] - from[i]) * (double(k) / n);
          double best = HUGE_VAL;
          for (size_t j = 0; j + 1 < to.size(); ++j) best = std::min(best, point_segment_distance(p, to[j], to[j + 1]));
          worst = std::max(worst, best);
        }
      }
      return worst;
    };
    return std::max(one_way(a, b), one_way(b, a));
  };
  // The arc through `pts` about `centre`, cut into `n` chords as a firmware cuts it: the
  // bound lies no lower than the densely sampled distance both ways, and little above it.
  auto bounded_as_sampled = [&](const std::vector<Vec3>& pts, const Vec2& centre, double sweep, uint32_t n) {
    const ArcGeom g = ArcGeom::through(pts.front(), pts.back(), centre, sweep > 0);
    std::vector<Vec3> chords;
    std::vector<Vec2> ends;
    for (uint32_t k = 0; k < n; ++k) chords.push_back(g.point_at(double(k) / n));
    chords.push_back(pts.back());
    for (uint32_t k = 1; k < n; ++k) ends.push_back(chords[k].head<2>());
    const auto bound = chords_deviation_bound(pts, g, ends);
    REQUIRE(bound);
    const double step = 0.0005;
    const double measured = sampled(pts, chords, step);
    INFO("chords " << n);
    CHECK(*bound >= measured - 1e-9);
    CHECK(*bound <= measured + 0.25 * (measured + step));
  };
  for (int trial = 0; trial < 200; ++trial) {
    const double r = 0.5 + 20 * unit(rng), sweep = (0.2 + 2.8 * unit(rng)) * (unit(rng) < 0.5 ? -1 : 1);
    const Vec2 centre(10 * unit(rng), 10 * unit(rng));
    const double a0 = 6.28 * unit(rng), noise = 0.02 * unit(rng);
    // Input: vertices on the circle, jittered radially, in order; the ends on the circle.
    const int m = 3 + int(30 * unit(rng));
    std::vector<Vec3> pts;
    for (int i = 0; i <= m; ++i) {
      const double a = a0 + sweep * i / m, rr = r + (i == 0 || i == m ? 0 : noise * (2 * unit(rng) - 1));
      pts.push_back({centre.x() + rr * std::cos(a), centre.y() + rr * std::sin(a), 1.0});
    }
    INFO("trial " << trial << " r " << r << " sweep " << sweep);
    bounded_as_sampled(pts, centre, sweep, 1 + uint32_t(40 * unit(rng)));
  }
  // Where vertices lie at chord ends' angles, a cut is both at once (every chord end on a
  // vertex's ray, or every other one); a repeated vertex makes a piece of no length.
  for (int trial = 0; trial < 100; ++trial) {
    const double r = 0.5 + 20 * unit(rng), sweep = (0.2 + 2.8 * unit(rng)) * (unit(rng) < 0.5 ? -1 : 1);
    const Vec2 centre(10 * unit(rng), 10 * unit(rng));
    const double a0 = 6.28 * unit(rng), noise = 0.02 * unit(rng);
    const int m = 2 * (2 + int(15 * unit(rng)));
    std::vector<Vec3> pts;
    for (int i = 0; i <= m; ++i) {
      const double a = a0 + sweep * i / m, rr = r + (i == 0 || i == m ? 0 : noise * (2 * unit(rng) - 1));
      pts.push_back({centre.x() + rr * std::cos(a), centre.y() + rr * std::sin(a), 1.0});
      if (i == m / 2) pts.push_back(pts.back());
    }
    INFO("cuts together, trial " << trial << " r " << r << " sweep " << sweep);
    bounded_as_sampled(pts, centre, sweep, uint32_t(trial % 2 ? m : m / 2));
  }
  // A helix or a whole turn is not measured this way.
  const ArcGeom full = ArcGeom::through({1, 0, 0}, {1, 0, 0}, {0, 0}, true);
  const std::vector<Vec2> eight{{0.7071, 0.7071}, {0, 1}, {-0.7071, 0.7071}, {-1, 0}, {-0.7071, -0.7071}, {0, -1}, {0.7071, -0.7071}};
  CHECK_FALSE(chords_deviation_bound(std::vector<Vec3>{{1, 0, 0}, {-1, 0, 0}, {1, 0, 0}}, full, eight));
}
