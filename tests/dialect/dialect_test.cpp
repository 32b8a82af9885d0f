// SPDX-License-Identifier: GPL-3.0-or-later
// Dialects as data: every shipped file loads, mistakes in a file are reported with their
// place, and every dialect writes arcs its controller reads back inside the band and its
// own rules. Outputs are checked by re-reading them (interpreter + verifier), not by text
// alone.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cstdlib>
#include <regex>
#include <sstream>

#include "arcpress/arcpress.hpp"
#include "arcpress/core/error.hpp"
#include "arcpress/dialect/dialect_loader.hpp"
#include "arcpress/dialect/program_flavor.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"
#include "arcpress/platform/platform.hpp"
#include "dialect/snippets.hpp"
#include "random_program.hpp"
#include "support.hpp"

using namespace arcpress;

namespace {

const std::vector<std::string> kShipped = {"rs274",   "linuxcnc", "fanuc",  "haas",  "haas-lathe", "mach3",
                                           "mach4",   "grbl",     "grblhal", "siemens", "heidenhain-iso",
                                           "okuma",   "marlin",   "klipper", "reprapfirmware",
                                           "smoothieware", "prusa", "prusa-mk3", "sinumerik"};

std::vector<std::string> source_dialect_path() { return {ARCPRESS_SOURCE_DIR "/dialects"}; }

Dialect shipped(const std::string& name) { return find_dialect(name, source_dialect_path()); }

std::string error_of(const std::string& toml) {
  try {
    parse_dialect(toml, "user.toml");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

CompressResult compress_as(const Dialect& d, const std::string& text, double tol = 0.01,
                           std::optional<ArcFormat> format = std::nullopt,
                           CompressOptions::Band band = CompressOptions::Band::Dialect) {
  DiagnosticSink sink;
  CompressOptions opt;
  opt.dialect = d;
  opt.band = band;
  opt.fit.tolerance_mm = tol;
  opt.arc_format = format;
  return compress("snippet.nc", text, opt, sink);
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

/// A block arcpress wrote for an arc: it has centre or radius words.
bool is_arc_line(const std::string& l) { return std::regex_search(l, std::regex("(^|\\s)[IJKR]-?[\\d.]")); }

/// Largest difference between start and end radius of the arcs in `text`, as `d`'s
/// controller reads the printed numbers, relative to what `d` allows for that radius.
double worst_radius_error_share(const Dialect& d, const std::string& text) {
  DiagnosticSink sink;
  Program p = lex("out", text, sink);
  Interpretation in = interpret(p, sink, d);
  double worst = 0;
  for (size_t i = 0; i < in.moves.size(); ++i) {
    const Move& m = in.moves[i];
    if (m.kind != MoveKind::ArcCW && m.kind != MoveKind::ArcCCW) continue;
    Vec2 c = project(m.center, m.plane);
    const AxisValues& f = in.from(i);
    Vec2 s = project(Vec3(f[kX], f[kY], f[kZ]), m.plane), e = project(m.xyz(), m.plane);
    double rs = (s - c).norm(), dr = std::abs(rs - (e - c).norm());
    worst = std::max(worst, dr / d.radius_allowance_mm(rs));
  }
  return worst;
}

}  // namespace

TEST_CASE("every shipped dialect loads from dialects/ and names itself after its file", "[dialect]") {
  for (const auto& name : kShipped) {
    INFO(name);
    Dialect d = shipped(name);
    CHECK(d.name == name);
    CHECK_FALSE(d.description.empty());
  }
  CHECK(list_dialects(source_dialect_path()).size() == kShipped.size());
}

TEST_CASE("rs274.toml spells out exactly the built-in default dialect", "[dialect]") {
  Dialect file = shipped("rs274"), builtin;
  CHECK(file.description == builtin.description);
  CHECK(file.arcs == builtin.arcs);
  CHECK(file.centre == builtin.centre);
  CHECK(file.radius_word == builtin.radius_word);
  CHECK(file.format == builtin.format);
  CHECK(file.planes == builtin.planes);
  CHECK(file.helical == builtin.helical);
  CHECK(file.extra_axes == builtin.extra_axes);
  CHECK(file.relative_arcs == builtin.relative_arcs);
  CHECK(file.max_sweep_deg == builtin.max_sweep_deg);
  CHECK(file.min_sweep_deg == builtin.min_sweep_deg);
  CHECK(file.max_radius_mm == builtin.max_radius_mm);
  CHECK(file.radius_abs_mm == builtin.radius_abs_mm);
  CHECK(file.radius_rel == builtin.radius_rel);
  CHECK(file.mm.centre == builtin.mm.centre);
  CHECK(file.mm.max == builtin.mm.max);
  CHECK(file.inch.centre == builtin.inch.centre);
  CHECK(file.decimal_point == builtin.decimal_point);
  CHECK(file.max_line_length == builtin.max_line_length);
  CHECK(file.refused == builtin.refused);
  CHECK(file.start_units == builtin.start_units);
  CHECK(file.centre_modal == builtin.centre_modal);
  CHECK(file.codes.empty());
}

TEST_CASE("a mistake in a dialect file is reported with the file, line, column and key", "[dialect]") {
  CHECK(error_of("name = \"x\"\n[arcs]\nmax_sweep = 90\n") == "user.toml:3:1: arcs.max_sweep: unknown key");
  CHECK(error_of("name = \"x\"\n[arcs]\nmax_sweep_deg = \"90\"\n") ==
        "user.toml:3:17: arcs.max_sweep_deg: expected a number");
  CHECK(error_of("name = \"x\"\n[arcs]\nmax_sweep_deg = 400\n") ==
        "user.toml:3:17: arcs.max_sweep_deg: 400 is outside 1 .. 359");
  CHECK(error_of("name = \"x\"\n[arcs]\nplanes = [\"G17\", \"XY\"]\n") ==
        "user.toml:3:18: arcs.planes: \"XY\" is not one of \"G17\", \"G18\", \"G19\"");
  CHECK(error_of("name = \"x\"\n[lines]\nmax_length = 80.5\n") ==
        "user.toml:3:14: lines.max_length: expected a whole number");
  CHECK(error_of("name = \"x\"\n[arcs\n").rfind("user.toml:2:", 0) == 0);  // TOML syntax, from toml++
  CHECK(error_of("name = \"x\"\n[arcs]\nradius_word = false\nformat = \"radius\"\n") ==
        "user.toml:2:1: arcs.format: \"radius\" needs radius_word = true");
  CHECK(error_of("name = \"x\"\n[startup]\nunits = \"inches\"\n") ==
        "user.toml:3:9: startup.units: expected one of \"mm\", \"inch\", \"machine\"");
  CHECK(error_of("name = \"x\"\n").empty());
}

TEST_CASE("an unknown dialect name lists the known ones", "[dialect]") {
  try {
    find_dialect("fanuk", source_dialect_path());
    FAIL("no error");
  } catch (const Error& e) {
    std::string what = e.what();
    CHECK(what.find("unknown dialect 'fanuk'") != std::string::npos);
    CHECK(what.find("fanuc") != std::string::npos);
    CHECK(e.exit_code() == kExitInput);
  }
}

TEST_CASE("every dialect writes the arc snippets so that its controller reads them inside the band and its rules",
          "[dialect]") {
  for (const auto& name : kShipped) {
    Dialect d = shipped(name);
    std::vector<std::optional<ArcFormat>> formats{std::nullopt};
    if (d.radius_word) formats.push_back(ArcFormat::Radius);
    for (const auto& format : formats) {
      for (const auto& s : test::arc_snippets()) {
        INFO(fmt::format("{} / {} / {}", name, s.name, format ? "R" : "default"));
        CompressResult r = compress_as(d, s.text, 0.01, format);
        REQUIRE(r.ok);
        // Read back with the dialect's own reading of centres, directions and numbers.
        REQUIRE(r.verified);
        INFO(r.comparison.mismatch << "\n" << r.output);
        CHECK(r.comparison.matched);
        CHECK(r.comparison.max_deviation_mm <= 0.01);
        CHECK(worst_radius_error_share(d, r.output) <= 1.0);
        // (Where X words are diameters, moves are read and compared, not fitted.)
        bool arcs_allowed = d.plane_allowed(s.plane) && (d.helical || !s.helical) && !d.diameter_x;
        CHECK((r.stats.arcs_out > 0) == arcs_allowed);
        for (const auto& l : lines_of(r.output)) {
          CHECK(l.size() <= d.max_line_length);
          if (!is_arc_line(l)) continue;
          for (const auto& code : d.refused) CHECK(l.find(code) == std::string::npos);
          if (d.decimal_point) {  // "X1." : no number without its point
            CHECK_FALSE(std::regex_search(l, std::regex("[XYZIJKRABCUVWEF]-?\\d+(\\s|$)")));
          }
          if (format == ArcFormat::Radius)
            CHECK((l.find(" R") != std::string::npos || l.find(" I") != std::string::npos));
          else
            CHECK(l.find(" R") == std::string::npos);
        }
      }
    }
  }
}

TEST_CASE("golden: a quarter circle in generic RS274, I/J from the start", "[dialect]") {
  CompressResult r = compress_as(shipped("rs274"), test::arc_snippets()[0].text);
  CHECK(r.output == "G21 G90 G17\nG0 X10. Y0. Z0.\nG3 X0. Y10. Z0. I-10.0029 J-0.0029 F300.\nM30\n");
  CHECK(r.within_band());
}

TEST_CASE("golden: R form gives the radius, and I/J where R would be ambiguous (180 degrees)", "[dialect]") {
  CompressResult q = compress_as(shipped("rs274"), test::arc_snippets()[0].text, 0.01, ArcFormat::Radius);
  CHECK(q.output == "G21 G90 G17\nG0 X10. Y0. Z0.\nG3 X0. Y10. Z0. R10.0029 F300.\nM30\n");
  CHECK(q.within_band());
  CompressResult full = compress_as(shipped("rs274"), test::arc_snippets()[1].text, 0.01, ArcFormat::Radius);
  CHECK(full.output.find("G3 X-10. Y0. Z0. I-10. J-0.0029") != std::string::npos);
  CHECK(full.within_band());
}

TEST_CASE("golden: Heidenhain ISO writes the absolute centre in I/J", "[dialect]") {
  CompressResult r = compress_as(shipped("heidenhain-iso"), test::arc_snippets()[0].text);
  CHECK(r.output == "G21 G90 G17\nG0 X10. Y0. Z0.\nG3 X0. Y10. Z0. I-0.0029 J-0.0029 F300.\nM30\n");
  CHECK(r.within_band());
}

namespace {

/// A Heidenhain ISO program, in `units` (G70 or G71): the blank, a tool call, then a circle of
/// radius `r` about (50, 50) in `moves` G01 blocks, each ended with '*' and numbered by 10s.
std::string heidenhain_circle(const char* units, double r, int moves) {
  std::string t = fmt::format("%CIRC {} *\nN10 G30 G17 X+0 Y+0 Z-20 *\nN20 G31 G90 X+100 Y+100 Z+0 *\n"
                              "N30 T1 G17 S3000 *\nN40 G00 G90 X{:+.4f} Y+50 Z+2 M3 *\nN50 G01 Z-5 F200 *\n",
                              units, 50 + r);
  int n = 60;
  for (int k = 1; k <= moves; ++k, n += 10)
    t += fmt::format("N{} G01 X{:+.4f} Y{:+.4f} F800 *\n", n, 50 + r * std::cos(2 * M_PI * k / moves),
                     50 + r * std::sin(2 * M_PI * k / moves));
  return t + fmt::format("N{} G00 Z+100 M2 *\nN99999999 %CIRC {} *\n", n, units);
}

}  // namespace

TEST_CASE("a Heidenhain ISO program is fitted, its new blocks numbered, signed and ended with a star as its own are, "
          "in the units its first block states",
          "[dialect][heidenhain]") {
  const Dialect tnc = shipped("heidenhain-iso");
  const std::string program = heidenhain_circle("G71", 10, 360);
  DiagnosticSink sink;
  CompressOptions opt;
  opt.dialect = tnc;
  opt.fit.tolerance_mm = 0.01;
  const CompressResult r = compress("circ.i", program, opt, sink);
  // (A star without a number read as a checksum had kept every move as it was.)
  CHECK(sink.warning_count("W-FIT-NONE") == 0);
  CHECK(sink.warning_count("W-MODEL-UNITS") == 0);  // G71 in the first block
  const std::vector<std::string> out = lines_of(r.output);
  REQUIRE(out.size() < 20);
  CHECK(out.front() == "%CIRC G71 *");
  CHECK(out.back() == "N99999999 %CIRC G71 *");
  size_t arcs = 0;
  long last_n = 0;
  for (const std::string& l : out) {
    INFO(l);
    CHECK(l.substr(l.size() - 2) == " *");
    std::smatch n;
    if (std::regex_search(l, n, std::regex("^N(\\d+) ")) && l.find('%') == std::string::npos) {
      CHECK(std::stol(n[1]) > last_n);  // numbers still ascend
      last_n = std::stol(n[1]);
    }
    if (!is_arc_line(l) && l.find(" I+") == std::string::npos) continue;
    ++arcs;
    // The absolute centre, every number signed as the program signs its own.
    CHECK(std::regex_match(l, std::regex("N\\d+ G0[23] X\\+[\\d.]+ Y\\+[\\d.]+ I\\+[\\d.]+ J\\+[\\d.]+ F800 \\*")));
  }
  CHECK(arcs >= 2);
  DiffOptions band;
  band.tolerance_mm = 0.01;
  CHECK(test::diff_texts(program, r.output, band, tnc).same(0.01));

  // In inches (G70), a circle of 1 inch radius in 48 moves has chords 0.054 mm inside it: no
  // arc of it lies within 0.01 mm. The same numbers in millimetres fit as two arcs.
  const CompressResult inch = compress("inch.i", heidenhain_circle("G70", 1, 48), opt, sink);
  const CompressResult mm = compress("mm.i", heidenhain_circle("G71", 1, 48), opt, sink);
  CHECK(inch.output == heidenhain_circle("G70", 1, 48));
  const std::vector<std::string> mm_lines = lines_of(mm.output);
  CHECK(std::count_if(mm_lines.begin(), mm_lines.end(), [](const std::string& l) { return l.find(" I+") != std::string::npos; }) >= 1);
  CHECK(mm_lines.size() < 12);
}

TEST_CASE("Heidenhain ISO's own codes: the blank form and a tool definition move nothing, a datum shift's words are "
          "the shift, a tool call and a machine-datum block leave the position to be given again",
          "[dialect][heidenhain]") {
  const std::string text =
      "%P G71 *\n"
      "N10 G30 G17 X+0 Y+0 Z-20 *\n"   // the blank's corners: no reference return, no skip move
      "N20 G31 G90 X+100 Y+100 Z+0 *\n"
      "N30 G00 X+5 Y+5 Z+2 *\n"         // move 0
      "N40 G01 Z-1 F100 *\n"
      "N50 G01 X+6 *\n"                 // move 2: from (5, 5, -1)
      "N60 G54 X+20 Y+30 Z+0 *\n"       // a datum shift, not a move
      "N70 G01 X+7 Y+7 Z-1 *\n"         // move 3: it starts where the shift left the tool: not known
      "N80 G01 X+8 *\n"                 // move 4: known again
      "N90 G99 T3 L+0 R+2 *\n"          // a tool's definition: no tool call
      "N100 G01 X+9 *\n"                // move 5: known
      "N110 T3 G17 S1000 *\n"           // the tool call
      "N120 G01 X+9 Y+9 Z-1 *\n"        // move 6: not known
      "N130 G01 X+10 *\n"               // move 7
      "N140 G00 Z+50 M91 *\n"           // move 8: Z in machine coordinates
      "N150 G01 X+10 Y+10 Z-1 *\n"      // move 9: not known
      "N160 G01 X+11 *\n"               // move 10
      "N99999999 %P G71 *\n";
  DiagnosticSink sink("p.i");
  const Program p = lex("p.i", text, sink);
  const Interpretation in = interpret(p, sink, shipped("heidenhain-iso"));
  REQUIRE(in.moves.size() == 11);
  CHECK(in.moves[1].known);
  CHECK(in.moves[2].known);
  CHECK(in.moves[2].to[kX] == 6);
  CHECK(in.moves[2].to[kZ] == -1);
  CHECK_FALSE(in.moves[3].known);
  CHECK(in.moves[3].unfit == Unfit::UnknownAfterOffset);
  CHECK(in.moves[4].known);
  CHECK(in.moves[5].known);
  CHECK_FALSE(in.moves[6].known);
  CHECK(in.moves[6].unfit == Unfit::UnknownAfterToolChange);
  CHECK(in.moves[7].known);
  CHECK_FALSE(in.moves[9].known);
  CHECK(in.moves[9].unfit == Unfit::UnknownAfterMachine);
  CHECK(in.moves[10].known);
  CHECK(sink.all().empty());
  // Read as RS274 reads the same codes, the blank's corners and the shift are moves.
  DiagnosticSink rs("p.i");
  CHECK(interpret(p, rs, shipped("rs274")).moves.size() == 14);
}

TEST_CASE("Heidenhain ISO's pole: I/J alone set it and move nothing, an arc without I/J turns about it, and after "
          "arcs arcpress wrote the program's own arc states it again",
          "[dialect][heidenhain]") {
  const Dialect tnc = shipped("heidenhain-iso");
  // The pole at (50, 50), set once: half a circle about it; then, `passes` times, a whole
  // circle of short moves about (35, 50), which arcpress writes as arcs about their own
  // centre, and the other half about the pole, whose block names no centre.
  auto program = [](int passes) {
    std::string t = "%POLE G71 *\nN10 G00 G90 X+60 Y+50 Z+2 *\nN20 G01 Z-5 F200 *\nN30 I+50 J+50 *\n"
                    "N40 G03 X+40 Y+50 F800 *\n";
    int n = 50;
    for (int pass = 0; pass < passes; ++pass) {
      for (int k = 1; k <= 360; ++k, n += 10)
        t += fmt::format("N{} G01 X{:+.3f} Y{:+.3f} *\n", n, 35 + 5 * std::cos(2 * M_PI * k / 360),
                         50 + 5 * std::sin(2 * M_PI * k / 360));
      t += fmt::format("N{} G00 Z+2 *\nN{} X+60 Y+50 *\nN{} G01 Z-5 *\nN{} G03 X+40 Y+50 *\n", n, n + 10, n + 20, n + 30);
      n += 40;
    }
    return t + fmt::format("N{} G00 Z+100 M2 *\nN99999999 %POLE G71 *\n", n);
  };
  const std::string text = program(1);
  {
    DiagnosticSink sink("p.i");
    const Program p = lex("p.i", text, sink);
    const Interpretation in = interpret(p, sink, tnc);
    CHECK(sink.all().empty());
    REQUIRE(in.moves.size() == 2 + 1 + 360 + 4 + 1);
    // The block of I/J alone moved nothing; the arcs turn about the pole.
    CHECK(in.moves[2].kind == MoveKind::ArcCCW);
    CHECK(in.moves[2].known);
    const Move& last_arc = in.moves[2 + 1 + 360 + 3];
    CHECK(last_arc.kind == MoveKind::ArcCCW);
    CHECK(last_arc.known);
    CHECK(last_arc.center.x() == 50);
    CHECK(last_arc.center.y() == 50);
    REQUIRE(in.pole_reads.size() == 2);  // both arcs name no centre
    CHECK(in.pole_reads[1].arc);
    CHECK(in.pole_reads[1].known);
    CHECK(in.pole_reads[1].words[0] == 50);
  }
  DiffOptions band;
  band.tolerance_mm = 0.01;
  for (int passes : {1, 12}) {
    const std::string t = program(passes);
    INFO(passes << " passes, " << t.size() << " bytes");
    DiagnosticSink sink;
    CompressOptions opt;
    opt.dialect = tnc;
    opt.fit.tolerance_mm = 0.01;
    Compressor c("p.i", opt, sink);
    for (size_t at = 0; at < t.size(); at += 700) c.push(std::string_view(t).substr(at, 700));
    c.finish();
    std::string out;
    c.take(out);
    REQUIRE(c.result().within_band());
    if (passes > 1) REQUIRE(c.pieces() > 2);
    CHECK(lines_of(out).size() < size_t(20 * passes));
    // Each of the program's arcs after arcpress's own states the pole again, and nothing else.
    size_t restated = 0;
    for (size_t at = 0; (at = out.find(" G03 X+40 Y+50 I+50 J+50 *\n", at)) != std::string::npos; ++at) ++restated;
    CHECK(restated == size_t(passes));
    CHECK(test::diff_texts(t, out, band, tnc).same(0.01));
    // Without the pole stated again, the arcs would turn about arcpress's own last centre.
    std::string moved = out;
    for (size_t at; (at = moved.find(" I+50 J+50 *\n")) != std::string::npos;) moved.replace(at, 10, "");
    CHECK_FALSE(test::diff_texts(t, moved, band, tnc).same(0.01));
  }
  // A polar move about the pole (its PR/PA words make it a line arcpress does not read) gets
  // the pole stated again in a block of its own before it.
  std::string polar = program(1);
  const std::string arc = "N3680 G03 X+40 Y+50 *";
  REQUIRE(polar.find(arc) != std::string::npos);
  polar.replace(polar.find(arc), arc.size(), "N3680 G11 PR+10 PA+0 *");
  DiagnosticSink sink;
  CompressOptions opt;
  opt.dialect = tnc;
  opt.fit.tolerance_mm = 0.01;
  const std::string out = compress("q.i", polar, opt, sink).output;
  CHECK(out.find("\nI+50 J+50 *\nN3680 G11 PR+10 PA+0 *\n") != std::string::npos);
  CHECK(sink.format_all().find("E-LEX-KEYWORD: unknown keyword 'PR'") != std::string::npos);
}

TEST_CASE("after Heidenhain's modal cycle call (M89) every move calls the cycle, so none is merged, until M99 or G79",
          "[dialect][heidenhain]") {
  // Holes in a row at X10 .. X50: each positioning block calls the drilling cycle G200
  // defined before (TNC 306/406 technical manual: "M89 is canceled by M99 or a CYCL
  // CALL-block"). Merged into one line, the holes between would not be drilled.
  const std::string text =
      "%DRILL G71 *\nN10 G00 G90 X+0 Y+0 Z+50 *\nN20 G01 Z+2 F1000 *\nN30 G200 Q200=+2 Q201=-10 Q206=+150 *\n"
      "N40 G01 X+10 Y+10 F3000 M89 *\nN50 X+20 *\nN60 X+30 *\nN70 X+40 *\nN80 X+50 M99 *\n"
      "N90 G00 Z+50 *\nN100 G01 X+60 Y+10 Z+2 *\nN110 X+70 *\nN120 X+80 *\nN130 X+90 *\nN140 G00 Z+100 M2 *\n"
      "N99999999 %DRILL G71 *\n";
  auto compressed = [&](const char* dialect) {
    DiagnosticSink sink;
    CompressOptions opt;
    opt.dialect = shipped(dialect);
    const CompressResult r = compress("d.i", text, opt, sink);
    CHECK(r.within_band());
    return r.output;
  };
  const std::string tnc = compressed("heidenhain-iso");
  for (const char* kept : {"\nN50 X+20 *\n", "\nN60 X+30 *\n", "\nN70 X+40 *\n"}) {
    INFO(kept);
    CHECK(tnc.find(kept) != std::string::npos);
  }
  // After M99 the moves are merged again.
  CHECK(tnc.find("\nN100 G01 X+60 Y+10 Z+2 *\nN130 X+90 *\n") != std::string::npos);
  // Read as RS274 reads M89 (a code of no meaning), the holes between were lost.
  CHECK(compressed("rs274").find("\nN60 X+30 *\n") == std::string::npos);
}

namespace {
/// A Heidenhain ISO program: a plunge, then 40 moves along an arc of radius 40 mm from
/// (0, 0) to (20, 0), then `after` (blocks, numbered from N450 on), then the end.
std::string tnc_arc_then(const std::string& after) {
  std::string t = "%ARC G71 *\nN10 G17 G90 *\nN20 G00 X+0 Y+0 Z+2 *\nN30 G01 Z-1 F300 *\n";
  const double cx = 10, cy = -std::sqrt(1500.0), a0 = std::atan2(-cy, -cx), a1 = std::atan2(-cy, 20 - cx);
  for (int i = 1; i <= 40; ++i) {
    const double a = a0 + (a1 - a0) * i / 40;
    t += fmt::format("N{} G01 X{:+.4f} Y{:+.4f} *\n", 30 + 10 * i, cx + 40 * std::cos(a), cy + 40 * std::sin(a));
  }
  return t + after + "N900 G00 Z+50 *\nN99999999 %ARC G71 *\n";
}
}  // namespace

TEST_CASE("the last move before a code arcpress does not model stays as the program wrote it, joined tangentially",
          "[dialect][heidenhain]") {
  // Heidenhain's chamfer (G24, only between two lines) and rounding (G25) take the block
  // before them and the one after; its tangential arc (G06) and departure (G27) go on along
  // the block before. An arc of arcpress's ending there, or a line along another chord,
  // changes what they make (a chamfer after an arc is refused). The last of the 40 moves is
  // N430 G01 X+20.0000 Y+0.0000 *.
  const std::string last = "N430 G01 X+20.0000 Y+0.0000 *\n";
  for (const char* code : {"N450 G24 R+2 *\nN460 G01 X+20 Y+20 *\n", "N450 G25 R+5 *\nN460 G01 X+20 Y+20 *\n",
                           "N450 G06 X+30 Y+20 *\n", "N450 G27 R+5 *\n"}) {
    INFO(code);
    const CompressResult r = compress_as(shipped("heidenhain-iso"), tnc_arc_then(code), 0.01);
    CHECK(test::broken_promise(r) == "");
    CHECK(r.output.find("\n" + last + code) != std::string::npos);
    CHECK(r.stats.arcs_out == 1);  // the other 39 moves: one arc, tangent to the line
  }
  // Without such a code after it, the move is part of the arc.
  const CompressResult plain = compress_as(shipped("heidenhain-iso"), tnc_arc_then("N450 G01 X+20 Y+20 *\n"), 0.01);
  CHECK(plain.output.find(last) == std::string::npos);
  CHECK(plain.stats.arcs_out == 1);
  // So does the move before a line arcpress does not understand at all (Sinumerik's
  // tangential arc, read in the ISO dialect).
  std::string iso = tnc_arc_then("");
  iso = iso.substr(iso.find("N10"), iso.find("N900") - iso.find("N10"));
  for (size_t at; (at = iso.find(" *")) != std::string::npos;) iso.erase(at, 2);
  const CompressResult sie = compress_as(shipped("siemens"), iso + "N450 CT X=IC(5) Y20\nM30\n", 0.01);
  CHECK(test::broken_promise(sie) == "");
  CHECK(sie.output.find("\nN430 G01 X+20.0000 Y+0.0000\nN450 CT") != std::string::npos);
  CHECK(sie.stats.arcs_out == 1);
}

TEST_CASE("Heidenhain ISO's G05 turns as the last arc programmed did, and after arcs of arcpress's is written with "
          "that arc's own code",
          "[dialect][heidenhain]") {
  const Dialect tnc = shipped("heidenhain-iso");
  // A clockwise G02, then 40 moves that turn counter-clockwise (which arcpress writes as a
  // G03), then a G05 arc of radius 20 mm, clockwise as the G02 was.
  std::string t = "%TURN G71 *\nN10 G17 G90 *\nN20 G00 X+0 Y+0 Z+2 *\nN30 G01 Z-1 F300 *\nN40 G02 X+10 Y+0 I+5 J+0 *\n";
  for (int i = 1; i <= 40; ++i) {
    const double a = (-90 + 60.0 * i / 40) * M_PI / 180;
    t += fmt::format("N{} G01 X{:+.4f} Y{:+.4f} *\n", 40 + 10 * i, 10 + 20 * std::cos(a), 20 + 20 * std::sin(a));
  }
  const std::string turn = "G05 X+0 Y+30 R+20 *\n";
  t += "N450 " + turn + "N460 G00 Z+50 *\nN99999999 %TURN G71 *\n";
  {
    DiagnosticSink sink("t.i");
    const Program p = lex("t.i", t, sink);
    const Interpretation in = interpret(p, sink, tnc);
    CHECK(sink.all().empty());
    REQUIRE(in.turn_reads.size() == 1);
    CHECK(in.turn_reads[0].turn == 2);
    CHECK(in.moves.back().kind == MoveKind::Rapid);
    CHECK(in.moves[in.moves.size() - 2].kind == MoveKind::ArcCW);  // the G05, read as the G02 before it
  }
  const CompressResult r = compress_as(tnc, t, 0.01);
  CHECK(test::broken_promise(r) == "");
  CHECK(r.stats.arcs_out == 1);
  CHECK(r.stats.turns_spelled == 1);
  CHECK(r.output.find("G03 X+27.3205 Y+10.0000") != std::string::npos);
  CHECK(r.output.find("\nN450 G02 X+0 Y+30 R+20 *\n") != std::string::npos);
  DiffOptions band;
  band.tolerance_mm = 0.01;
  CHECK(test::diff_texts(t, r.output, band, tnc).same(0.01));
  // Left as G05, it would turn as arcpress's G03 did.
  std::string left = r.output;
  left.replace(left.find("N450 G02"), 8, "N450 G05");
  CHECK_FALSE(test::diff_texts(t, left, band, tnc).same(0.01));
  // With no arc of arcpress's between, the program's G05 stays; where the program set no way
  // before it, it is not modelled, and said so.
  {
    DiagnosticSink sink;
    CompressOptions keep;
    keep.dialect = tnc;
    keep.fit.method = FitOptions::Method::Keep;
    CHECK(compress("t.i", t, keep, sink).output.find("\nN450 " + turn) != std::string::npos);
  }
  std::string unset = t;
  unset.replace(unset.find("N40 G02"), 7, "N40 G01");
  DiagnosticSink sink("u.i");
  const Program p = lex("u.i", unset, sink);
  const Interpretation in = interpret(p, sink, tnc);
  CHECK(sink.warning_count("W-MODEL-ARC-TURN") == 1);
  CHECK_FALSE(in.moves[in.moves.size() - 2].known);
  // An arc of arcpress's before it would decide its way: the moves before it are lines.
  const CompressResult lines = compress_as(tnc, unset, 0.01);
  CHECK(test::broken_promise(lines) == "");
  CHECK(lines.stats.arcs_out == 0);
  CHECK(lines.stats.lines_out < 40);  // still fewer than the 40 moves
}

TEST_CASE("Fanuc's and Haas's smoothing and look-ahead codes set nothing the path depends on, and Fanuc's modal "
          "macro call keeps every move it calls at",
          "[dialect]") {
  // 40 moves along 60 degrees of a circle of radius 20 mm, after a code of the controller's.
  auto program = [](const std::string& code) {
    std::string t = "%\nO1000\nG21 G17 G90 G40\nG0 X0. Y0.\nG43 Z5. H1\nG1 Z-1. F300.\n" + code + "\n";
    for (int i = 1; i <= 40; ++i) {
      const double a = (-90 + 60.0 * i / 40) * M_PI / 180;
      t += fmt::format("X{:.3f} Y{:.3f}\n", 10 + 20 * std::cos(a), 20 + 20 * std::sin(a));
    }
    return t + "G0 Z50.\nM30\n%\n";
  };
  // Fanuc's AI contour control (G05.1 Q1): read as RS274's quadratic spline, no move after it
  // was fitted.
  const CompressResult fanuc = compress_as(shipped("fanuc"), program("G05.1 Q1"), 0.01);
  CHECK(test::broken_promise(fanuc) == "");
  CHECK(fanuc.stats.moves_in == 40);
  CHECK(fanuc.stats.arcs_out >= 1);
  CHECK(fanuc.output.find("\nG05.1 Q1\nX10.524 Y0.007\nG3 ") != std::string::npos);  // no motion word added
  CHECK(compress_as(shipped("rs274"), program("G05.1 Q1"), 0.01).stats.moves_in == 0);
  for (const char* code : {"G05 P10000", "G08 P1"}) {
    INFO(code);
    CHECK(compress_as(shipped("fanuc"), program(code), 0.01).stats.arcs_out >= 1);
  }
  // Haas's accuracy control: its E is a tolerance, not the extruder.
  const CompressResult haas = compress_as(shipped("haas"), program("G187 P1 E0.01"), 0.01);
  CHECK(test::broken_promise(haas) == "");
  CHECK(haas.stats.arcs_out >= 1);
  // A code arcpress does not model ends anywhere, whatever axis words its block holds: Haas's
  // engraving G47 starts at its X/Y, so the move after it, from wherever the text ends, is
  // kept as written (joined to the arc after it, it would start at X1 Y1).
  const std::string g47 = "G21 G90 G17\nG0 X0. Y0. Z1.\nG1 Z-0.1 F300.\nG47 P0 (AB) X1. Y1. I0. J0.2 R0.1 Z-0.05 F300. E50.\n"
                          "G1 X2. Y1.5\nG1 X3. Y1.8\nG1 X4. Y1.9\nG1 X5. Y1.8\nG1 X6. Y1.5\nG0 Z5.\nM30\n";
  const CompressResult engraved = compress_as(shipped("haas"), g47, 0.05);
  CHECK(engraved.output.find("\nG1 X2. Y1.5\nG2 X6. Y1.5 ") != std::string::npos);
  // Under G66 every move calls the macro at its end (a hole at each): none is merged.
  const std::string holes = "%\nO1001\nG21 G17 G90\nG0 X0. Y0. Z5.\nG1 Z2. F1000.\nG66 P9010 R1. Z-5.\nX10.\nX20.\n"
                            "X30.\nX40.\nG67\nG0 Z50.\nM30\n%\n";
  const CompressResult calls = compress_as(shipped("fanuc"), holes, 0.01);
  CHECK(calls.output == holes);
  // (G66's own Z is the macro's argument: the holes are at Z2.)
  DiagnosticSink sink("h.nc");
  const Program hp = lex("h.nc", holes, sink);
  const Interpretation hi = interpret(hp, sink, shipped("fanuc"));
  REQUIRE(hi.moves.size() == 2 + 4 + 1);
  CHECK(hi.moves[2].to[kZ] == 2);
  CHECK(hi.moves[2].known);
  CHECK(compress_as(shipped("rs274"), holes, 0.01).output.find("\nX20.\n") == std::string::npos);
}

TEST_CASE("a code that switches a mode shares its block with a move, which is read as RS274 reads it", "[dialect]") {
  // Exact stop at the end of the block (Fanuc, Haas), continuous path and look-ahead: the
  // block still moves, and the move after it goes on from there.
  for (const auto& [name, code] : {std::pair{"fanuc", "G09"}, std::pair{"haas", "G09"}, std::pair{"haas", "G103 P1"},
                                   std::pair{"sinumerik", "G642"}, std::pair{"sinumerik", "G9"},
                                   std::pair{"sinumerik", "SOFT"}}) {
    INFO(name << " " << code);
    const std::string t = fmt::format("G21 G90 G17\nG0 X0. Y0. Z0.\nG1 X1. F100.\n{} G1 X10. Y5. F500.\nG1 X11. Y6.\nM30\n", code);
    DiagnosticSink sink("m.nc");
    const Program p = lex("m.nc", t, sink, lex_rules(shipped(name)));
    const Interpretation in = interpret(p, sink, shipped(name));
    REQUIRE(in.moves.size() == 4);
    CHECK(in.moves[2].to[kX] == 10);
    CHECK(in.moves[2].feed_mm_min == 500);
    CHECK(in.moves[3].known);
  }
  // A code read as settings holds values: Sinumerik's dwell G4 F2 (seconds) leaves the feed.
  const std::string dwell = "G71 G90 G17\nG0 X0 Y0 Z0\nG1 X1 F500\nG4 F2\nG1 X2\n";
  DiagnosticSink sink("d.mpf");
  const Program p = lex("d.mpf", dwell, sink, lex_rules(shipped("sinumerik")));
  const Interpretation in = interpret(p, sink, shipped("sinumerik"));
  REQUIRE(in.moves.size() == 3);
  CHECK(in.moves[2].feed_mm_min == 500);
}

TEST_CASE("a dialect's [arcs.last_turn] names G-codes, each with the clockwise and counter-clockwise codes it stands for",
          "[dialect]") {
  const Dialect d = parse_dialect("name = \"x\"\n[arcs.last_turn]\nG05 = [\"G02\", \"G03\"]\nG15 = [\"G12\", \"G13\"]\n", "x.toml");
  REQUIRE(d.turn_reading(150));
  CHECK(d.turn_reading(150)->ccw10 == 130);
  CHECK(d.turn_set_by(120) == 2);
  CHECK(d.turn_set_by(30) == 3);
  CHECK(d.turn_set_by(50) == 0);
  CHECK(error_of("name = \"x\"\n[arcs.last_turn]\nM05 = [\"G02\", \"G03\"]\n").find("arcs.last_turn.M05: expected a G-code") !=
        std::string::npos);
  CHECK(error_of("name = \"x\"\n[arcs.last_turn]\nG05 = [\"G02\"]\n").find("expected two G-codes") != std::string::npos);
  CHECK(error_of("name = \"x\"\n[arcs.last_turn]\nG05 = [\"G02\", \"X3\"]\n").find("\"X3\": expected a G-code") !=
        std::string::npos);
}

TEST_CASE("a dialect's [codes] keys and meanings are checked where the file gives them", "[dialect]") {
  CHECK(error_of("name = \"x\"\n[codes]\nX70 = \"inch\"\n").find("user.toml:3:1: codes.X70: expected a G- or M-code") !=
        std::string::npos);
  CHECK(error_of("name = \"x\"\n[codes]\nG70 = \"inches\"\n").find("codes.G70: expected one of") != std::string::npos);
  CHECK(error_of("name = \"x\"\n[codes]\nG70.5x = \"inch\"\n") != "");
  // (A code with a point is quoted: a bare G54.1 is a dotted key, which TOML reads as a table.)
  CHECK(error_of("name = \"x\"\n[codes]\nG54.1 = \"frame\"\n").find("codes.G54: a code with a point is quoted") !=
        std::string::npos);
  const Dialect d = parse_dialect("name = \"x\"\n[codes]\n\"G54.1\" = \"frame\"\nM91 = \"machine\"\nT = \"moves\"\n", "x.toml");
  REQUIRE(d.meaning_of('G', 541));
  CHECK(*d.meaning_of('G', 541) == CodeMeaning::Frame);
  CHECK(*d.meaning_of('M', 910) == CodeMeaning::Machine);
  CHECK(*d.meaning_of('T', 0) == CodeMeaning::Moves);
  CHECK(d.meaning_of('G', 540) == nullptr);
}

TEST_CASE("golden: Klipper's G18 arcs turn the other way, so the same arc is G2 there", "[dialect]") {
  const test::Snippet g18 = test::arc_snippets()[4];
  // (On the programmed path: Klipper's own 1 mm chords of this arc lie 0.014 mm inside it,
  // over the band, so the executed band would keep it as lines.)
  CompressResult rs = compress_as(shipped("rs274"), g18.text),
                 kl = compress_as(shipped("klipper"), g18.text, 0.01, std::nullopt, CompressOptions::Band::Program);
  CHECK(rs.output.find("\nG3 X10. Y0. Z0. I-0.0029 K-10.0029 F300.\n") != std::string::npos);
  CHECK(kl.output.find("\nG2 X10. Y0. Z0. I-0.0029 K-10.0029 F300.\n") != std::string::npos);
  CHECK(kl.within_band());
}

TEST_CASE("golden: Mach3 states G91.1 once before the first arc, and a program that sets it itself is left alone",
          "[dialect]") {
  CompressResult r = compress_as(shipped("mach3"), test::arc_snippets()[0].text);
  CHECK(r.output == "G21 G90 G17\nG0 X10. Y0. Z0.\nG91.1\nG3 X0. Y10. Z0. I-10.0029 J-0.0029 F300.\nM30\n");
  std::string own = "G91.1\n" + test::arc_snippets()[0].text;
  CompressResult o = compress_as(shipped("mach3"), own);
  CHECK(o.output.find("G91.1") == o.output.rfind("G91.1"));
}

TEST_CASE("a Mach3 program whose own arcs are whole only as absolute centres runs on a machine set so as it did, "
          "the output saying G91.1 before its arcs and G90.1 before the program's",
          "[dialect]") {
  // Quarter circles of short moves, each followed by a half circle of the program's own whose
  // I/J name the absolute centre (the origin), with no G90.1: the IJ-mode setting decides.
  std::string program = "G21 G90 G17\nG0 X10 Y0 Z1\nG1 Z-1 F300\n";
  for (int pass = 0; pass < 40; ++pass) {
    for (int k = 1; k <= 90; ++k)
      program += fmt::format("G1 X{:.4f} Y{:.4f}\n", 10 * std::cos(k * M_PI / 180), 10 * std::sin(k * M_PI / 180));
    program += "G3 X0 Y-10 I0 J0\nG3 X10 Y0 I0 J0\nG0 Z1\nG0 X10 Y0\nG1 Z-1\n";
  }
  program += "M30\n";
  for (size_t chunk : {size_t(0), size_t(700)}) {
    INFO("pushed in pieces of " << chunk << " bytes (0: whole)");
    DiagnosticSink sink;
    CompressOptions opt;
    opt.dialect = shipped("mach3");
    std::string out;
    if (chunk == 0) {
      out = compress("m.nc", program, opt, sink).output;
    } else {
      Compressor c("m.nc", opt, sink);
      for (size_t at = 0; at < program.size(); at += chunk) c.push(std::string_view(program).substr(at, chunk));
      c.finish();
      c.take(out);
      REQUIRE(c.result().within_band());
      REQUIRE(c.pieces() > 2);
    }
    CHECK(sink.warning_count("W-MODEL-ARC-MODE") == 1);
    CHECK(out.find("G91.1\nG3 X0.0000 Y10.0000") != std::string::npos);
    CHECK(out.find("G90.1\nG3 X0 Y-10 I0 J0") != std::string::npos);
    // Read as the machine set to absolute centres reads both, the paths are the same.
    Dialect absolute = shipped("mach3");
    absolute.start_centres = StartCentres::Absolute;
    DiffOptions band;
    band.tolerance_mm = 0.01;
    const ProgramDiff d = test::diff_texts(program, out, band, absolute);
    CHECK(d.same(0.01));
  }
  // A program whose own arcs read whole as offsets gets G91.1 once, as before.
  const std::string incremental = "G21 G90 G17\nG0 X0 Y10\nG3 X-10 Y0 I0 J-10 F100\nM30\n";
  DiagnosticSink sink;
  CHECK(compress_as(shipped("mach3"), incremental).output == incremental);
}

TEST_CASE("golden: Fanuc prints 3 decimals with a point, and reads X1 as one micrometre", "[dialect]") {
  CompressResult r = compress_as(shipped("fanuc"), test::arc_snippets()[0].text);
  CHECK(r.output == "G21 G90 G17\nG0 X10. Y0. Z0.\nG3 X0. Y10. Z0. I-10.003 J-0.003 F300.\nM30\n");
  DiagnosticSink sink;
  Program p = lex("f.nc", "G21 G90\nG0 X1 Y2.\n", sink);
  Interpretation in = interpret(p, sink, shipped("fanuc"));
  REQUIRE(in.moves.size() == 1);
  CHECK(in.moves[0].to[kX] == Approx(0.001));
  CHECK(in.moves[0].to[kY] == Approx(2.0));
}

TEST_CASE("an arc end word the input left modal keeps the input's own digits, finer than the dialect's", "[dialect]") {
  // A curve flattening into a straight move that gives only X: the arc over that last move
  // must print Y, which the input gave with 4 decimals where Fanuc prints 3.
  std::string t = "G21 G90 G17\nG0 X50.0000 Y61.7000 Z0\nG1 F300\n";
  for (int k = 1; k <= 15; ++k) {
    double x = 50 - k * 0.26;
    t += fmt::format("X{:.4f} Y{:.4f}\n", x, 61.5244 + 0.035 * (x - 46.1) * (x - 46.1));
  }
  t += "X44.0672\nM30\n";
  CompressResult r = compress_as(shipped("fanuc"), t);
  INFO(r.output);
  REQUIRE(r.verified);
  CHECK(r.comparison.matched);
  CHECK(r.within_band());
  CHECK(r.output.find("X44.0672 Y61.5244") != std::string::npos);
}

TEST_CASE("printer dialects with no G18/G19 arcs, and no arcs under G91 for Klipper, keep those runs as lines",
          "[dialect]") {
  CompressResult m = compress_as(shipped("marlin"), test::arc_snippets()[4].text);
  CHECK(m.stats.arcs_out == 0);
  CHECK(m.output.find("G2 ") == std::string::npos);
  CHECK(m.output.find("G3 ") == std::string::npos);
  CHECK(m.within_band());
  // The quarter circle again, in incremental moves.
  std::string rel = "G21 G90\nG0 X10 Y0 Z0\nG91\n";
  double px = 10, py = 0;
  for (int k = 1; k <= 48; ++k) {
    double a = kPi / 2 * k / 48, x = 10 * std::cos(a), y = 10 * std::sin(a);
    rel += fmt::format("G1 X{:.4f} Y{:.4f} F300\n", x - px, y - py);
    px = x, py = y;
  }
  CHECK(compress_as(shipped("klipper"), rel).stats.arcs_out == 0);
  CompressResult rs = compress_as(shipped("rs274"), rel);
  CHECK(rs.stats.arcs_out > 0);
  CHECK(rs.within_band());
}

TEST_CASE("Grbl's 79-character limit: a block that cannot be made short enough stays as the input's lines",
          "[dialect]") {
  // Long words: every move carries A and B with many digits, so an arc block would need
  // X Y Z I J A B F > 80 characters even without spaces.
  std::string t = "G21 G90\nG0 X10 Y0 Z0 A123.456789 B-98.765432 C45.678901 U7.654321\n";
  for (int k = 1; k <= 48; ++k) {
    double a = kPi / 2 * k / 48;
    t += fmt::format("G1 X{:.6f} Y{:.6f} Z-0.000001 A123.456789 B-98.765432 C45.678901 U7.654321 F1234.5678\n", 10 * std::cos(a),
                     10 * std::sin(a));
  }
  CompressResult g = compress_as(shipped("grbl"), t);
  for (const auto& l : lines_of(g.output)) {
    if (l.rfind("G1 ", 0) == 0 && l.find("A123") != std::string::npos) continue;  // the input's own lines
    CHECK(l.size() <= 79);
  }
  CHECK(g.within_band());
  CHECK(g.stats.arcs_unprintable > 0);
  CHECK(compress_as(shipped("grblhal"), t).stats.arcs_out > 0);  // 256 characters are enough
}

TEST_CASE("words a dialect refuses are reported where the input has them, and passed through", "[dialect]") {
  DiagnosticSink sink("p.nc");
  CompressOptions opt;
  opt.dialect = shipped("grbl");
  std::string text = "%\nO1000\nG90.1\nG0 X0 Y0\nM30\n%\n";
  auto r = compress("p.nc", text, opt, sink);
  CHECK(r.output == text);
  CHECK(sink.warning_count("W-DIALECT-REFUSED") == 4);
  std::string all = sink.format_all();
  CHECK(all.find("p.nc:1:1: warning: W-DIALECT-REFUSED: '%' is refused by grbl") != std::string::npos);
  CHECK(all.find("4 more") == std::string::npos);
}

TEST_CASE("a comment form the dialect does not read is reported only where it opens a comment", "[dialect]") {
  auto comment_warnings = [](const std::string& dialect, const std::string& text) {
    DiagnosticSink sink("p.gcode");
    CompressOptions opt;
    opt.dialect = shipped(dialect);
    compress("p.gcode", text, opt, sink);
    return sink.warning_count("W-DIALECT-COMMENT");
  };
  // Marlin reads ';' comments only: a '(' that opens a comment is reported, one inside a
  // ';' comment is that comment's text.
  CHECK(comment_warnings("marlin", "G1 X1 (note)\n") == 1);
  CHECK(comment_warnings("marlin", "; estimated printing time (normal mode) = 1h\n") == 0);
  CHECK(comment_warnings("marlin", "G1 X1 ; move (fast)\n") == 0);
  CHECK(comment_warnings("marlin", "G1 X1 (a) ; b (c)\n") == 1);
  // Fanuc reads '( )' only: a ';' inside parentheses opens nothing.
  CHECK(comment_warnings("fanuc", "G1 X1 (a; b)\n") == 0);
  CHECK(comment_warnings("fanuc", "G1 X1 (a) ; b\n") == 1);
}

TEST_CASE("a lathe dialect reads X words as diameters from the start, and G8 as radii", "[dialect][lathe]") {
  DiagnosticSink sink;
  Program p = lex("t.nc", "G18 G21 G90\nG0 X20. Z1.\nG1 Z0. F50.\nG8\nG1 X12.\n", sink);
  Interpretation in = interpret(p, sink, shipped("haas-lathe"));
  REQUIRE(in.moves.size() == 3);
  CHECK(in.moves[0].to[kX] == 10.0);  // a diameter of 20 mm
  CHECK(in.moves[1].unfit == Unfit::DiameterMode);
  CHECK(in.moves[2].to[kX] == 12.0);  // G8: radius
  Interpretation mill = interpret(p, sink, shipped("haas"));
  CHECK(mill.moves[0].to[kX] == 20.0);
}

TEST_CASE("G10 and G11 are a printer firmware's retraction that leaves the programmed position where it is",
          "[dialect][printer]") {
  const std::vector<std::string> retracting = {"marlin", "prusa", "prusa-mk3", "klipper", "reprapfirmware",
                                                "smoothieware"};
  for (const std::string& name : kShipped) {
    INFO(name);
    CHECK(shipped(name).firmware_retraction ==
          (std::find(retracting.begin(), retracting.end(), name) != retracting.end()));
  }
  const std::string text =
      "G21 G90\nG0 X0 Y0 Z0.2\nG1 X1 E1 F600\n"
      "G10\nG0 X5 Y5\nG11\nG1 X6 E2\n"            // a retraction around a travel
      "G10 P0 S200 R150\nG1 X7 E3\n"                // a tool's temperatures (RepRapFirmware)
      "G10 S1\nG1 X8 E4\nG11\n"                     // a tool-change retraction (Marlin)
      "G10 P0 X1 Y1\nG1 X9 E5\n";                   // a tool's offsets
  DiagnosticSink sink("t.gcode");
  Program p = lex("t.gcode", text, sink);
  Interpretation in = interpret(p, sink, shipped("reprapfirmware"));
  REQUIRE(in.moves.size() == 7);
  for (size_t k = 1; k < 6; ++k) {
    INFO(k);
    CHECK(in.moves[k].known);
  }
  CHECK(in.moves[3].to[kX] == 6.0);
  CHECK(in.moves[3].to[kZ] == 0.2);
  CHECK_FALSE(in.moves[6].known);  // X from the new offsets
  CHECK(in.moves[6].unfit == Unfit::UnknownAfterCycle);
  CHECK(sink.format_all().empty());
  // Where G10 sets offsets and tables only, the position after it is unknown, and G11 is
  // not read.
  DiagnosticSink cnc("t.gcode");
  Interpretation plain = interpret(p, cnc, shipped("rs274"));
  CHECK_FALSE(plain.moves[2].known);
  CHECK(plain.moves[2].unfit == Unfit::UnknownAfterCycle);
  CHECK(cnc.format_all().find("t.gcode:6:1: warning: E-MODEL-GCODE: G11 is not modelled") != std::string::npos);
  // G11 with axis words is none of the firmware's.
  DiagnosticSink odd("t.gcode");
  Program q = lex("t.gcode", "G0 X0 Y0 Z0\nG11 X3\nG1 Y4 F600\n", odd);
  Interpretation qi = interpret(q, odd, shipped("marlin"));
  CHECK(odd.format_all().find("t.gcode:2:1: warning: E-MODEL-GCODE: G11 with axis words is not modelled") !=
        std::string::npos);
  CHECK_FALSE(qi.moves.back().known);
}

TEST_CASE("E words are relative as each firmware reads G90 and G91 with M82 and M83", "[dialect][printer]") {
  // Marlin 2 and Smoothieware: G90/G91 set E's mode with the axes', M82/M83 then E's alone.
  // Klipper: E is relative under G91 or after M83, each kept. RepRapFirmware: M82/M83 only.
  CHECK(shipped("marlin").extrusion_distance == ExtrusionDistance::WithAxes);
  CHECK(shipped("prusa").extrusion_distance == ExtrusionDistance::WithAxes);
  CHECK(shipped("smoothieware").extrusion_distance == ExtrusionDistance::WithAxes);
  CHECK(shipped("klipper").extrusion_distance == ExtrusionDistance::G91OrM83);
  CHECK(shipped("reprapfirmware").extrusion_distance == ExtrusionDistance::M82M83Only);
  CHECK(shipped("prusa-mk3").extrusion_distance == ExtrusionDistance::M82M83Only);  // "E axis is left intact"
  CHECK(shipped("rs274").extrusion_distance == ExtrusionDistance::WithAxes);
  // E after each extruding move, read by Marlin / Klipper / RepRapFirmware:
  const std::string text =
      "G21 G90 M83\nG0 X0 Y0 Z0.2\nG1 X1 E1 F600\n"  // M83: 1 / 1 / 1
      "G91\nG1 Z0.2\nG90\nG1 X2 E1\n"                 // a layer change in G91, then G90: 1 / 2 / 2
      "M82\nG91\nG1 X1 E1\n"                          // M82, then G91: 2 / 3 / 1
      "M83\nG1 X1 E1\n"                                // M83 under G91: 3 / 4 / 2
      "G90\nM82\nG1 X5 E7\n";                         // absolute again: 7 / 7 / 7
  struct Expected {
    const char* dialect;
    std::vector<double> e;
  };
  for (const Expected& x : {Expected{"marlin", {1, 1, 2, 3, 7}}, Expected{"smoothieware", {1, 1, 2, 3, 7}},
                            Expected{"klipper", {1, 2, 3, 4, 7}}, Expected{"reprapfirmware", {1, 2, 1, 2, 7}}}) {
    INFO(x.dialect);
    DiagnosticSink sink("t.gcode");
    const Program p = lex("t.gcode", text, sink);
    const Interpretation in = interpret(p, sink, shipped(x.dialect));
    REQUIRE(in.moves.size() == 7);
    std::vector<double> e;
    for (size_t k : {1, 3, 4, 5, 6}) e.push_back(in.moves[k].to[kE]);
    CHECK(e == x.e);
  }
  // RepRapFirmware keeps E absolute under G91 after M82: the G91 line's E is a position.
  DiagnosticSink sink("t.gcode");
  const Program p = lex("t.gcode", "G21 G90 M82\nG0 X0 Y0 Z0.2\nG1 X1 E3 F600\nG91\nG1 X1 E2\n", sink);
  CHECK(interpret(p, sink, shipped("reprapfirmware")).moves.back().to[kE] == 2.0);
  CHECK(interpret(p, sink, shipped("marlin")).moves.back().to[kE] == 5.0);
  CHECK(error_of("name = \"x\"\n[printer]\nextrusion_distance = \"g91\"\n").find("extrusion_distance") !=
        std::string::npos);
}

TEST_CASE("the extended commands a dialect names as moving nothing leave the position known and others forget it",
          "[dialect][printer]") {
  const Dialect klipper = shipped("klipper");
  for (const char* name : {"EXCLUDE_OBJECT_START", "EXCLUDE_OBJECT_END", "SET_VELOCITY_LIMIT", "SET_PRESSURE_ADVANCE"}) {
    INFO(name);
    CHECK(std::count(klipper.position_keeping_commands.begin(), klipper.position_keeping_commands.end(), name) == 1);
  }
  const std::string text =
      "G21 G90 M83\nG0 X0 Y0 Z0.2\nG1 X1 E1 F600\n"
      "EXCLUDE_OBJECT_START NAME=part_1\nG1 X2 E1\n"  // an object label (exclude_object.py)
      "  set_velocity_limit ACCEL=3000\nG1 X3 E1\n"  // Klipper reads names in any case
      "/EXCLUDE_OBJECT_END NAME=part_1\nG1 X4 E1\n"   // behind a block delete
      "CLEAN_NOZZLE\nG1 X5 E1\n";                     // a macro of the printer's own config
  DiagnosticSink sink("t.gcode");
  const Program p = lex("t.gcode", text, sink);
  const Interpretation in = interpret(p, sink, klipper);
  REQUIRE(in.moves.size() == 6);
  for (size_t k = 1; k < 5; ++k) {
    INFO(k);
    CHECK(in.moves[k].known);
  }
  CHECK(in.moves[4].to[kX] == 4.0);
  CHECK_FALSE(in.moves[5].known);
  CHECK(in.moves[5].unfit == Unfit::UnknownAfterControl);
  // A dialect without the list (Marlin has no such commands) forgets the position at each.
  DiagnosticSink other("t.gcode");
  const Interpretation marlin = interpret(p, other, shipped("marlin"));
  CHECK_FALSE(marlin.moves[2].known);
  CHECK(marlin.moves[2].unfit == Unfit::UnknownAfterControl);
  // A name the lexer would not read as a command's is refused where the file says it.
  CHECK(error_of("name = \"x\"\n[printer]\nposition_keeping_commands = [\"SET FAN\"]\n")
            .find("user.toml:3:30: printer.position_keeping_commands: \"SET FAN\": expected a command's name") !=
        std::string::npos);
  CHECK(error_of("name = \"x\"\n[printer]\nposition_keeping_commands = [\"M486\"]\n") != "");
}

TEST_CASE("Marlin's G61 returns to a saved position the program does not say, and its G60 moves nothing",
          "[dialect][printer]") {
  // Marlin/src/gcode/feature/pause/G61.cpp: the axes named (or all) go back to the slot's
  // position, the words' values added to it; RS274 reads G61 as exact-path mode.
  const std::string text =
      "G21 G90 M83\nG0 X0 Y0 Z0.2\nG1 X1 E1 F600\nG60 S0\n"
      "G1 X2 E1\n"        // move 2: known (G60 only saved the position)
      "G1 X30 Y30 E1\n"
      "G61 X Y S0\n"      // back to X1 Y0
      "G1 X31 Y30 Z0.2 E1\n"  // move 4: it starts where G61 left the tool
      "G1 X32 E1\n";          // move 5: starts at a known point again
  for (const char* name : {"marlin", "prusa"}) {
    INFO(name);
    DiagnosticSink sink("t.gcode");
    const Program p = lex("t.gcode", text, sink);
    const Interpretation in = interpret(p, sink, shipped(name));
    REQUIRE(in.moves.size() == 6);
    CHECK(in.moves[2].known);
    CHECK_FALSE(in.moves[4].known);
    CHECK(in.moves[4].unfit == Unfit::UnknownAfterCodeMove);
    CHECK(in.moves[5].known);
    CHECK(sink.all().empty());
  }
  // Read as RS274 (where G60 is not read, so left out), G61 moves nothing and the move after
  // it is placed from X30 Y30.
  std::string no_save = text;
  no_save.erase(no_save.find("G60 S0\n"), 7);
  DiagnosticSink rs("t.gcode");
  const Program p = lex("t.gcode", no_save, rs);
  CHECK(interpret(p, rs, shipped("rs274")).moves[4].known);
}

TEST_CASE("a program names its own dialect by its slicer's flavor, where the flavor says which firmware",
          "[dialect][flavor]") {
  auto flavor = [](const std::string& text) { return program_flavor(text); };
  const auto prusa = flavor("; generated by PrusaSlicer 2.7.1\nG1 X1\n; prusaslicer_config = begin\n; gcode_flavor = marlin2\n");
  REQUIRE(prusa);
  CHECK(prusa->dialect == "marlin");
  CHECK(prusa->evidence == "; gcode_flavor = marlin2");
  CHECK(prusa->line == 4);
  const auto cura = flavor(";FLAVOR:Marlin\n;TIME:6666\n");
  REQUIRE(cura);
  CHECK(cura->dialect == "marlin");
  CHECK(flavor(";FLAVOR:Marlin(Volumetric)\n")->dialect == "marlin");  // Marlin, E in mm³
  CHECK(flavor("; gcode_flavor = klipper\n")->dialect == "klipper");
  CHECK(flavor("; gcode_flavor = reprapfirmware\n")->dialect == "reprapfirmware");
  CHECK(flavor("; gcode_flavor = smoothie\n")->dialect == "smoothieware");
  // Where the flavor says Marlin, or there is none, a Prusa printer's model says which of
  // Prusa's firmwares runs it: Prusa-Firmware (prusa-mk3) or Buddy (prusa).
  const auto mk3s = flavor("M862.3 P \"MK3S\" ; printer model check\nG28\n; gcode_flavor = marlin2\n; printer_model = MK3S\n");
  REQUIRE(mk3s);
  CHECK(mk3s->dialect == "prusa-mk3");
  CHECK(mk3s->evidence == "M862.3 P \"MK3S\" ; printer model check");
  CHECK(mk3s->line == 1);
  CHECK_FALSE(mk3s->model_only);
  for (const auto& [model, dialect] : std::vector<std::pair<std::string, std::string>>{
           {"MK3", "prusa-mk3"}, {"MK3SMMU3", "prusa-mk3"}, {"MK2.5S", "prusa-mk3"}, {"MK3.5", "prusa"},
           {"MK3.9", "prusa"}, {"MK4IS", "prusa"}, {"MINI", "prusa"}, {"XL", "prusa"}, {"COREONE", "prusa"}}) {
    INFO(model);
    const auto named = flavor(";FLAVOR:Marlin\n; printer_model = " + model + "\n");
    REQUIRE(named);
    CHECK(named->dialect == dialect);
    CHECK(named->line == 2);
  }
  CHECK(flavor("; gcode_flavor = marlin2\n; printer_model = \n")->dialect == "marlin");  // no model named
  CHECK(flavor("; gcode_flavor = marlin2\n; printer_model = ENDER3\n")->dialect == "marlin");
  CHECK(flavor("M862.3 P \"MK4\"\n; gcode_flavor = klipper\n")->dialect == "klipper");  // another firmware
  const auto alone = flavor("M862.3 P \"MK4\"\nG28\n");
  REQUIRE(alone);
  CHECK(alone->dialect == "prusa");
  CHECK(alone->model_only);
  // RepRap/Sprinter is several firmwares: the line is seen, and names no dialect. A program
  // without a flavor line names none.
  const auto reprap = flavor("G28\n; gcode_flavor = reprap\n");
  REQUIRE(reprap);
  CHECK(reprap->dialect.empty());
  CHECK(reprap->line == 2);
  CHECK_FALSE(flavor("G21 G90\nG1 X1 (gcode_flavor = marlin)\n"));
  // Every dialect a flavor maps to is shipped.
  for (const char* text : {"; gcode_flavor = marlin\n", "; gcode_flavor = klipper\n",
                           "; gcode_flavor = reprapfirmware\n", "; gcode_flavor = smoothie\n"})
    CHECK(shipped(flavor(text)->dialect).name == flavor(text)->dialect);
  for (const std::string& name : flavor_dialects()) CHECK(shipped(name).name == name);
  // A Heidenhain ISO program begins with its own block; that names the TNC, and no slicer.
  const auto tnc = flavor("%PART-7 G71 *\nN10 G01 X+1 *\n");
  REQUIRE(tnc);
  CHECK(tnc->dialect == "heidenhain-iso");
  CHECK(tnc->evidence == "%PART-7 G71 *");
  CHECK_FALSE(tnc->slicer);
  CHECK(shipped(tnc->dialect).name == "heidenhain-iso");
  CHECK(flavor("\xEF\xBB\xBF\n  %P G70 * ; inch\n")->line == 2);
  CHECK_FALSE(flavor("%\nO1000\n"));                 // a tape mark
  CHECK_FALSE(flavor("G21\n%PART G71 *\n"));          // not where a program begins
  CHECK_FALSE(flavor("%PART G21 *\n"));
}

TEST_CASE("ARCPRESS_DIALECT_PATH is a list of folders split as the system splits path lists, searched in order",
          "[dialect][platform]") {
  auto dir = test::temp_dir("dialect-path");
  test::write_file(dir / "mine.toml", "name = \"mine\"\ndescription = \"a user's own\"\n");
  const std::string list = std::string("/nonexistent") + platform::path_list_separator() + dir.string();
  const char* before = std::getenv("ARCPRESS_DIALECT_PATH");
  const std::string saved = before ? before : "";
  ::setenv("ARCPRESS_DIALECT_PATH", list.c_str(), 1);
  const Dialect d = dialect_named("mine");
  if (before) ::setenv("ARCPRESS_DIALECT_PATH", saved.c_str(), 1);
  else ::unsetenv("ARCPRESS_DIALECT_PATH");
  CHECK(d.name == "mine");
  CHECK(d.description == "a user's own");
  // The library finds the shipped dialects from where it was loaded (here, the test program
  // it is linked into, in the build tree), and the program's folder is that same folder.
  CHECK_FALSE(platform::own_folder().empty());
  CHECK(platform::own_folder() == platform::program_folder());
}

TEST_CASE("a block arcpress adds to select a plane takes a number the program's blocks leave free, where they are "
          "numbered",
          "[dialect][heidenhain]") {
  // A quarter circle in XZ under G17, numbered N30 to N330: one G02 in G18 between a G18
  // block and a G17 block, every block numbered, the numbers ascending.
  std::string text = "%P G71 *\nN10 G17 G90 *\nN20 G00 X+0 Y+0 Z+0 *\nN25 G01 F500 *\n";
  for (int i = 0; i <= 30; ++i)
    text += fmt::format("N{} G01 X{:+.4f} Y+0 Z{:+.4f} *\n", 30 + 10 * i, 20 * std::sin(M_PI / 60 * i),
                        20 - 20 * std::cos(M_PI / 60 * i));
  text += "N400 G00 Z+50 *\nN410 M30 *\nN99999999 %P G71 *\n";
  const CompressResult r = compress_as(shipped("heidenhain-iso"), text);
  CHECK(test::broken_promise(r) == "");
  CHECK(r.stats.plane_words_added == 2);
  CHECK(r.stats.arcs_out >= 1);
  std::istringstream lines(r.output);
  std::string line;
  long previous = -1;
  size_t numbered = 0;
  std::getline(lines, line);  // (%P G71 *)
  while (std::getline(lines, line)) {
    INFO(line);
    REQUIRE(line.size() > 1);
    REQUIRE(line[0] == 'N');
    const long n = std::stol(line.substr(1));
    CHECK(n > previous);
    previous = n;
    ++numbered;
  }
  CHECK(numbered == 3 + r.stats.arcs_out + r.stats.lines_out + 2 + 3);
  CHECK(r.output.find("G18 *\n") != std::string::npos);
  CHECK(r.output.find("G17 *\nN400 G00") != std::string::npos);
  // A program without numbers gets none.
  std::string bare;
  for (std::istringstream in(text); std::getline(in, line);)
    bare += (line[0] == 'N' && line[1] != '9' ? line.substr(line.find(' ') + 1) : line) + "\n";
  const CompressResult b = compress_as(shipped("heidenhain-iso"), bare);
  CHECK(test::broken_promise(b) == "");
  CHECK(b.output.find("\nG18 *\n") != std::string::npos);
  CHECK(b.output.find("\nG17 *\n") != std::string::npos);
}
