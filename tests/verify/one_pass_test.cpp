// SPDX-License-Identifier: GPL-3.0-or-later
// The compressor's check in one pass: the move-by-move comparison pairs each output move
// with the input moves it replaces and measures each pair both ways (on the firmware's
// chords where it moves on chords); where the pairs cover both paths, that bounds the
// distance `arcpress diff` measures over the whole paths, which is then not measured again.
// Where they do not, the whole paths are measured, and decide.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "arcpress/arcpress.hpp"
#include "arcpress/api/arcpress.hpp"
#include "arcpress/dialect/dialect_loader.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"
#include "arcpress/verify/executed_path.hpp"
#include "arcpress/verify/program_diff.hpp"
#include "random_program.hpp"
#include "support.hpp"

using namespace arcpress;

namespace {

/// Half a circle of radius `r_mm` about (50, 50) in 1-degree G1 moves, printed to 3
/// decimals, then a straight line of five 2 mm moves away from it.
std::string half_circle_and_tail(double r_mm) {
  std::string p = fmt::format("G21 G90 G17\nM3 S1000\nG0 X{:.3f} Y50\nG1 F1200\n", 50 + r_mm);
  for (int i = 1; i <= 180; ++i)
    p += fmt::format("G1 X{:.3f} Y{:.3f}\n", 50 + r_mm * std::cos(i * M_PI / 180), 50 + r_mm * std::sin(i * M_PI / 180));
  for (int i = 1; i <= 5; ++i) p += fmt::format("G1 X{:.3f} Y{:.3f}\n", 50 - r_mm, 50 - 2.0 * i);
  return p + "G0 Z5\nM5\nM2\n";
}

struct Checked {
  CompressResult result;
  ProgramDiff whole;  ///< arcpress diff's measure of the whole paths (executed where the band is)
};

/// `text` compressed with `opt`, and the output measured as `arcpress diff` measures it.
Checked compressed_and_measured(const std::string& text, const CompressOptions& opt) {
  DiagnosticSink sink("in");
  Checked c;
  c.result = compress("in", text, opt, sink);
  DiagnosticSink read_sink("in");
  const Program a = lex("in", text, read_sink, lex_rules(opt.dialect)),
                b = lex("out", c.result.output, read_sink, lex_rules(opt.dialect));
  const Interpretation ia = interpret(a, read_sink, opt.dialect), ib = interpret(b, read_sink, opt.dialect);
  DiffOptions dopt;
  dopt.tolerance_mm = opt.fit.tolerance_mm;
  dopt.feed = false;
  const ArcSegmentation rule = opt.executed_rule();
  c.whole = diff_programs(a, executed_path(ia, rule), b, executed_path(ib, rule), dopt);
  return c;
}

/// The check of `output` against `text`, as compress() checks its own.
CompressResult checked(const std::string& text, const std::string& output, const CompressOptions& opt) {
  DiagnosticSink sink("in");
  const Program in = lex("in", text, sink, lex_rules(opt.dialect));
  const Interpretation ii = interpret(in, sink, opt.dialect);
  CompressResult r;
  r.output = output;
  verify_output(in, ii, opt, r);
  return r;
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  REQUIRE(at != std::string::npos);
  return s.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("arcpress's own output is checked in one pass, and its bound holds the distance arcpress diff measures",
          "[verify][one-pass]") {
  for (const char* dialect : {"rs274", "marlin", "klipper"}) {
    for (double r : {0.8, 3.0, 40.0}) {
      INFO(dialect << ", radius " << r << " mm");
      CompressOptions opt;
      opt.dialect = dialect_named(dialect);
      const Checked c = compressed_and_measured(half_circle_and_tail(r), opt);
      REQUIRE(c.result.verified);
      CHECK(c.result.within_band());
      CHECK(c.result.stats.arcs_out > 0);
      CHECK(c.result.comparison.covers_path);
      CHECK(c.result.pieces_checked == 1);
      CHECK(c.result.pieces_measured_whole == 0);
      CHECK(c.result.check.max_deviation_mm > 0);
      // The pairs' bound is no less than the whole paths' distance (to that measure's precision).
      CHECK(c.whole.max_deviation_mm <= c.result.check.max_deviation_mm + c.whole.arc_chord_mm);
      CHECK(c.whole.same(opt.fit.tolerance_mm));
    }
  }
}

TEST_CASE("on the corpus, the one-pass check covers every piece, and bounds the whole paths' distance",
          "[verify][one-pass][corpus]") {
  ARCPRESS_CORPUS_FILES_OR_SKIP(files);
  for (const auto& f : files) {
    if (std::filesystem::file_size(f) > 2'000'000) continue;  // (the bunny and ps271: the same kind, minutes of measure)
    const bool printer = f.parent_path().filename() == "printer";
    CompressOptions opt;
    opt.fit.tolerance_mm = 0.01;
    opt.threads = 2;
    opt.dialect = dialect_named(printer ? "marlin" : "rs274");
    INFO(f.filename().string());
    const Checked c = compressed_and_measured(test::read_file(f), opt);
    REQUIRE(c.result.verified);
    CHECK(c.result.within_band());
    CHECK(c.result.pieces_checked > 0);
    CHECK(c.result.pieces_measured_whole == 0);
    CHECK(c.whole.max_deviation_mm <= c.result.check.max_deviation_mm + c.whole.arc_chord_mm);
    CHECK(c.whole.agrees(opt.fit.tolerance_mm));
  }
}

TEST_CASE("an output whose moves do not pair one for one with the input's is measured whole, and refused",
          "[verify][one-pass]") {
  const std::string text = half_circle_and_tail(3.0);
  CompressOptions opt;
  DiagnosticSink sink("in");
  const CompressResult r = compress("in", text, opt, sink);
  REQUIRE(r.within_band());
  const std::string last = "G1 X47.000 Y40.000\n";  // the tail's last move, written as it was
  REQUIRE(r.output.find(last) != std::string::npos);

  SECTION("the output stops short, its last feed move and the rapid after it left out: every output move still "
          "ends on the input path") {
    const CompressResult v = checked(text, replaced(r.output, last + "G0 Z5\n", ""), opt);
    CHECK(v.comparison.matched);
    CHECK_FALSE(v.comparison.covers_path);
    CHECK(v.pieces_measured_whole == 1);
    CHECK(v.check.max_deviation_mm > 1.9);  // the 2 mm move missing
    CHECK_FALSE(v.within_band());
  }
  SECTION("the last feed move made a rapid to the same point") {
    const CompressResult v = checked(text, replaced(r.output, last, "G0 X47.000 Y40.000\nG1\n"), opt);
    CHECK_FALSE(v.comparison.covers_path);
    CHECK(v.pieces_measured_whole == 1);
    CHECK_FALSE(v.within_band());
  }
  SECTION("the spindle reversed: paired one for one, and the rest still compared") {
    const CompressResult v = checked(text, replaced(r.output, "M3", "M4"), opt);
    CHECK(v.comparison.covers_path);
    CHECK(v.pieces_measured_whole == 0);
    CHECK(v.check.non_motion_differences == 1);
    CHECK_FALSE(v.within_band());
  }
}

TEST_CASE("an arc inside the band as programmed whose firmware chords leave it is refused where the band is on "
          "the chords",
          "[verify][one-pass][executed]") {
  // Klipper cuts a 3 mm radius into 1 mm chords, 0.04 mm inside the circle: four times the band.
  const std::string text = half_circle_and_tail(3.0);
  CompressOptions opt;
  opt.dialect = dialect_named("klipper");
  opt.band = CompressOptions::Band::Program;
  DiagnosticSink sink("in");
  const CompressResult programmed = compress("in", text, opt, sink);
  REQUIRE(programmed.within_band());
  REQUIRE(programmed.stats.arcs_out > 0);
  opt.band = CompressOptions::Band::Executed;
  const CompressResult v = checked(text, programmed.output, opt);
  CHECK(v.comparison.covers_path);
  CHECK(v.comparison.max_deviation_mm <= 0.01);    // the circles themselves keep the band
  CHECK(v.comparison.max_executed_mm > 0.03);       // their chords do not
  CHECK(v.pieces_measured_whole == 1);              // so the whole paths are measured, and decide
  CHECK(v.check.max_deviation_mm > 0.03);
  CHECK(v.check.max_deviation_mm <= v.comparison.max_executed_mm + v.check.arc_chord_mm);
  CHECK_FALSE(v.within_band());
}

TEST_CASE("on programs made from random bytes, in every plane, method, scale and dialect, the one-pass bound is "
          "never below the whole paths' distance",
          "[verify][one-pass][property]") {
  std::mt19937 rng(20261127);
  std::uniform_int_distribution<int> byte(0, 255), length(4, 400);
  size_t one_pass = 0, whole = 0;
  for (int trial = 0; trial < 1500; ++trial) {
    std::vector<uint8_t> bytes(static_cast<size_t>(length(rng)));
    for (auto& b : bytes) b = static_cast<uint8_t>(byte(rng));
    test::RandomCase c = test::random_case(bytes);
    INFO("trial " << trial << ", " << c.opt.dialect.name << ", tolerance " << c.opt.fit.tolerance_mm << " mm\n"
                  << c.text);
    const Checked r = compressed_and_measured(c.text, c.opt);
    if (!r.result.verified || !r.result.within_band()) continue;
    if (r.result.pieces_measured_whole > 0) {
      ++whole;
      continue;
    }
    ++one_pass;
    INFO("one-pass bound " << r.result.check.max_deviation_mm << " mm, whole paths " << r.whole.max_deviation_mm
                           << " mm, precision " << r.whole.arc_chord_mm << " mm");
    CHECK(r.whole.max_deviation_mm <= r.result.check.max_deviation_mm + r.whole.arc_chord_mm);
    CHECK(r.whole.agrees(c.opt.fit.tolerance_mm + r.whole.arc_chord_mm));
  }
  // Most are checked in one pass; the rest hold arcs on chords that climb, or lie over input
  // that climbs, which are measured whole.
  CHECK(one_pass > 1000);
  CHECK(whole < one_pass / 4);
}

TEST_CASE("the check measures a rotary axis at every input vertex an output move replaces, as the controller carries "
          "it along the move",
          "[verify][one-pass][axes]") {
  // Along X while A turns ever faster (a quarter of a degree a millimetre more each move):
  // the fit may join moves only while A, carried linearly along the block, stays within the
  // band of the input's A at every vertex between.
  std::string text = "G21 G90 G17\nG0 X0 Y0 Z0 A0\nG1 F300\n";
  double a = 0;
  for (int k = 1; k <= 40; ++k) text += fmt::format("G1 X{} A{:.4f}\n", k, a += 0.001 * k);
  text += "M2\n";
  CompressOptions opt;
  opt.dialect = dialect_named("linuxcnc");
  DiagnosticSink sink("in");
  const CompressResult r = compress("in", text, opt, sink);
  REQUIRE(r.within_band());
  CHECK(r.stats.lines_out + r.stats.arcs_out < 40);  // some moves were joined
  CHECK(r.comparison.extra_axis == kA);
  CHECK(r.comparison.max_extra_axis > 0);
  CHECK(r.comparison.max_extra_axis <= opt.fit.tolerance_mm);
  SECTION("one line over all of it, with the right ends, is refused at the vertex where A is farthest from it") {
    const std::string one = "G21 G90 G17\nG0 X0 Y0 Z0 A0\nG1 F300\n" + fmt::format("G1 X40 A{:.4f}\n", a) + "M2\n";
    const CompressResult v = checked(text, one, opt);
    CHECK(v.comparison.matched);
    CHECK(v.comparison.max_deviation_mm == 0.0);  // the same line in XYZ
    CHECK(v.comparison.extra_axis == kA);
    // A at X20 is 0.21 degrees; the line carries 0.82 / 2 = 0.41 there: the largest gap of
    // the parabola, at its middle.
    CHECK(v.comparison.max_extra_axis == Approx(0.2).margin(1e-4));  // (read within a tenth of the band of X20)
    CHECK(v.comparison.extra_axis_line_a == 23);  // "G1 X20 ..."
    CHECK(v.comparison.extra_axis_line_b == 4);
    CHECK_FALSE(v.within_band());
  }
}

TEST_CASE("every input move keeps its E per mm within the extrusion variance of the block that replaces it, which "
          "the check measures",
          "[verify][one-pass][extrusion]") {
  // A quarter circle of 40 mm in 1-degree moves whose extrusion grows by 4 % a move: each
  // move's rate within 5 % of its neighbours', twelvefold from the first to the last.
  std::string text = "G21 G90 M83\nG0 X40 Y0 Z0.2\nG1 F1200\n";
  double rate = 0.03;  // mm of E per mm
  for (int k = 1; k <= 90; ++k, rate *= 1.04)
    text += fmt::format("G1 X{:.3f} Y{:.3f} E{:.5f}\n", 40 * std::cos(k * M_PI / 180), 40 * std::sin(k * M_PI / 180),
                        rate * 0.698);
  text += "M2\n";
  CompressOptions opt;
  opt.dialect = dialect_named("marlin");
  opt.fit.tolerance_mm = 0.025;
  DiagnosticSink sink("in");
  const CompressResult r = compress("in", text, opt, sink);
  REQUIRE(r.within_band());
  CHECK(r.runs_kept_as_input == 0);
  CHECK(r.stats.arcs_out > 10);  // the band alone would take one arc
  CHECK(r.comparison.max_extrusion_rate_share > 0);
  CHECK(r.comparison.max_extrusion_rate_share <= 0.05 + 1e-9);
  SECTION("with the variance at 1 the rate may change anywhere: one arc") {
    opt.fit.extrusion_variance = 1;
    const CompressResult one = compress("in", text, opt, sink);
    CHECK(one.within_band());
    CHECK(one.stats.arcs_out + one.stats.lines_out == 1);
  }
  SECTION("one arc over all of it, printed by hand, is refused: its first move extrudes a ninth of the arc's "
          "average rate") {
    double e = 0;
    for (double x = 0.03, k = 0; k < 90; ++k, x *= 1.04) e += std::round(x * 0.698 * 1e5) / 1e5;
    const std::string one = fmt::format("G21 G90 M83\nG0 X40 Y0 Z0.2\nG1 F1200\nG3 X0.000 Y40.000 I-40 J0 E{:.5f}\nM2\n", e);
    const CompressResult v = checked(text, one, opt);
    CHECK(v.comparison.matched);
    CHECK(v.comparison.max_deviation_mm < 0.025);
    CHECK(v.comparison.max_extrusion_rate_share == Approx(1 - 0.03 / (e / (20 * M_PI))).margin(0.001));
    CHECK(v.comparison.extrusion_line_b == 4);
    CHECK_FALSE(v.within_band());
  }
}
