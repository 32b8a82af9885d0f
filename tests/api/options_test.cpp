// SPDX-License-Identifier: GPL-3.0-or-later
// The library refuses numbers no search is bounded for, as the command line does.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>

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
