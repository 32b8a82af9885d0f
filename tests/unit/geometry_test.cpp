// SPDX-License-Identifier: GPL-3.0-or-later
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>

#include "arcpress/core/geometry.hpp"

using namespace arcpress;

TEST_CASE("pseudo-angles grow with the angle, and the scan's bound tests agree with them without dividing",
          "[geometry]") {
  // Directions all the way round, in steps that are no simple fraction of a turn.
  double last = -1;
  for (int i = 0; i < 3600; ++i) {
    const double rad = 2 * kPi * (i + 0.37) / 3600;
    const double p = pseudo_angle(std::cos(rad), std::sin(rad));
    INFO("angle " << rad << " rad");
    REQUIRE(p > last);
    REQUIRE(p >= 0);
    REQUIRE(p < 4);
    last = p;
  }
  // The bounds the fitter uses (half the sweep, a quarter of the G1 angle, none), against
  // seeded points of the upper half-plane at scales from micrometres to metres.
  uint64_t state = 0x2545f4914f6cdd1dull;
  auto next = [&] {
    state ^= state << 13, state ^= state >> 7, state ^= state << 17;
    return double(state % 2000001) / 1000000.0 - 1.0;  // [-1, 1]
  };
  size_t above = 0, below = 0;
  for (const double bound_rad : {0.0, deg_to_rad(0.125), deg_to_rad(45.0), kPi / 2, deg_to_rad(170.0)}) {
    const double bound = pseudo_angle_of(bound_rad);
    for (int i = 0; i < 20000; ++i) {
      const double scale = std::pow(10.0, int(i % 7) - 3);
      const double x = next() * scale, y = std::abs(next()) * scale;
      if (x == 0 && y == 0) continue;
      const double p = pseudo_angle(x, y);
      // Only where the division itself rounds onto the bound may the two differ.
      if (std::abs(p - bound) <= 1e-15) continue;
      INFO("(" << x << ", " << y << ") against " << bound);
      REQUIRE(pseudo_angle_above(x, y, bound) == (p > bound));
      REQUIRE(pseudo_angle_below(x, y, bound) == (p < bound));
      above += p > bound;
      below += p < bound;
    }
  }
  CHECK(above > 1000);  // both sides of every bound were tried
  CHECK(below > 1000);
  // No bound reaches past the upper half-plane's pseudo-angles (3: no sweep limit).
  CHECK_FALSE(pseudo_angle_above(-1, 1e-9, 3.0));
  CHECK_FALSE(pseudo_angle_above(-1, 0, 3.0));
}
