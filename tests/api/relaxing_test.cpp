// Relaxing a constraint never costs blocks: a wider G1 angle allows every chain the default
// allows, so it never writes more blocks than the default does.
#include <catch2/catch.hpp>

#include <random>

#include "arcpress/arcpress.hpp"
#include "random_program.hpp"
#include "support.hpp"

using namespace arcpress;

namespace {

size_t blocks_out(const CompressResult& r) { return r.stats.lines_out + r.stats.arcs_out; }

CompressResult compressed(const std::string& text, CompressOptions opt, double g1_angle_deg) {
  opt.fit.g1_angle_deg = g1_angle_deg;
  opt.threads = 1;
  DiagnosticSink sink("relaxed");
  return compress("relaxed", text, opt, sink);
}

}  // namespace

TEST_CASE("a wider G1 angle never writes more blocks than the default, on random programs", "[property][relax]") {
  for (uint32_t seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(seed);
    std::vector<uint8_t> bytes(3 + 3 * 400);
    for (auto& b : bytes) b = uint8_t(rng());
    const test::RandomCase c = test::random_case(bytes);
    const CompressResult base = compressed(c.text, c.opt, 0.5);
    REQUIRE(base.ok);
    for (double g1 : {1.0, 5.0, 30.0, 90.0}) {
      INFO("seed " << seed << ", G1 angle " << g1);
      const CompressResult relaxed = compressed(c.text, c.opt, g1);
      CHECK(test::broken_promise(relaxed).empty());
      CHECK(blocks_out(relaxed) <= blocks_out(base));
    }
  }
}

TEST_CASE("a wider G1 angle never writes more blocks than the default, on the printer corpus", "[property][relax]") {
  for (const auto& f : test::corpus_files()) {
    if (f.parent_path().filename() != "printer" || std::filesystem::file_size(f) > 200000) continue;
    INFO(f.filename().string());
    CompressOptions opt;
    opt.fit.tolerance_mm = 0.025;
    opt.dialect = dialect_named("marlin");
    const std::string text = test::read_file(f);
    const size_t base = blocks_out(compressed(text, opt, 0.5));
    for (double g1 : {2.0, 10.0, 60.0}) {
      INFO("G1 angle " << g1);
      CHECK(blocks_out(compressed(text, opt, g1)) <= base);
    }
  }
}
