// SPDX-License-Identifier: GPL-3.0-or-later
// Extrusion along fitted arcs: E per mm stays the replaced moves' within the variance, the
// E at every written end is the input's, and extrusion never joins a travel.
#include <catch2/catch.hpp>

#include <cmath>

#include <fmt/format.h>

#include "arcpress/arcpress.hpp"

using namespace arcpress;

namespace {

/// A quarter circle of radius 10 in 1-degree moves, E per mm `first` for the first 45
/// moves and `second` after (absolute E, 5 decimals); `travel_at` > 0 leaves E out of that
/// move (a travel inside the curve).
std::string quarter(double first, double second, int travel_at = 0) {
  std::string p = "G21 G90 M82\nG92 E0\nG0 X10 Y0\nG1 F1200\n";
  double e = 0, step = 10 * M_PI / 180;
  for (int i = 1; i <= 90; ++i) {
    const double x = 10 * std::cos(i * M_PI / 180), y = 10 * std::sin(i * M_PI / 180);
    if (i == travel_at) {
      p += fmt::format("G1 X{:.4f} Y{:.4f}\n", x, y);
      continue;
    }
    e += (i <= 45 ? first : second) * step;
    p += fmt::format("G1 X{:.4f} Y{:.4f} E{:.5f}\n", x, y, e);
  }
  return p + "M2\n";
}

CompressResult run(const std::string& text, double variance) {
  CompressOptions opt;
  opt.fit.extrusion_variance = variance;
  DiagnosticSink sink("e");
  return compress("e", text, opt, sink);
}

}  // namespace

TEST_CASE("an arc ends where E per mm changes by more than --extrusion-variance, with the input's E there",
          "[extrusion]") {
  const std::string doubled = quarter(0.05, 0.10);
  const CompressResult strict = run(doubled, 0.05);
  REQUIRE(strict.within_band());
  // The move to 45 degrees ends a primitive, with the E the input has there.
  const std::string at45 = fmt::format("X{:.4f} Y{:.4f}", 10 * std::cos(M_PI / 4), 10 * std::sin(M_PI / 4));
  CHECK(strict.output.find(at45) != std::string::npos);
  CHECK(strict.output.find(fmt::format("E{:.5f}", 45 * 0.05 * 10 * M_PI / 180)) != std::string::npos);
  CHECK(strict.stats.arcs_out == 2);
  // A variance that allows the change lets one arc carry both rates; the E total is kept.
  const CompressResult loose = run(doubled, 1.0);
  REQUIRE(loose.within_band());
  CHECK(loose.stats.arcs_out == 1);
  CHECK(loose.output.find(fmt::format("E{:.5f}", (45 * 0.05 + 45 * 0.10) * 10 * M_PI / 180)) != std::string::npos);
  // An even rate is one arc at any variance.
  CHECK(run(quarter(0.05, 0.05), 0.01).stats.arcs_out == 1);
}

TEST_CASE("a travel move inside an extruded curve is never joined to it, at any variance", "[extrusion]") {
  const CompressResult r = run(quarter(0.05, 0.05, 30), 1.0);
  REQUIRE(r.within_band());
  // The travel is a block of its own that moves no E (a line, or an arc over it where the
  // joints ask for one), between blocks that end where the input's extrusion stops and
  // starts again, with the input's E there.
  const std::string to29 = fmt::format("X{:.4f} Y{:.4f}", 10 * std::cos(29 * M_PI / 180), 10 * std::sin(29 * M_PI / 180));
  const std::string to30 = fmt::format("X{:.4f} Y{:.4f}", 10 * std::cos(30 * M_PI / 180), 10 * std::sin(30 * M_PI / 180));
  const size_t at29 = r.output.find(to29), at30 = r.output.find(to30);
  REQUIRE(at29 != std::string::npos);
  REQUIRE(at30 != std::string::npos);
  const std::string block29 = r.output.substr(at29, r.output.find('\n', at29) - at29);
  const std::string block30 = r.output.substr(at30, r.output.find('\n', at30) - at30);
  CHECK(block29.find(fmt::format("E{:.5f}", 29 * 0.05 * 10 * M_PI / 180)) != std::string::npos);
  CHECK(block30.find('E') == std::string::npos);
}
