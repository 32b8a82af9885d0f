// SPDX-License-Identifier: GPL-3.0-or-later
// Relaxing a constraint never costs blocks: a wider G1 angle, the band on the programmed
// circles rather than the firmware's chords, a wider extrusion variance, smaller radii or
// longer sweeps allow every chain the defaults allow, so none writes more forced kinks, or
// with as many more blocks, than the defaults do.
#include <catch2/catch.hpp>

#include <functional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "arcpress/arcpress.hpp"
#include "random_program.hpp"
#include "support.hpp"

using namespace arcpress;

namespace {

size_t blocks_out(const CompressResult& r) { return r.stats.lines_out + r.stats.arcs_out; }
/// What the fit weighs: forced kinks first, then blocks.
std::pair<size_t, size_t> cost(const CompressResult& r) { return {r.forced_kinks, blocks_out(r)}; }

CompressResult compressed(const std::string& text, CompressOptions opt) {
  opt.threads = 1;
  DiagnosticSink sink("relaxed");
  return compress("relaxed", text, opt, sink);
}

/// The ways to loosen a limit from its default, each with its name.
std::vector<std::pair<std::string, std::function<void(CompressOptions&)>>> loosenings() {
  return {{"G1 angle 1", [](CompressOptions& o) { o.fit.g1_angle_deg = 1; }},
          {"G1 angle 5", [](CompressOptions& o) { o.fit.g1_angle_deg = 5; }},
          {"G1 angle 30", [](CompressOptions& o) { o.fit.g1_angle_deg = 30; }},
          {"G1 angle 90", [](CompressOptions& o) { o.fit.g1_angle_deg = 90; }},
          {"band on the program", [](CompressOptions& o) { o.band = CompressOptions::Band::Program; }},
          {"extrusion variance 0.5", [](CompressOptions& o) { o.fit.extrusion_variance = 0.5; }},
          {"no smallest radius", [](CompressOptions& o) { o.fit.min_radius_mm = 0; }},
          {"sweeps to 359 degrees", [](CompressOptions& o) { o.fit.max_sweep_deg = 359; }}};
}

}  // namespace

TEST_CASE("no loosened limit writes more blocks than the defaults, on random programs", "[property][relax]") {
  for (uint32_t seed = 1; seed <= 30; ++seed) {
    std::mt19937 rng(seed);
    std::vector<uint8_t> bytes(3 + 3 * 400);
    for (auto& b : bytes) b = uint8_t(rng());
    test::RandomCase c = test::random_case(bytes);
    c.opt.fit.min_radius_mm = FitOptions{}.min_radius_mm;  // (the case may pick another: loosened from the default here)
    const CompressResult base = compressed(c.text, c.opt);
    REQUIRE(base.ok);
    for (const auto& [name, loosen] : loosenings()) {
      INFO("seed " << seed << ", " << name << ", dialect " << c.opt.dialect.name);
      CompressOptions o = c.opt;
      loosen(o);
      const CompressResult relaxed = compressed(c.text, o);
      CHECK(test::broken_promise(relaxed).empty());
      INFO(relaxed.forced_kinks << " kinks and " << blocks_out(relaxed) << " blocks against " << base.forced_kinks
                                 << " and " << blocks_out(base));
      CHECK(cost(relaxed) <= cost(base));
    }
  }
}

TEST_CASE("no loosened limit writes more blocks than the defaults, on the printer corpus for Marlin",
          "[property][relax]") {
  for (const auto& f : test::corpus_files()) {
    if (f.parent_path().filename() != "printer" || std::filesystem::file_size(f) > 200000) continue;
    for (double band : {0.025, 0.01}) {
      CompressOptions opt;
      opt.fit.tolerance_mm = band;
      opt.dialect = dialect_named("marlin");
      const std::string text = test::read_file(f);
      const CompressResult base = compressed(text, opt);
      for (const auto& [name, loosen] : loosenings()) {
        INFO(f.filename().string() << " at " << band << " mm, " << name);
        CompressOptions o = opt;
        loosen(o);
        const CompressResult relaxed = compressed(text, o);
        INFO(relaxed.forced_kinks << " kinks and " << blocks_out(relaxed) << " blocks against " << base.forced_kinks
                                   << " and " << blocks_out(base));
        CHECK(cost(relaxed) <= cost(base));
      }
    }
  }
}
