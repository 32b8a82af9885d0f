// SPDX-License-Identifier: GPL-3.0-or-later
// Every program, every axis: 2-D laser, plasma and router programs that never write Z,
// lathe programs that never write Y, laser programs that carry S on every move, and what
// arcpress says about the G1 moves it leaves as they are.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <regex>
#include <sstream>

#include "arcpress/api/arcpress.hpp"
#include "arcpress/dialect/dialect_loader.hpp"
#include "support.hpp"

using namespace arcpress;

namespace {

CompressResult compressed(const std::string& text, DiagnosticSink& sink, const std::string& dialect = "rs274") {
  CompressOptions opt;
  opt.fit.tolerance_mm = 0.01;
  opt.dialect = load_dialect_file(ARCPRESS_SOURCE_DIR "/dialects/" + dialect + ".toml");
  CompressResult r = compress("t.nc", text, opt, sink);
  REQUIRE(r.ok);
  REQUIRE(r.verified);
  INFO(r.comparison.mismatch);
  REQUIRE(r.within_band());
  return r;
}

/// Xu's first test curve (a cubic Bézier through (0,0), (1,4), (5,-2), (6,3) scaled to mm)
/// as 1000 G1 moves, with `z_word` written on the rapid to its start ("" for a 2-D program).
std::string bezier_program(const std::string& z_word) {
  std::string t = fmt::format("G21 G90\nG0 X0 Y0{}\nG1 F600\n", z_word);
  const double px[4] = {0, 10, 50, 60}, py[4] = {0, 40, -20, 30};
  for (int k = 1; k <= 1000; ++k) {
    const double s = k / 1000.0, u = 1 - s;
    const double w[4] = {u * u * u, 3 * u * u * s, 3 * u * s * s, s * s * s};
    t += fmt::format("G1 X{:.4f} Y{:.4f}\n", w[0] * px[0] + w[1] * px[1] + w[2] * px[2] + w[3] * px[3],
                     w[0] * py[0] + w[1] * py[1] + w[2] * py[2] + w[3] * py[3]);
  }
  return t + "M2\n";
}

size_t count_of(const std::string& text, const std::regex& line) {
  std::istringstream in(text);
  size_t n = 0;
  for (std::string l; std::getline(in, l);) n += std::regex_search(l, line);
  return n;
}

}  // namespace

TEST_CASE("a 2-D curve that never writes Z is fitted with arcs, as the same curve with Z is", "[api][2d]") {
  DiagnosticSink s2("2d"), s3("3d");
  const CompressResult flat = compressed(bezier_program(""), s2);
  const CompressResult with_z = compressed(bezier_program(" Z0"), s3);
  CHECK(flat.stats.moves_in == 1000);
  CHECK(flat.stats.arcs_out >= 3);
  CHECK(flat.stats.arcs_out + flat.stats.lines_out <= 12);
  CHECK(flat.stats.arcs_out == with_z.stats.arcs_out);
  CHECK(flat.stats.lines_out == with_z.stats.lines_out);
  // Z is never printed where the input did not print it.
  CHECK(flat.output.find('Z') == std::string::npos);
}

TEST_CASE("a Z-less laser program from the corpus is compressed within the band", "[api][2d][corpus]") {
  const auto file = std::filesystem::path(ARCPRESS_CORPUS_DIR) / "laser" / "jscut_jsdc-laser.gcode";
  if (!std::filesystem::exists(file)) {
    WARN(file.string() << " is absent: skipped");
    return;
  }
  const std::string text = test::read_file(file);
  REQUIRE(text.find('Z') == std::string::npos);
  DiagnosticSink sink(file.string());
  const CompressResult r = compressed(text, sink);
  CHECK(r.stats.moves_in > 2000);
  CHECK(r.stats.arcs_out > 50);
  CHECK(r.stats.arcs_out + r.stats.lines_out < r.stats.moves_in / 10);
  CHECK(r.check.max_deviation_mm <= 0.01);
  CHECK(r.output.find('Z') == std::string::npos);
}

TEST_CASE("a lathe program in G18 that never writes Y is fitted with G18 arcs", "[api][lathe]") {
  // A radius-mode (G8) finishing pass: a quarter circle of radius 8 mm in XZ, in 1° steps.
  std::string t = "G21 G18 G8 G90\nG0 X0 Z1\nG1 Z0 F50\n";
  for (int k = 1; k <= 90; ++k)
    t += fmt::format("G1 X{:.4f} Z{:.4f}\n", 8 * std::sin(deg_to_rad(k)), 8 * std::cos(deg_to_rad(k)) - 8);
  t += "G0 X10\nM2\n";
  DiagnosticSink sink("lathe");
  const CompressResult r = compressed(t, sink, "linuxcnc");
  CHECK(r.stats.moves_in == 91);  // the plunge and the quarter circle
  CHECK(r.stats.arcs_out >= 1);
  CHECK(r.stats.arcs_out + r.stats.lines_out <= 2);
  CHECK(r.stats.plane_words_added == 0);  // the program's own G18
  CHECK(count_of(r.output, std::regex("^G[23] X[-0-9.]+ Z[-0-9.]+ I[-0-9.]+ K[-0-9.]+")) == r.stats.arcs_out);
  CHECK(r.output.find('Y') == std::string::npos);
}

TEST_CASE("a lathe program in diameter mode (G7) is left as it is, and --stats says why", "[api][lathe]") {
  std::string t = "G21 G18 G7 G90\nG0 X0 Z1\nG1 Z0 F50\n";
  for (int k = 1; k <= 30; ++k)
    t += fmt::format("G1 X{:.4f} Z{:.4f}\n", 16 * std::sin(deg_to_rad(k)), 8 * std::cos(deg_to_rad(k)) - 8);
  DiagnosticSink sink("lathe-g7");
  const CompressResult r = compressed(t, sink, "linuxcnc");
  CHECK(r.output == t);
  REQUIRE_FALSE(r.not_fitted.empty());
  CHECK(r.not_fitted[0].why == Unfit::DiameterMode);
  CHECK(r.not_fitted[0].moves == 31);
  CHECK(r.not_fitted[0].first_line == 3);
}

TEST_CASE("a printer program that retracts in firmware (G10/G11) between its curves is fitted on both sides",
          "[api][printer]") {
  // Two circles of 10 mm radius, each in 72 moves, a travel between them under G10/G11.
  auto circle = [](double cx, double e0) {
    std::string t;
    for (int k = 1; k <= 72; ++k) {
      const double a = deg_to_rad(5.0 * k);
      t += fmt::format("G1 X{:.3f} Y{:.3f} E{:.5f}\n", cx + 10 * std::cos(a), 10 * std::sin(a), e0 + 0.03 * k);
    }
    return t;
  };
  const std::string t = "G21 G90 M82\nG28\nG0 X10 Y0 Z0.2 F6000\nG1 F1200\n" + circle(0, 0) +
                        "G10\nG0 X40 Y0 F6000\nG11\nG1 F1200\n" + circle(30, 2.16) + "M84\n";
  DiagnosticSink sink("t.gcode");
  const CompressResult r = compressed(t, sink, "marlin");
  CHECK(sink.format_all().empty());
  CHECK(r.stats.moves_in == 144);
  CHECK(r.stats.arcs_out >= 4);  // each circle in arcs of at most 180 degrees
  CHECK(r.stats.arcs_out + r.stats.lines_out <= 8);
  for (const auto& n : r.not_fitted) CHECK_FALSE(is_position_unknown(n.why));
  // Every other line is the input's own, in order.
  for (const char* kept : {"G10\n", "G0 X40 Y0 F6000\nG11\nG1 F1200\n", "M84\n"})
    CHECK(r.output.find(kept) != std::string::npos);
}

TEST_CASE("a Klipper print with relative extrusion is fitted between the host commands that forget its position",
          "[api][printer]") {
  // Klipper's EXCLUDE_OBJECT_START/END around each of two circles of 40 mm radius in 360
  // moves (Klipper's 1 mm chords lie 0.003 mm inside), E relative (M83) in steps of 0.03: after each host command the first move comes
  // from an unknown position, and E there is the sum of the words before it, which the
  // output's arcs sum in other groups: the doubles differ in their last bits.
  auto circle = [](double cx) {
    std::string t;
    for (int k = 1; k <= 360; ++k) {
      const double a = deg_to_rad(k);
      t += fmt::format("G1 X{:.3f} Y{:.3f} E0.03\n", cx + 40 * std::cos(a), 40 * std::sin(a));
    }
    return t;
  };
  const std::string t = "G21 G90 M83\nG28\nG0 X40 Y0 Z0.2 F6000\nG1 F1200\n"
                        "EXCLUDE_OBJECT_START NAME=a\nG1 X40 Y0 E0.01\n" + circle(0) +
                        "EXCLUDE_OBJECT_END NAME=a\nG0 X140 Y0 F6000\nEXCLUDE_OBJECT_START NAME=b\nG1 X140 Y0 E0.01 F1200\n" +
                        circle(100) + "EXCLUDE_OBJECT_END NAME=b\nM84\n";
  DiagnosticSink sink("t.gcode");
  const CompressResult r = compressed(t, sink, "klipper");
  CHECK(r.runs_kept_as_input == 0);
  CHECK(r.stats.arcs_out >= 4);  // each circle in arcs of at most 180 degrees
  CHECK(r.stats.arcs_out + r.stats.lines_out <= 8);
  // The moves from an unknown position are the input's own, as is every other line.
  for (const char* kept : {"EXCLUDE_OBJECT_START NAME=a\nG1 X40 Y0 E0.01\n",
                           "EXCLUDE_OBJECT_END NAME=a\nG0 X140 Y0 F6000\nEXCLUDE_OBJECT_START NAME=b\nG1 X140 Y0 E0.01 F1200\n",
                           "EXCLUDE_OBJECT_END NAME=b\nM84\n"})
    CHECK(r.output.find(kept) != std::string::npos);
}

TEST_CASE("a laser contour with S on every move is fitted with arcs that carry its S, never across an S change",
          "[api][laser]") {
  // Grbl laser mode: a circle of radius 10 mm in 2° steps, S300 on the first half's moves,
  // S500 on the second's.
  std::string t = "G21 G90\nG0 X10 Y0\nM4 S0\n";
  for (int k = 1; k <= 180; ++k)
    t += fmt::format("G1 X{:.4f} Y{:.4f} F1200 S{}\n", 10 * std::cos(deg_to_rad(2 * k)), 10 * std::sin(deg_to_rad(2 * k)),
                     k <= 90 ? 300 : 500);
  t += "M5\nM2\n";
  DiagnosticSink sink("laser");
  const CompressResult r = compressed(t, sink, "grbl");
  CHECK(r.stats.moves_in == 180);
  CHECK(r.stats.arcs_out >= 2);
  CHECK(r.stats.arcs_out + r.stats.lines_out <= 6);
  // Every new block carries the S of the moves it replaces; S500 starts where the input's does.
  CHECK(count_of(r.output, std::regex("^G[123] .* S300$")) + count_of(r.output, std::regex("^G[123] .* S500$")) ==
        r.stats.arcs_out + r.stats.lines_out);
  CHECK(count_of(r.output, std::regex("^G[123] .* S300$")) >= 1);
  CHECK(count_of(r.output, std::regex("^G[123] .* S500$")) >= 1);
  CHECK(count_of(r.output, std::regex("X-10(\\.0+)? Y0(\\.0+)? .*S300$")) == 1);  // the half turn ends at S300's last move
}

TEST_CASE("the G1 moves left as they are are counted by reason, with the first line of each", "[api][stats]") {
  const std::string t =
      "G21 G90\nG0 X0 Y0 Z0\nG1 X1 F100\nG1 X2\nG1 X3 (comment)\nG1 X4\nG1 X[#1]\nG1 X6\nG1 X7\nG93\nG1 X8 F2\nG94\n";
  DiagnosticSink sink("t.nc");
  const CompressResult r = compressed(t, sink);
  CHECK(r.g1_moves == 8);
  CHECK(r.stats.moves_in == 2);  // X1 X2
  auto group = [&](Unfit why) {
    for (const NotFitted& n : r.not_fitted)
      if (n.why == why) return n;
    return NotFitted{};
  };
  CHECK(group(Unfit::Comment).moves == 1);
  CHECK(group(Unfit::Comment).first_line == 5);
  CHECK(group(Unfit::None).moves == 2);  // X4 and X7, each alone beside moves that are no run
  CHECK(group(Unfit::None).first_line == 6);
  CHECK(group(Unfit::UnknownAfterExpression).moves == 2);  // X[#1], and X6 from where it left X
  CHECK(group(Unfit::UnknownAfterExpression).first_line == 7);
  CHECK(group(Unfit::UnknownAfterExpression).cause_line == 7);
  CHECK(group(Unfit::InverseTime).moves == 1);
  CHECK(group(Unfit::InverseTime).first_line == 11);
}

TEST_CASE("a program with G1 moves of which none could be fitted gets one warning saying why", "[api][stats]") {
  std::string t = "G21 G90\n#1=2\nG0 X0 Y0 Z[#1]\n";
  for (int k = 1; k <= 20; ++k) t += fmt::format("G1 X{} Y[#1*{}] F100\n", k, k);
  DiagnosticSink sink("t.nc");
  const CompressResult r = compressed(t, sink);
  CHECK(r.stats.moves_in == 0);
  CHECK(sink.warning_count("W-FIT-NONE") == 1);
  const std::string said = sink.format_all();
  CHECK(said.find("t.nc:4:1: warning: W-FIT-NONE: none of the 20 G1 moves could be fitted") != std::string::npos);
  // Nothing is said where something was fitted.
  DiagnosticSink quiet("2d");
  compressed(bezier_program(""), quiet);
  CHECK(quiet.warning_count("W-FIT-NONE") == 0);
}

TEST_CASE("a run too far from the origin for the check to measure is written as the input's moves, and the rest is "
          "still compressed",
          "[api][fallback]") {
  // Two circles of radius 5 mm: one at the origin, one at X -1e15, where a double holds a
  // coordinate to 0.125 mm and no fitted arc could be measured inside a 0.01 mm band.
  std::string t = "G21 G90\nG0 X5 Y0 Z0\nG1 F600\n";
  for (int i = 1; i < 300; ++i)
    t += fmt::format("G1 X{:.4f} Y{:.4f}\n", 5 * std::cos(kPi * i / 75), 5 * std::sin(kPi * i / 75));
  t += "G0 Z5\nG0 X-999999999999995 Y0\nG1 Z0\n";
  for (int i = 1; i < 300; ++i)
    t += fmt::format("G1 X{:.6f} Y{:.6f}\n", -1e15 + 5 * std::cos(kPi * i / 75) + 1e-6 * ((i * 7) % 3 - 1),
                     5 * std::sin(kPi * i / 75) + 1e-6 * ((i * 5) % 3 - 1));
  t += "M2\n";
  CompressOptions opt;
  DiagnosticSink sink("t.nc");
  const CompressResult r = compress("t.nc", t, opt, sink);
  REQUIRE(r.ok);
  REQUIRE(r.verified);
  CHECK(r.within_band());
  CHECK(r.runs_kept_as_input == 0);  // never fitted, so never refused
  REQUIRE(r.not_fitted.size() == 1);
  CHECK(r.not_fitted.front().why == Unfit::FarFromOrigin);
  CHECK(r.not_fitted.front().moves == 300);
  CHECK(r.stats.arcs_out >= 2);  // the circle at the origin
  // The far circle's moves are the input's own lines, byte for byte.
  const std::string far = t.substr(t.find("G1 Z0\n"));
  CHECK(r.output.find(far) != std::string::npos);
}

namespace {

/// A circle of 1 inch radius in 48 G1 moves, written in inches with no G20 (`units_word`
/// before the first move, where given): each chord lies 0.0021 in (0.054 mm) inside the
/// circle through its ends, within a 0.01 band only if the numbers are read as mm.
std::string inch_circle(const std::string& units_word) {
  std::string t = units_word + "G90 G17\nG0 X1 Y0\nG1 F20\n";
  for (int k = 1; k <= 48; ++k)
    t += fmt::format("G1 X{:.4f} Y{:.4f}\n", std::cos(k * 2 * M_PI / 48), std::sin(k * 2 * M_PI / 48));
  return t + "M2\n";
}

CompressResult compressed_in(const std::string& text, DiagnosticSink& sink, StartUnits units) {
  CompressOptions opt;
  opt.fit.tolerance_mm = 0.01;
  opt.dialect.start_units = units;
  CompressResult r = compress("t.nc", text, opt, sink);
  REQUIRE(r.ok);
  REQUIRE(r.within_band());
  return r;
}

}  // namespace

TEST_CASE("a program that gives lengths before G20 or G21 is read in the units its controller starts in, and where "
          "that is the machine's own setting a warning says so",
          "[api][units]") {
  Dialect inch_start;
  inch_start.start_units = StartUnits::Inch;
  DiffOptions band;
  band.tolerance_mm = 0.01;
  SECTION("read as millimetres where the controller starts in inches, the chords' 0.054 mm pass for 0.0021 mm") {
    DiagnosticSink sink("t.nc");
    const CompressResult r = compressed_in(inch_circle(""), sink, StartUnits::Machine);
    CHECK(sink.warning_count("W-MODEL-UNITS") == 1);
    CHECK(sink.format_all().find("t.nc:2:4: warning: W-MODEL-UNITS") != std::string::npos);
    CHECK(r.stats.arcs_out > 0);
    // On a machine that starts in inches, that output leaves the band 5 times over.
    const ProgramDiff d = test::diff_texts(inch_circle(""), r.output, band, inch_start);
    CHECK_FALSE(d.agrees(0.01));
    CHECK(d.max_deviation_mm > 0.05);
  }
  SECTION("read in inches, nothing is fitted, the band holds, and nothing is warned of") {
    DiagnosticSink sink("t.nc");
    const CompressResult r = compressed_in(inch_circle(""), sink, StartUnits::Inch);
    CHECK(sink.warning_count("W-MODEL-UNITS") == 0);
    CHECK(r.stats.arcs_out == 0);
    CHECK(test::diff_texts(inch_circle(""), r.output, band, inch_start).agrees(0.01));
  }
  SECTION("a program that states its units is read in them, whatever the start, and is not warned of") {
    for (StartUnits start : {StartUnits::Mm, StartUnits::Inch, StartUnits::Machine}) {
      DiagnosticSink sink("t.nc");
      const CompressResult r = compressed_in(inch_circle("G20\n"), sink, start);
      CHECK(sink.warning_count("W-MODEL-UNITS") == 0);
      CHECK(r.stats.arcs_out == 0);
      DiagnosticSink metric("t.nc");
      CHECK(compressed_in(inch_circle("G21\n"), metric, start).stats.arcs_out > 0);
      CHECK(metric.warning_count("W-MODEL-UNITS") == 0);
    }
  }
  SECTION("printer firmwares start in millimetres: their dialects say so, and nothing is warned of") {
    for (const char* name : {"marlin", "klipper", "prusa", "prusa-mk3", "reprapfirmware", "smoothieware"}) {
      INFO(name);
      DiagnosticSink sink("t.nc");
      CHECK(load_dialect_file(ARCPRESS_SOURCE_DIR "/dialects/" + std::string(name) + ".toml").start_units ==
            StartUnits::Mm);
      compressed(inch_circle(""), sink, name);
      CHECK(sink.warning_count("W-MODEL-UNITS") == 0);
    }
  }
}

TEST_CASE("after a tool change (M6) the tool is where the controller left it: the first move after it is kept as it "
          "is, and what follows is fitted from its end",
          "[api][toolchange]") {
  // A quarter circle cut after a tool change, whose first G1 starts from wherever the tool
  // change left the tool (LinuxCNC re-reads its position after M6).
  std::string program = "G21 G90 G17\nT1 M6\nG0 X10 Y0 Z1\nG1 Z-1 F300\nT2 M6\n";
  for (int k = 1; k <= 180; ++k)
    program += fmt::format("G1 X{:.4f} Y{:.4f}\n", 10 * std::cos(k * M_PI / 180), 10 * std::sin(k * M_PI / 180));
  program += "M2\n";
  DiagnosticSink sink("t.nc");
  const CompressResult r = compressed(program, sink, "linuxcnc");
  CHECK(r.stats.arcs_out > 0);
  REQUIRE_FALSE(r.not_fitted.empty());
  bool told = false;
  for (const NotFitted& n : r.not_fitted)
    if (n.why == Unfit::UnknownAfterToolChange) told = n.first_line == 6 && n.cause_line == 5 && n.moves == 1;
  CHECK(told);
  const size_t after = r.output.find("T2 M6\n") + 6;
  CHECK(r.output.compare(after, 21, "G1 X9.9985 Y0.1745\nG3") == 0);
  // Where the controller parks the tool for the change, both programs move the same from it.
  auto parked = [](std::string text) { return text.replace(text.find("T2 M6\n"), 6, "T2 M6\nG0 X0 Y0 Z50\n"); };
  DiffOptions band;
  band.tolerance_mm = 0.01;
  const ProgramDiff d = test::diff_texts(parked(program), parked(r.output), band);
  CHECK(d.same(0.01));
}

TEST_CASE("moves in polar coordinates (G16) are kept as they are, and a check of them is never a pass", "[api][polar]") {
  // A quarter circle of radius 10 mm in Fanuc's polar coordinates (X the radius, Y the
  // angle): read as X and Y, a straight line, which one G1 would replace, cutting across.
  std::string program = "G21 G90 G17\nG0 X10 Y0 Z1\nG1 Z-1 F300\nG16\n";
  for (int k = 1; k <= 180; ++k) program += fmt::format("G1 X10. Y{:.3f}\n", k * 0.5);
  const std::string after = "G15\nG0 X0 Y0\nG1 X5 Y0\nG1 X5.5 Y0.1\nG1 X6 Y0\nM30\n";
  DiagnosticSink sink("t.nc");
  CompressOptions opt;
  opt.fit.tolerance_mm = 0.01;
  opt.dialect = load_dialect_file(ARCPRESS_SOURCE_DIR "/dialects/fanuc.toml");
  const CompressResult r = compress("t.nc", program + after, opt, sink);
  REQUIRE(r.ok);
  CHECK(r.output == program + after);
  bool told = false;
  for (const NotFitted& n : r.not_fitted) told = told || (n.why == Unfit::UnknownInPolar && n.moves == 180);
  CHECK(told);
  // The chord in place of the arc: never SAME.
  DiffOptions band;
  band.tolerance_mm = 0.01;
  const std::string chord = "G21 G90 G17\nG0 X10 Y0 Z1\nG1 Z-1 F300\nG16\nG1 X10. Y0.5\nG1 X10. Y90.\n" + after;
  const ProgramDiff d = test::diff_texts(program + after, chord, band, opt.dialect);
  CHECK_FALSE(d.same(0.01));
  CHECK(d.a.unplaced_feed_moves == 180);
  // After G15 the plane's words are X and Y again, placed once both are written.
  const ProgramDiff back = test::diff_texts(after, after, band, opt.dialect);
  CHECK(back.same(0.01));
}
