// SPDX-License-Identifier: GPL-3.0-or-later
// The block rate a program demands: blocks and bytes per second over any 1 s of cutting, at
// the programmed feeds, and the share of the cutting time over a dialect's limits.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <string>

#include "arcpress/api/arcpress.hpp"
#include "arcpress/api/compressor.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"
#include "arcpress/verify/block_rate.hpp"
#include "support.hpp"

using namespace arcpress;

namespace {

BlockRate rate_of(const std::string& text, double max_blocks = 0, double link_bytes = 0) {
  DiagnosticSink sink("rate.nc");
  Program p = lex("rate.nc", text, sink);
  Interpretation in = interpret(p, sink);
  return block_rate(p, in, max_blocks, link_bytes);
}

/// `count` moves along X of `step_mm` each at `feed`, from X `from`, each block `X<value>`
/// printed with 3 decimals (so every block is "G1 X12.345\n" or as long).
std::string moves_along_x(int count, double step_mm, double from, double feed, bool state_feed = true) {
  std::string t = state_feed ? fmt::format("G1 F{}\n", feed) : std::string();
  for (int i = 1; i <= count; ++i) t += fmt::format("G1 X{:.3f}\n", from + i * step_mm);
  return t;
}

}  // namespace

TEST_CASE("a printer program at F6000 in 0.1 mm moves demands 1000 blocks per second", "[block_rate]") {
  // 3000 moves of 0.1 mm at 100 mm/s: 3 s of cutting, 1000 blocks in every second of it.
  const std::string text = "G21 G90\nG0 X100 Y0\n" + moves_along_x(3000, 0.1, 100, 6000);
  const BlockRate r = rate_of(text);
  CHECK(r.blocks == 3000);  // ("G1 F6000" moves nowhere: not a block of cutting)
  CHECK(r.cutting_s == Approx(3.0).epsilon(1e-9));
  CHECK(r.peak_blocks_per_s == Approx(1000).margin(1));
  CHECK(r.p95_blocks_per_s == Approx(1000).margin(1));
  // Blocks "G1 X100.100\n" to "G1 X400.000\n": 12 bytes each.
  CHECK(r.peak_bytes_per_s == Approx(12000).margin(12));
  CHECK(r.untimed == 0);
}

TEST_CASE("the peak is a burst's and the 95th percentile the rate most of the cutting keeps", "[block_rate]") {
  // One second at 1000 blocks/s, then 39 s at 10 blocks/s (1 mm moves at F600).
  const std::string text = "G21 G90\nG0 X0 Y0\n" + moves_along_x(1000, 0.1, 0, 6000) +
                           moves_along_x(390, 1.0, 100, 600);
  const BlockRate r = rate_of(text);
  CHECK(r.cutting_s == Approx(40.0).epsilon(1e-9));
  CHECK(r.peak_blocks_per_s == Approx(1000).margin(1));
  CHECK(r.p95_blocks_per_s == Approx(10).margin(1));
}

TEST_CASE("the share of cutting time over the dialect's limits", "[block_rate]") {
  // 2 s at 1000 blocks/s (12 000 bytes/s), then 18 s at 10 blocks/s.
  const std::string text =
      "G21 G90\nG0 X100 Y0\n" + moves_along_x(2000, 0.1, 100, 6000) + moves_along_x(180, 1.0, 300, 600);
  const BlockRate r = rate_of(text, 500, 11520);
  // Windows start over [0, 19] s. One starting at t in [1, 2] holds 1000 (2 - t) fast blocks
  // and 10 (t - 1) slow ones, 12 bytes each: over 500 blocks for t < 1490 / 990, over
  // 11 520 bytes (960 blocks) for t < 1030 / 990.
  CHECK(r.over_blocks_share == Approx(1490.0 / 990 / 19).margin(0.001));
  CHECK(r.over_link_share == Approx(1030.0 / 990 / 19).margin(0.001));
  const BlockRate none = rate_of(text);
  CHECK(none.over_blocks_share < 0);  // no limit set: not measured
  CHECK(none.over_link_share < 0);
}

TEST_CASE("a program that cuts for less than a second is one window", "[block_rate]") {
  const BlockRate r = rate_of("G21 G90\nG0 X0\n" + moves_along_x(10, 5.0, 0, 6000), 5, 0);
  CHECK(r.cutting_s == Approx(0.5));
  CHECK(r.peak_blocks_per_s == 10);
  CHECK(r.p95_blocks_per_s == 10);
  CHECK(r.over_blocks_share == 1);
}

TEST_CASE("arcs last their length at the feed, and moves without a feed or in inverse time are counted apart",
          "[block_rate]") {
  // A half circle of radius 10 at F600: 31.4 mm, 3.14 s.
  const BlockRate arc = rate_of("G21 G90 G17\nG0 X10 Y0\nG3 X-10 Y0 I-10 J0 F600\n");
  CHECK(arc.cutting_s == Approx(M_PI).epsilon(1e-9));
  const BlockRate odd = rate_of("G21 G90\nG0 X0\nG1 X1\nG93 G1 X2 F10\nG94 G1 X3 F600\n");
  CHECK(odd.untimed == 2);  // the first G1 has no feed yet; the G93 one's F is per block
  CHECK(odd.blocks == 1);
}

TEST_CASE("compressing shows the block rate falling, and a streamed program measures as a whole one",
          "[block_rate]") {
  // A circle of radius 20 in 0.1 mm moves at F6000, ten times over: about 1000 blocks/s.
  std::string text = "G21 G90 G17\nG0 X20 Y0\nG1 F6000\n";
  const int n = 1257;
  for (int lap = 0; lap < 10; ++lap)
    for (int i = 1; i <= n; ++i)
      text += fmt::format("G1 X{:.4f} Y{:.4f}\n", 20 * std::cos(2 * M_PI * i / n), 20 * std::sin(2 * M_PI * i / n));
  REQUIRE(text.size() > 2 * kPieceBytes);  // several pieces
  CompressOptions opt;
  opt.block_rate = true;
  opt.dialect.link_bytes_per_s = 11520;
  DiagnosticSink sink("circle.nc");
  const CompressResult r = compress("circle.nc", text, opt, sink);
  REQUIRE(r.ok);
  REQUIRE(r.rate_in);
  REQUIRE(r.rate_out);
  CHECK(r.rate_in->peak_blocks_per_s == Approx(1000).margin(2));
  CHECK(r.rate_in->over_link_share > 0.9);  // 22 bytes a block, 22 000 bytes/s
  CHECK(r.rate_out->peak_blocks_per_s < 20);
  CHECK(r.rate_out->over_link_share == 0);
  // The pieces' measure is the whole program's.
  const BlockRate whole = rate_of(text, 0, 11520);
  CHECK(r.rate_in->peak_blocks_per_s == whole.peak_blocks_per_s);
  CHECK(r.rate_in->p95_blocks_per_s == whole.p95_blocks_per_s);
  CHECK(r.rate_in->peak_bytes_per_s == whole.peak_bytes_per_s);
  CHECK(r.rate_in->cutting_s == Approx(whole.cutting_s).epsilon(1e-12));
  CHECK(r.rate_in->over_link_share == Approx(whole.over_link_share).epsilon(1e-9));
}

TEST_CASE("arcpress diff --json and --stats report the block rate of both programs against the dialect's link",
          "[block_rate][cli]") {
  const test::TempDir dir = test::temp_dir("rate");
  std::string text = "G21 G90 G17\nG0 X20 Y0\nG1 F6000\n";
  for (int i = 1; i <= 1257; ++i)
    text += fmt::format("G1 X{:.4f} Y{:.4f}\n", 20 * std::cos(2 * M_PI * i / 1257), 20 * std::sin(2 * M_PI * i / 1257));
  test::write_file(dir / "in.nc", text);
  const std::string in = (dir / "in.nc").string(), out = (dir / "out.nc").string();
  const test::Command made = test::run_arcpress(fmt::format("'{}' -o '{}' --dialect grbl --stats", in, out));
  REQUIRE(made.exit_code == 0);
  // 0.09997 mm chords at 100 mm/s: 1000.3 blocks in a second.
  CHECK(made.err.find("in:  peak 1001 blocks/s") != std::string::npos);
  CHECK(made.err.find("link 11520 bytes/s exceeded 100.0 % of it") != std::string::npos);
  const test::Command d = test::run_arcpress(fmt::format("diff '{}' '{}' --dialect grbl --json", in, out));
  REQUIRE(d.exit_code == 0);
  CHECK(d.out.find("\"block_rate\": {\"cutting_s\": ") != std::string::npos);
  CHECK(d.out.find("\"peak_blocks_per_s\": 1001") != std::string::npos);
  CHECK(d.out.find("\"over_link_share\": 1.000000") != std::string::npos);   // the input
  CHECK(d.out.find("\"over_link_share\": 0.000000") != std::string::npos);   // the output
  CHECK(d.out.find("\"over_max_blocks_share\": null") != std::string::npos);  // grbl sets no block limit
}
