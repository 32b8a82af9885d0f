// SPDX-License-Identifier: GPL-3.0-or-later
#include <catch2/catch.hpp>
#include <sstream>
#include <cmath>
#include <fmt/format.h>

#include "arcpress/api/arcpress.hpp"
#include "arcpress/emit/emitter.hpp"
#include "arcpress/emit/number_format.hpp"
#include "arcpress/extract/run.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"

using namespace arcpress;

TEST_CASE("numbers are printed in fixed point, never with an exponent or as -0", "[emit]") {
  CHECK(format_number(1e-5, {6, true, false}) == "0.00001");
  CHECK(format_number(1e-5, {4, true, false}) == "0");
  CHECK(format_number(-0.00001, {4, true, false}) == "0");
  CHECK(format_number(12.5, {3, true, false}) == "12.5");
  CHECK(format_number(12.0, {3, true, false}) == "12");
  CHECK(format_number(12.0, {3, true, true}) == "12.");
  CHECK(format_number(-3.14159, {4, false, false}) == "-3.1416");
  CHECK(format_number(123456789.0, {3, true, false}) == "123456789");
}

TEST_CASE("a printed number reads back as the value rounded to its digits, half away from zero, with exactly "
          "as many digits as it needs",
          "[emit]") {
  CHECK(format_number(0.00005, {4, true, false}) == "0.0001");
  CHECK(format_number(-0.00005, {4, true, false}) == "-0.0001");
  CHECK(format_number(-0.00004, {3, false, true}) == "0.000");
  CHECK(format_number(7.0, {0, false, true}) == "7.");
  CHECK(format_number(-2.5, {0, true, false}) == "-3");
  CHECK(format_number(0.1, {3, false, false}) == "0.100");
  // Seeded, so every run checks the same values: magnitudes from 1e-7 to 1e9 mm, 0 to 6 decimals.
  uint64_t state = 0x9e3779b97f4a7c15ull;
  auto next = [&] {
    state ^= state << 13, state ^= state >> 7, state ^= state << 17;
    return state;
  };
  for (int i = 0; i < 200000; ++i) {
    const int decimals = int(next() % 7);
    const double magnitude = std::pow(10.0, int(next() % 17) - 7);
    const double value = (double(next() % 2000001) / 1000000.0 - 1.0) * magnitude;
    for (const NumberStyle style : {NumberStyle{decimals, true, false}, NumberStyle{decimals, false, true}}) {
      const std::string text = format_number(value, style);
      INFO(fmt::format("{:.17g} at {} decimals: {}", value, decimals, text));
      REQUIRE(text.find_first_of("eE") == std::string::npos);
      REQUIRE(text != "-0");
      REQUIRE(std::stod(text) == rounded(value, decimals));
      const size_t point = text.find('.');
      const size_t digits = point == std::string::npos ? 0 : text.size() - point - 1;
      if (style.trim_zeros) {
        REQUIRE(digits <= size_t(decimals));
        REQUIRE((digits == 0 || text.back() != '0'));
      } else {
        REQUIRE(digits == size_t(decimals));
      }
    }
  }
}

namespace {
/// Emits `text` with the given primitives for its single run.
std::string emit_with(const std::string& text, std::vector<Primitive> prims) {
  DiagnosticSink sink;
  Program p = lex("t.nc", text, sink);
  Interpretation in = interpret(p, sink);
  auto runs = extract_runs(in);
  REQUIRE(runs.size() == 1);
  std::vector<FitResult> fits{{std::move(prims)}};
  return emit_program(p, in, runs, fits);
}
}  // namespace

TEST_CASE("lines the fitter keeps are copied byte for byte", "[emit]") {
  std::string text = "G0 X0 Y0 Z0\nG1 X1 Y0 F100 \nX2 Y0.5\nX3 Y0.5\nM2\n";
  CHECK(emit_with(text, {{1}, {2}, {3}}) == text);
}

TEST_CASE("a merged line reuses the input's own number text and look", "[emit]") {
  std::string text = "g0 x0 y0 z0\ng01 x1.000 y0 f100\nx2.000 y0\nx3.000 y0\nm2\n";
  CHECK(emit_with(text, {{3}}) == "g0 x0 y0 z0\ng01 x3.000 y0 f100\nm2\n");
}

namespace {
/// A quarter circle of radius 10 about the origin from (10, 0) to (0, 10) as 32 G1 moves
/// printed to 4 decimals, then one more move and M2.
std::string quarter_circle_program(const std::string& header = "G0 X10 Y0 Z0\n") {
  std::string t = header;
  for (int k = 1; k <= 32; ++k) {
    double a = kPi / 2 * k / 32;
    t += fmt::format("{}X{} Y{}{}\n", k == 1 ? "G1 " : "", format_number(10 * std::cos(a), {4, true, false}),
                     format_number(10 * std::sin(a), {4, true, false}), k == 1 ? " F200" : "");
  }
  return t + "X-5 Y10\nM2\n";
}
}  // namespace

TEST_CASE("an arc is written with I/J from its start, and the next copied block restates G1", "[emit]") {
  Primitive arc{32, Primitive::Kind::Arc, true, Vec2(0, 0), 10.0};
  std::string out = emit_with(quarter_circle_program(), {arc, {33}});
  CHECK(out == "G0 X10 Y0 Z0\nG3 X0 Y10 I-10 J0 F200\nG1 X-5 Y10\nM2\n");
}

TEST_CASE("an arc that leaves the band once printed is written as the input's own lines", "[emit]") {
  // Two chords of a radius-10 circle: the arc bulges 0.76 mm away from them.
  std::string text = "N5 G0 X10 Y0 Z0\nN10 G1 X7.071 Y7.071 F200\nN20 X0 Y10\nN30 X-5 Y10\nN40 M2\n";
  Primitive arc{2, Primitive::Kind::Arc, true, Vec2(0, 0), 10.0};
  CHECK(emit_with(text, {arc, {3}}) == text);
}

TEST_CASE("relative programs get relative end points, and M83 E is summed", "[emit]") {
  std::string text = "G0 X0 Y0 Z0\nG91\nM83\nG1 X1 E0.1 F100\nX1 E0.1\nX1 E0.1\nM2\n";
  CHECK(emit_with(text, {{3}}) == "G0 X0 Y0 Z0\nG91\nM83\nG1 X3 E0.3 F100\nM2\n");
}

TEST_CASE("blocks composed on several threads read the same as on one: the motion word is settled in order",
          "[emit][threads]") {
  // Forty runs between rapid moves, each a line, a quarter circle and a line in short G1
  // moves, the motion word written on the first move only (every third run: on every move),
  // every fourth run numbered: whether a new block must state G1, G2 or G3 depends on the
  // block before it in the output, which a thread composing blocks apart cannot know.
  std::string text = "G21 G90 G17\nG0 Z1\n";
  for (int k = 0; k < 40; ++k) {
    const double cx = 40.0 * (k % 8), cy = 40.0 * (k / 8), r = 5.0 + k % 5, turn = k % 2 ? -1 : 1;
    std::vector<std::pair<double, double>> pts;
    for (int i = 0; i <= 10; ++i) pts.push_back({cx + r, cy - 5 * turn + 0.5 * i * turn});  // up to (cx + r, cy)
    for (int d = 1; d <= 90; ++d) {
      const double a = d * kPi / 180 * turn;
      pts.push_back({cx + r * std::cos(a), cy + r * std::sin(a)});
    }
    for (int i = 1; i <= 10; ++i) pts.push_back({cx - 0.5 * i, cy + r * turn});  // on from (cx, cy + r)
    text += fmt::format("G0 X{:.4f} Y{:.4f}\n", pts[0].first, pts[0].second);
    for (size_t i = 1; i < pts.size(); ++i) {
      std::string line = fmt::format("X{:.4f} Y{:.4f}", pts[i].first, pts[i].second);
      if (i == 1 || k % 3 == 0) line = "G1 " + line;
      if (i == 1) line += " F600";
      if (k % 4 == 0) line = fmt::format("N{} ", 1000 * k + int(i)) + line;
      text += line + "\n";
    }
  }
  text += "M30\n";
  auto run = [&](unsigned threads) {
    CompressOptions opt;
    opt.threads = threads;
    DiagnosticSink sink;
    return compress("t.nc", text, opt, sink);
  };
  const CompressResult one = run(1), three = run(3);
  REQUIRE(one.ok);
  REQUIRE(three.ok);
  CHECK(three.output == one.output);
  CHECK(one.stats.arcs_out >= 40);
  CHECK(one.stats.lines_out >= 80);
  // Read back, the path is the input's: no block lost its motion word, none gained a wrong one.
  CHECK(one.check.same(0.01));
  CHECK(one.comparison.max_deviation_mm <= 0.01);
}

TEST_CASE("an arc that continues the modal motion starts with its first word, as the input's blocks do", "[emit]") {
  // Two quarter circles the same way round, written as modal continuations ("X.. Y.."):
  // the second arc leaves out its G2, and its separator with it.
  std::string t = "G21 G90 G17\nG0 X10 Y0 Z0\nG1 F300\n";
  for (int k = 1; k <= 90; ++k)
    t += fmt::format("X{:.4f} Y{:.4f}\n", 10 * std::cos(-k * M_PI / 180), 10 * std::sin(-k * M_PI / 180));
  for (int k = 1; k <= 90; ++k)
    t += fmt::format("X{:.4f} Y{:.4f}\n", 5 * std::cos(M_PI / 2 - k * M_PI / 180), -15 + 5 * std::sin(M_PI / 2 - k * M_PI / 180));
  t += "M30\n";
  CompressOptions opt;
  DiagnosticSink sink;
  const CompressResult r = compress("t.nc", t, opt, sink);
  REQUIRE(r.ok);
  REQUIRE(r.within_band());
  REQUIRE(r.stats.arcs_out >= 2);
  std::istringstream out(r.output);
  size_t continuations = 0;
  for (std::string line; std::getline(out, line);) {
    INFO(line);
    CHECK((line.empty() || line[0] != ' '));
    continuations += line.rfind("X", 0) == 0 && line.find(" I") != std::string::npos;
  }
  CHECK(continuations >= 1);
}
