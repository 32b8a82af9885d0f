// SPDX-License-Identifier: GPL-3.0-or-later
// The library refuses numbers no search is bounded for, as the command line does.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <regex>
#include <stdexcept>

#include <fmt/format.h>

#include "arcpress/api/arcpress.hpp"
#include "arcpress/core/error.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"

using namespace arcpress;

TEST_CASE("compress() refuses a band or a limit that is not a finite number in its range", "[api][options]") {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const std::string program = "G21 G90\nG0 X0 Y0 Z0\nG1 X1 F100\nG1 X2 Y0.1\nM2\n";
  auto refused = [&](auto edit) {
    CompressOptions opt;
    edit(opt.fit);
    DiagnosticSink sink;
    try {
      compress("t.nc", program, opt, sink);
    } catch (const Error& e) {
      return e.exit_code() == kExitInput;
    }
    return false;
  };
  CHECK(refused([&](FitOptions& o) { o.tolerance_mm = nan; }));
  CHECK(refused([&](FitOptions& o) { o.tolerance_mm = 1e-300; }));
  CHECK(refused([&](FitOptions& o) { o.g1_angle_deg = nan; }));
  CHECK(refused([&](FitOptions& o) { o.corner_angle_deg = inf; }));
  CHECK(refused([&](FitOptions& o) { o.min_radius_mm = -1; }));
  CHECK(refused([&](FitOptions& o) { o.max_radius_mm = nan; }));
  CHECK(refused([&](FitOptions& o) { o.max_sweep_deg = nan; }));
  CHECK(refused([&](FitOptions& o) { o.min_arc_length_mm = inf; }));
  CHECK_FALSE(refused([&](FitOptions&) {}));
}

TEST_CASE("diff_programs() refuses a band it cannot end its search at", "[api][options][diff]") {
  DiagnosticSink sink;
  Program p = lex("t.nc", "G0 X0 Y0 Z0\nG1 X1 F100\n", sink);
  Interpretation in = interpret(p, sink);
  for (double tol : {std::numeric_limits<double>::quiet_NaN(), 0.0, 1e-300, 1e9}) {
    DiffOptions opt;
    opt.tolerance_mm = tol;
    CHECK_THROWS_AS(diff_programs(p, in, p, in, opt), std::invalid_argument);
  }
}

TEST_CASE("the fitter keeps back twice what rounding a centre to the dialect's finest digits can move it: 1 % of the "
          "band at the least, 3 % at the most and where the step is not known",
          "[api][options][fit]") {
  auto share = [](int max_decimals, double unit_mm, double band_mm) {
    Dialect d;
    d.mm.max = d.inch.max = max_decimals;
    Frame frame;
    frame.unit_mm = unit_mm;
    FitOptions user;
    user.tolerance_mm = band_mm;
    return rounding_reserve_share(fit_options_for(user, d, frame, Plane::XY));
  };
  // A step of 10^-max in the frame's unit moves a centre rounded on both axes by up to 0.71
  // of it; twice that, as a share of the band.
  CHECK(share(6, 1.0, 0.01) == Approx(kMinRoundingReserve));        // 1.4e-6 mm: far below 1 %
  CHECK(share(4, 1.0, 0.01) == Approx(2 * 0.71 * 1e-4 / 0.01));     // 1.42 %
  CHECK(share(4, 1.0, 0.005) == Approx(2 * 0.71 * 1e-4 / 0.005));   // 2.84 %
  CHECK(share(3, 1.0, 0.01) == Approx(kMaxRoundingReserve));        // 14 % would be more than the most kept
  CHECK(share(4, 25.4, 0.01) == Approx(kMaxRoundingReserve));       // 10^-4 inch is 2.54 µm
  CHECK(share(6, 25.4, 0.01) == Approx(kMinRoundingReserve));
  FitOptions unknown;
  CHECK(rounding_reserve_share(unknown) == kMaxRoundingReserve);
  // What is kept back is what the printed arcs need: a circle written in fine moves comes out
  // as arcs inside the band at each number of digits, its centres printed to no more.
  std::string program = "G21 G90 G17\nG0 X10 Y0 Z0\nG1 F600\n";
  for (int k = 1; k <= 720; ++k)
    program += fmt::format("G1 X{:.4f} Y{:.4f}\n", 10 * std::cos(k * kPi / 360), 10 * std::sin(k * kPi / 360));
  program += "M2\n";
  for (int max_decimals : {3, 4, 5, 6}) {
    CompressOptions opt;
    opt.fit.tolerance_mm = 0.005;
    opt.dialect.mm.centre = 3;
    opt.dialect.mm.max = max_decimals;
    DiagnosticSink sink;
    const CompressResult r = compress("circle.nc", program, opt, sink);
    INFO("centres to at most " << max_decimals << " decimals:\n" << r.output);
    REQUIRE(r.ok);
    CHECK(r.stats.arcs_out >= 2);
    CHECK(r.stats.lines_out == 0);
    CHECK(r.check.max_deviation_mm <= 0.005);
    const std::regex centre_word("[IJ]-?[0-9]*\\.([0-9]+)");
    for (auto w = std::sregex_iterator(r.output.begin(), r.output.end(), centre_word); w != std::sregex_iterator(); ++w)
      CHECK((*w)[1].length() <= max_decimals);
  }
}
