// SPDX-License-Identifier: GPL-3.0-or-later
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>

#include "support.hpp"

namespace fs = std::filesystem;
using arcpress::test::run_arcpress;

namespace {
const std::string kProgram = "G21 G90\nG0 X0 Y0 Z1\nG1 Z0 F100\nG1 X1 Y0\nX2 Y0.1\nX3 Y0.3\nM2\n";
}

TEST_CASE("arcpress reads standard input and writes standard output", "[cli]") {
  auto c = run_arcpress("--method keep", kProgram);
  CHECK(c.exit_code == 0);
  CHECK(c.out == kProgram);
  auto d = run_arcpress("- --passthrough", kProgram);
  CHECK(d.exit_code == 0);
  CHECK(d.out == kProgram);
}

TEST_CASE("help and version succeed and help documents the exit codes", "[cli]") {
  auto h = run_arcpress("--help");
  CHECK(h.exit_code == 0);
  CHECK(h.out.find("--tolerance") != std::string::npos);
  CHECK(h.out.find("Exit codes") != std::string::npos);
  auto v = run_arcpress("--version");
  CHECK(v.exit_code == 0);
  CHECK(v.out.find("arcpress ") == 0);
  // The commit it was built from, as git names it (or "unknown" outside a checkout), and its license.
  CHECK(std::regex_search(v.out, std::regex("^arcpress [0-9.]+ \\(commit ([0-9a-f]{12}(-dirty)?|unknown)\\)\n")));
  CHECK(v.out.find("GPL-3.0-or-later") != std::string::npos);
  // The header of what it writes names the same version and commit.
  std::smatch named;
  REQUIRE(std::regex_search(v.out, named, std::regex("^arcpress ([0-9.]+) \\(commit ([^)]+)\\)")));
  auto out = run_arcpress("--dialect marlin", "; a slicer's first line\nG1 X1 Y1 F600\n");
  CHECK(out.out.find("; arcpress " + named[1].str() + " commit " + named[2].str() + " --tolerance ") != std::string::npos);
}

TEST_CASE("every fitting method named in --help is accepted and writes a verified arc for a sampled arc", "[cli]") {
  std::string arc = "G21 G90 G17\nG0 X10 Y0 Z0\nG1 F600\n";
  for (int i = 1; i <= 90; ++i)
    arc += "G1 X" + std::to_string(10 * std::cos(i * M_PI / 180)) + " Y" + std::to_string(10 * std::sin(i * M_PI / 180)) + "\n";
  arc += "M2\n";
  for (const char* m : {"arcs", "global", "greedy", "stream", "lowe"}) {
    INFO(m);
    CHECK(run_arcpress("--help").out.find(std::string(m) + ":") != std::string::npos);
    auto c = run_arcpress(std::string("--method ") + m, arc);
    CHECK(c.exit_code == 0);
    CHECK(c.out.find("G3") != std::string::npos);
  }
  CHECK(run_arcpress("--method nosuch", arc).exit_code == 2);
}

TEST_CASE("any thread count (--threads) gives the same output, and a negative count is a usage error", "[cli]") {
  std::string two_runs = "G21 G90 G17\nG0 X10 Y0 Z0\nG1 F600\n";
  for (int run = 0; run < 2; ++run) {
    for (int i = 1; i <= 90; ++i)
      two_runs += "G1 X" + std::to_string(10 * std::cos(i * M_PI / 180)) + " Y" + std::to_string(10 * std::sin(i * M_PI / 180)) + "\n";
    two_runs += "G0 X10 Y0\nG1 F600\n";  // the rapid ends the first run
  }
  two_runs += "M2\n";
  auto one = run_arcpress("--threads 1", two_runs);
  auto two = run_arcpress("-j 2", two_runs);
  CHECK(one.exit_code == 0);
  CHECK(two.exit_code == 0);
  CHECK(two.out == one.out);
  size_t arcs = 0;
  for (size_t at = one.out.find("G3"); at != std::string::npos; at = one.out.find("G3", at + 1)) ++arcs;
  CHECK(arcs >= 2);  // both runs fitted
  CHECK(run_arcpress("--help").out.find("--threads") != std::string::npos);
  CHECK(run_arcpress("--threads -1", two_runs).exit_code == 2);
}

TEST_CASE("usage errors exit with 2", "[cli]") {
  CHECK(run_arcpress("--tolerance -1", kProgram).exit_code == 2);
  CHECK(run_arcpress("--no-such-option", kProgram).exit_code == 2);
  CHECK(run_arcpress("--dialect nosuch", kProgram).exit_code == 2);
}

TEST_CASE("a usage error says what to type instead", "[cli]") {
  const std::string sample = "'" ARCPRESS_SOURCE_DIR "/samples/contour.nc'";
  // A second file name that does not exist: the output is written with -o.
  auto two = run_arcpress(sample + " out.nc");
  CHECK(two.exit_code == 2);
  CHECK(two.err == "arcpress: no program 'out.nc' to read; to write a file, use -o out.nc\n");
  // A mistyped option: the nearest real one, and its value is not taken for a file name.
  auto typo = run_arcpress(sample + " --tolerence 0.01");
  CHECK(typo.exit_code == 2);
  CHECK(typo.err == "arcpress: unknown option '--tolerence'; did you mean '--tolerance'?\n");
  auto diff_typo = run_arcpress("diff " + sample + " " + sample + " --plto=x.svg");
  CHECK(diff_typo.err == "arcpress: unknown option '--plto'; did you mean '--plot'?\n");
  auto diff_three = run_arcpress("diff " + sample + " " + sample + " c.nc");
  CHECK(diff_three.err == "arcpress: unexpected argument 'c.nc': diff compares two programs, A and B\n");
  CHECK(run_arcpress("--zzzzzzzz").err == "arcpress: unknown option '--zzzzzzzz' (see --help)\n");
  // The dialect's default is no fixed name: absent, it comes from the program.
  const std::string help = run_arcpress("--help").out;
  CHECK(help.find("--dialect NAME ") != std::string::npos);
  CHECK(help.find("=rs274") == std::string::npos);
}

TEST_CASE("a missing input file exits with 3", "[cli]") {
  auto c = run_arcpress("/nonexistent/in.nc -o /tmp/x.nc");
  CHECK(c.exit_code == 3);
  CHECK(c.err.find("cannot open") != std::string::npos);
}

TEST_CASE("strict mode refuses an unreadable block with its place and leaves no output", "[cli]") {
  auto d = arcpress::test::temp_dir("strict");
  arcpress::test::write_file(d / "in.nc", "G0 X0 Y0\nG1 X1 Y@\n");
  auto c = run_arcpress("--strict '" + (d / "in.nc").string() + "' -o '" + (d / "out.nc").string() + "'");
  CHECK(c.exit_code == 2);
  CHECK(c.err.find("in.nc:2:7: error: E-LEX-NUMBER") != std::string::npos);
  CHECK_FALSE(fs::exists(d / "out.nc"));
  // No temporary files are left behind either.
  CHECK(std::distance(fs::directory_iterator(d), fs::directory_iterator()) == 1);
}

TEST_CASE("non-strict mode passes an unreadable block through and warns", "[cli]") {
  auto c = run_arcpress("", "G0 X0 Y0\nG1 X1 Y@\n");
  CHECK(c.exit_code == 0);
  CHECK(c.out == "G0 X0 Y0\nG1 X1 Y@\n");
  CHECK(c.err.find("<stdin>:2:7: warning: E-LEX-NUMBER") != std::string::npos);
}

TEST_CASE("the input is never overwritten unless --in-place is given", "[cli]") {
  auto d = arcpress::test::temp_dir("inplace");
  fs::path in = d / "in.nc";
  arcpress::test::write_file(in, kProgram);
  auto c = run_arcpress("'" + in.string() + "' -o '" + in.string() + "'");
  CHECK(c.exit_code == 2);
  CHECK(arcpress::test::read_file(in) == kProgram);
  auto ok = run_arcpress("--in-place --method keep '" + in.string() + "'");
  CHECK(ok.exit_code == 0);
  CHECK(arcpress::test::read_file(in) == kProgram);
}

TEST_CASE("an existing output file is replaced only when the run succeeds", "[cli]") {
  auto d = arcpress::test::temp_dir("atomic");
  arcpress::test::write_file(d / "out.nc", "old content\n");
  arcpress::test::write_file(d / "bad.nc", "G1 X(\n");
  auto c = run_arcpress("--strict '" + (d / "bad.nc").string() + "' -o '" + (d / "out.nc").string() + "'");
  CHECK(c.exit_code == 2);
  CHECK(arcpress::test::read_file(d / "out.nc") == "old content\n");
}

TEST_CASE("the stats flag reports counts on standard error", "[cli]") {
  auto c = run_arcpress("--stats --method keep", kProgram);
  CHECK(c.exit_code == 0);
  CHECK(c.out == kProgram);
  CHECK(c.err.find("G1 moves       4 in the input, 4 in 1 runs") != std::string::npos);
  // Every line of the stats ends, so what comes next on standard error starts a line.
  CHECK(c.err.back() == '\n');
  const std::string forced = fmt::format("G21 G90\nG0 X0 Y0 Z0\nG1 F300\n{}M2\n", [] {
    std::string zig;  // sharp turns in a run of short moves: many joints named
    for (int k = 1; k <= 40; ++k) zig += fmt::format("G1 X{:.3f} Y{:.3f}\n", 0.3 * k, (k % 2) * 0.004);
    return zig;
  }());
  auto many = run_arcpress("--stats", forced);
  REQUIRE(many.exit_code == 0);
  CHECK(many.err.back() == '\n');
}

TEST_CASE("the stats name the input lines where the band forced the tangent to break", "[cli]") {
  // A pass over a dome clipped to the floor at both ends: the tangent breaks at the hooks.
  std::string dome = "G21 G90 G17\nG0 X-11.2 Y0 Z0\nG1 F800\n";
  for (int k = 0; k <= 112; ++k) {
    const double x = -11.2 + 0.2 * k;
    dome += fmt::format("G1 X{:.4f} Y{:.4f}\n", x, std::max(0.0, std::sqrt(std::max(0.0, 224 - x * x)) - 10));
  }
  dome += "M2\n";
  auto c = run_arcpress("--stats", dome);
  REQUIRE(c.exit_code == 0);
  const size_t at = c.err.find("  forced at      input line");
  REQUIRE(at != std::string::npos);
  // Each named line is a G1 of the input.
  std::istringstream named(c.err.substr(c.err.find_first_of("0123456789", at)));
  int line = 0;
  int count = 0;
  while (named >> line) {
    std::istringstream text(dome);
    std::string l;
    for (int k = 0; k < line; ++k) std::getline(text, l);
    CHECK(l.rfind("G1 X", 0) == 0);
    ++count;
    if (named.peek() == ',') named.ignore();
  }
  CHECK(count >= 1);
  // The joints over the G1 angle as read back are named, each one the fit reported forced.
  CHECK(c.err.find(fmt::format("{} over 0.5 deg, each forced by the band or the digits", count)) != std::string::npos);
  auto kept = run_arcpress("--stats --method keep", dome);
  CHECK(kept.err.find("forced at") == std::string::npos);
}

TEST_CASE("diff passes a compressed program within the band and fails it outside", "[cli][diff]") {
  auto d = arcpress::test::temp_dir("diff");
  fs::path in = fs::path(ARCPRESS_SOURCE_DIR) / "samples" / "contour.nc";
  fs::path out = d / "out.nc";
  auto c = run_arcpress("'" + in.string() + "' -o '" + out.string() + "' --tolerance 0.01");
  REQUIRE(c.exit_code == 0);
  auto same = run_arcpress("diff '" + in.string() + "' '" + out.string() + "' --tolerance 0.01");
  CHECK(same.exit_code == 0);
  CHECK(same.out.find("SAME: max deviation") != std::string::npos);
  auto tight = run_arcpress("diff '" + in.string() + "' '" + out.string() + "' --tolerance 0.0001");
  CHECK(tight.exit_code == 1);
  CHECK(tight.out.find("DIFFERENT") != std::string::npos);
  CHECK(tight.out.find("line") != std::string::npos);
  // A program whose path leaves the original's is reported with its line.
  arcpress::test::write_file(d / "moved.nc", "G21 G90 G17\nG0 Z5.000\nG0 X20.000 Y0.000\nG1 X21 Y3 F800\nM2\n");
  auto moved = run_arcpress("diff '" + in.string() + "' '" + (d / "moved.nc").string() + "'");
  CHECK(moved.exit_code == 1);
  CHECK(moved.out.find("moved.nc") != std::string::npos);
}

TEST_CASE("with --units inch a program that never states its units is read as a controller that starts in inches reads it",
          "[cli][units]") {
  auto d = arcpress::test::temp_dir("units");
  // A circle of 1 inch radius in 48 moves: its chords lie 0.054 mm inside the circle.
  std::string program = "(a program in inches that never says so)\nG90 G17\nG0 X1 Y0\nG1 F20\n";
  for (int k = 1; k <= 48; ++k)
    program += fmt::format("G1 X{:.4f} Y{:.4f}\n", std::cos(k * 2 * M_PI / 48), std::sin(k * 2 * M_PI / 48));
  arcpress::test::write_file(d / "in.nc", program + "M2\n");
  const std::string in = "'" + (d / "in.nc").string() + "'";
  auto as_mm = run_arcpress(in + " -o '" + (d / "mm.nc").string() + "'");
  REQUIRE(as_mm.exit_code == 0);
  CHECK(as_mm.err.find("in.nc:3:4: warning: W-MODEL-UNITS") != std::string::npos);
  auto mm_in_inches = run_arcpress("diff " + in + " '" + (d / "mm.nc").string() + "' --units inch");
  CHECK(mm_in_inches.exit_code == 1);
  CHECK(mm_in_inches.out.find("DIFFERENT") != std::string::npos);
  auto as_inch = run_arcpress(in + " -o '" + (d / "inch.nc").string() + "' --units inch");
  REQUIRE(as_inch.exit_code == 0);
  CHECK(as_inch.err.find("W-MODEL-UNITS") == std::string::npos);
  CHECK(arcpress::test::read_file(d / "inch.nc").find(" --units inch)") != std::string::npos);
  CHECK(run_arcpress("diff " + in + " '" + (d / "inch.nc").string() + "' --units inch").exit_code == 0);
  CHECK(run_arcpress(in + " --units cm").exit_code == 2);
}

TEST_CASE("diff of a 2-D arc against its chord fails with the sagitta, and what it could not place is never a pass",
          "[cli][diff][2d]") {
  auto d = arcpress::test::temp_dir("diff-2d");
  arcpress::test::write_file(d / "arc.nc", "G21 G90\nG0 X10 Y0\nG2 X0 Y-10 I-10 J0 F100\nM2\n");
  arcpress::test::write_file(d / "chord.nc", "G21 G90\nG0 X10 Y0\nG1 X0 Y-10 F100\nM2\n");
  auto apart = run_arcpress("diff '" + (d / "arc.nc").string() + "' '" + (d / "chord.nc").string() + "'");
  CHECK(apart.exit_code == 1);
  CHECK(apart.out.find("DIFFERENT: max deviation 2.928932 mm outside the 0.01 mm band") != std::string::npos);
  auto json = run_arcpress("diff --json '" + (d / "arc.nc").string() + "' '" + (d / "chord.nc").string() + "'");
  CHECK(json.exit_code == 1);
  CHECK(json.out.find("\"verdict\": \"different\"") != std::string::npos);
  CHECK(json.out.find("\"max_deviation_mm\": 2.92893") != std::string::npos);
  // Moves set by expressions cannot be placed: the verdict is incomplete, exit 2, with the line.
  arcpress::test::write_file(d / "expr.nc", "G21 G90\nG0 X0 Y0\n#1=3\nG1 X[#1] F100\nG1 Y[#1]\nM2\n");
  auto open = run_arcpress("diff '" + (d / "expr.nc").string() + "' '" + (d / "expr.nc").string() + "'");
  CHECK(open.exit_code == 2);
  CHECK(open.out.find("2 feed move(s) not compared: their position is not known (first at line 4: position unknown "
                      "after flow control, a macro or parameter line, a subprogram or a host command at line 3)") !=
        std::string::npos);
  CHECK(open.out.find("INCOMPLETE: ") != std::string::npos);
  auto open_json = run_arcpress("diff --json '" + (d / "expr.nc").string() + "' '" + (d / "expr.nc").string() + "'");
  CHECK(open_json.exit_code == 2);
  CHECK(open_json.out.find("\"verdict\": \"incomplete\"") != std::string::npos);
  CHECK(open_json.out.find("\"unplaced_feed_moves\": 2, \"first_unplaced_line\": 4") != std::string::npos);
}

TEST_CASE("the stats list the G1 moves not fitted, by reason, and a program with none fitted is warned about",
          "[cli][stats]") {
  std::string t = "G21 G90\nG0 X0 Y0\n";
  for (int k = 1; k <= 10; ++k) t += fmt::format("G1 X{} Y{} F100 (step {})\n", k, k % 2, k);
  auto c = run_arcpress("--stats", t);
  CHECK(c.exit_code == 0);
  CHECK(c.out == t);
  CHECK(c.err.find("<stdin>:3:1: warning: W-FIT-NONE: none of the 10 G1 moves could be fitted; 10 of them: comment "
                   "in the block") != std::string::npos);
  CHECK(c.err.find("  not fitted     10 G1 moves: comment in the block (first at line 3)") != std::string::npos);
}

TEST_CASE("compression measures its own output and reports the deviation", "[cli]") {
  fs::path in = fs::path(ARCPRESS_SOURCE_DIR) / "samples" / "contour.nc";
  auto c = run_arcpress("'" + in.string() + "' --stats");
  CHECK(c.exit_code == 0);
  CHECK(c.out.find("G3 ") != std::string::npos);
  CHECK(c.err.find("mm max (band 0.01 mm, on the programmed path), input line ") != std::string::npos);
  // A path written back as it was has no worst place to name; the check measures it exactly
  // down to a twentieth of the band, and says so.
  auto kept = run_arcpress("--stats --method keep", kProgram);
  CHECK(kept.err.find("0.000000 mm max (band 0.01 mm, on the programmed path), under 0.000500 mm everywhere (measured no closer)\n") !=
        std::string::npos);
  auto n = run_arcpress("'" + in.string() + "' --stats --no-verify");
  CHECK(n.err.find("not measured") != std::string::npos);
}

TEST_CASE("arcpress dialects lists every shipped dialect, one line each", "[cli][dialect]") {
  auto c = run_arcpress("dialects");
  CHECK(c.exit_code == 0);
  size_t lines = std::count(c.out.begin(), c.out.end(), '\n');
  CHECK(lines == 19);
  CHECK(c.out.find("heidenhain-iso  Heidenhain TNC DIN/ISO") != std::string::npos);
}

TEST_CASE("a user's own dialect file (--dialect-file) is loaded, and its mistakes name the file and line", "[cli][dialect]") {
  auto dir = arcpress::test::temp_dir("dialect-file");
  arcpress::test::write_file(dir / "mine.toml", "name = \"mine\"\ndescription = \"lines only\"\n[arcs]\nenabled = false\n");
  std::string quarter = "G21 G90\nG0 X10 Y0 Z0\n";
  for (int k = 1; k <= 32; ++k) {
    double a = 3.14159265358979 / 2 * k / 32;
    quarter += "G1 X" + std::to_string(10 * std::cos(a)) + " Y" + std::to_string(10 * std::sin(a)) + " F100\n";
  }
  auto rs = run_arcpress("--dialect rs274", quarter);
  CHECK(rs.exit_code == 0);
  CHECK(rs.out.find("G3") != std::string::npos);
  auto mine = run_arcpress("--dialect-file " + (dir / "mine.toml").string(), quarter);
  CHECK(mine.exit_code == 0);
  CHECK(mine.out.find("G3") == std::string::npos);

  arcpress::test::write_file(dir / "bad.toml", "name = \"bad\"\n[arcs]\nenabeld = false\n");
  auto bad = run_arcpress("--dialect-file " + (dir / "bad.toml").string(), quarter);
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("bad.toml:3:1: arcs.enabeld: unknown key") != std::string::npos);
  CHECK(bad.out.empty());
}

TEST_CASE("R-form arcs for a controller that rejects them is a usage error", "[cli][dialect]") {
  auto c = run_arcpress("--dialect klipper --arc-format r", kProgram);
  CHECK(c.exit_code == 2);
  CHECK(c.err.find("klipper does not read R-form arcs") != std::string::npos);
}

TEST_CASE("every floating option must be a finite number in its range, and says so in one short line", "[cli][options]") {
  struct Case {
    std::string option, value, range;
  };
  const std::vector<Case> cases = {
      {"--tolerance", "nan", "from 0.00001 to 100 mm"},        {"--tolerance", "1e-300", "from 0.00001 to 100 mm"},
      {"--tolerance", "abc", "from 0.00001 to 100 mm"},        {"--tolerance", "-1", "from 0.00001 to 100 mm"},
      {"--g1-angle", "nan", "> 0 and <= 90 degrees"},          {"--corner-angle", "inf", "from 0 to 180 degrees"},
      {"--min-radius", "nan", "from 0 to 1000000 mm"},         {"--max-radius", "1e308", "> 0 and <= 1000000 mm"},
      {"--max-sweep", "nan", "from 1 to 359 degrees"},         {"--min-arc-length", "-inf", "from 0 to 10000 mm"},
  };
  for (const Case& c : cases) {
    INFO(c.option << " " << c.value);
    auto r = run_arcpress(c.option + " " + c.value, kProgram);
    CHECK(r.exit_code == 2);
    CHECK(r.out.empty());
    CHECK(r.err.find(c.option + ": must be a finite number " + c.range + ", got '" + c.value + "'") != std::string::npos);
    CHECK(r.err.size() < 200);
  }
  auto diff = run_arcpress("diff --tolerance nan a b");
  CHECK(diff.exit_code == 2);
  CHECK(diff.err.find("--tolerance: must be a finite number from 0.00001 to 100 mm, got 'nan'") != std::string::npos);
  auto crossed = run_arcpress("--min-radius 5 --max-radius 1", kProgram);
  CHECK(crossed.exit_code == 2);
  CHECK(crossed.err.find("--min-radius 5 mm is larger than --max-radius 1 mm") != std::string::npos);
}

TEST_CASE("with no input and a terminal on standard input, arcpress says how to use it instead of waiting",
          "[cli]") {
  if (std::system("command -v script > /dev/null 2>&1") != 0) {
    WARN("script (util-linux) is not installed: no terminal to test with, skipped");
    return;
  }
  // script(1) gives the program a terminal for its standard input.
  auto c = arcpress::test::run_shell("script -qec '\"$ARCPRESS\"' /dev/null");
  CHECK(c.exit_code == 2);
  CHECK(c.out.find("arcpress: no input: give a program file, or pipe one into standard input") != std::string::npos);
  CHECK(c.out.find("Usage:") != std::string::npos);
}

TEST_CASE("without --dialect a slicer's program is written for the firmware it names, and --stats says why",
          "[cli][dialect][flavor]") {
  std::string t = "; generated by PrusaSlicer 2.7.1\nG21 G90\nM83\nG0 X10 Y0 Z0.2\nG1 F1800\n";
  for (int k = 1; k <= 90; ++k)
    t += fmt::format("G1 X{:.3f} Y{:.3f} E0.01\n", 10 * std::cos(k * M_PI / 180), 10 * std::sin(k * M_PI / 180));
  t += "; prusaslicer_config = begin\n; gcode_flavor = klipper\n; prusaslicer_config = end\n";
  auto c = run_arcpress("--stats", t);
  CHECK(c.exit_code == 0);
  CHECK(c.err.find("dialect        klipper") != std::string::npos);
  CHECK(c.err.find("by the program's '; gcode_flavor = klipper' at line 97") != std::string::npos);
  // PrusaSlicer's default flavor, RepRap/Sprinter, names no single firmware: the default
  // dialect, and --stats says why and what to pass.
  std::string reprap = t;
  reprap.replace(reprap.find("= klipper"), 9, "= reprap");
  auto unnamed = run_arcpress("--stats", reprap);
  CHECK(unnamed.exit_code == 0);
  CHECK(unnamed.err.find("dialect        rs274") != std::string::npos);
  CHECK(unnamed.err.find(", by the default: the program's '; gcode_flavor = reprap' at line 97 names no single "
                         "firmware (pass --dialect marlin, klipper, reprapfirmware, smoothieware)\n") != std::string::npos);
  // A Prusa printer's model names which of Prusa's firmwares runs it, where the flavor says
  // Marlin: its start G-code's model check, or its config block's printer_model.
  std::string mk3 = t;
  mk3.replace(mk3.find("= klipper"), 9, "= marlin2\n; printer_model = MK3S");
  mk3.insert(mk3.find('\n') + 1, "M862.3 P \"MK3S\" ; printer model check\n");
  auto by_model = run_arcpress("--stats", mk3);
  CHECK(by_model.exit_code == 0);
  CHECK(by_model.err.find("dialect        prusa-mk3") != std::string::npos);
  CHECK(by_model.err.find("by the program's 'M862.3 P \"MK3S\" ; printer model check' at line 2") != std::string::npos);
  // Past the first MiB, a flavor near the end that names another firmware outranks the model
  // at the start (a Prusa profile moved to Klipper).
  const auto dir = arcpress::test::temp_dir("flavor-model");
  const auto big = dir / "big.gcode";
  std::string padding;
  while (padding.size() < (size_t(1) << 20) + 4096) padding += "; a comment to pad the program past its first MiB\n";
  std::string klipper_mk3 = mk3;
  klipper_mk3.replace(klipper_mk3.find("= marlin2"), 9, "= klipper");
  arcpress::test::write_file(big, klipper_mk3.substr(0, klipper_mk3.find("; prusaslicer_config")) + padding +
                                      klipper_mk3.substr(klipper_mk3.find("; prusaslicer_config")));
  auto outranked = run_arcpress("'" + big.string() + "' -o /dev/null --stats");
  CHECK(outranked.err.find("dialect        klipper") != std::string::npos);
  CHECK(outranked.err.find("by the program's '; gcode_flavor = klipper' near its end") != std::string::npos);
  arcpress::test::write_file(big, mk3.substr(0, mk3.find("; prusaslicer_config")) + padding +
                                      mk3.substr(mk3.find("; prusaslicer_config")));
  CHECK(run_arcpress("'" + big.string() + "' -o /dev/null --stats").err.find("dialect        prusa-mk3") !=
        std::string::npos);
  // A dialect named on the command line wins.
  auto named = run_arcpress("--stats --dialect marlin", t);
  CHECK(named.err.find("dialect        marlin") != std::string::npos);
  CHECK(named.err.find("by --dialect") != std::string::npos);
  // diff reads both programs as the first names itself: Klipper's G18 arcs turn the other
  // way from RS274's, so A's G2 is B's quarter circle read as RS274 and three quarters read
  // as Klipper.
  auto d = arcpress::test::temp_dir("flavor-diff");
  arcpress::test::write_file(d / "a.gcode",
                             "G21 G90 G18\nG0 X10 Y0 Z0\nG2 X0 Z10 I-10 K0 F100\nM2\n; gcode_flavor = klipper\n");
  std::string quarter = "G21 G90 G18\nG0 X10 Y0 Z0\nG1 F100\n";
  for (int k = 1; k <= 90; ++k)
    quarter += fmt::format("G1 X{:.4f} Z{:.4f}\n", 10 * std::cos(k * M_PI / 180), 10 * std::sin(k * M_PI / 180));
  arcpress::test::write_file(d / "b.gcode", quarter + "M2\n; gcode_flavor = klipper\n");
  const std::string files = " '" + (d / "a.gcode").string() + "' '" + (d / "b.gcode").string() + "' --tolerance 0.01";
  CHECK(run_arcpress("diff --dialect rs274" + files).exit_code == 0);
  CHECK(run_arcpress("diff --dialect klipper" + files).exit_code == 1);
  CHECK(run_arcpress("diff" + files).exit_code == 1);  // as A names itself: Klipper
}

TEST_CASE("without --dialect a Heidenhain ISO program is written for the TNC its first block names", "[cli][dialect][flavor]") {
  std::string t = "%ARC G71 *\nN10 G00 G90 X+10 Y+0 Z+0 *\nN20 G01 F300 *\n";
  for (int k = 1; k <= 90; ++k)
    t += fmt::format("N{} G01 X{:+.4f} Y{:+.4f} *\n", 20 + 10 * k, 10 * std::cos(k * M_PI / 180),
                     10 * std::sin(k * M_PI / 180));
  t += "N99999999 %ARC G71 *\n";
  auto c = run_arcpress("--stats --tolerance 0.01", t);
  CHECK(c.exit_code == 0);
  CHECK(c.err.find("dialect        heidenhain-iso") != std::string::npos);
  CHECK(c.err.find("by the program's '%ARC G71 *' at line 1") != std::string::npos);
  // The centre itself (by the origin), as the TNC reads I/J: as offsets, RS274's, they would be I-9.99.. J+0.00..
  CHECK(c.out.find("N920 G03 X+0.0000 Y+10.0000 I+0.0028 J+0.0028 *\n") != std::string::npos);
}

TEST_CASE("a file that is not G-code is refused with exit 2, why, and nothing written", "[cli][foreign]") {
  auto d = arcpress::test::temp_dir("foreign");
  std::mt19937 rng(46);
  std::string noise(20000, '\0');
  for (char& c : noise) c = char(rng() & 0xff);
  std::string zipped = std::string("PK\x03\x04", 4) + "\x14\x00\x00\x00" + kProgram;  // a .3mf is a ZIP
  std::string bgcode = "GCDE" + std::string("\x01\x00\x00\x00", 4) + kProgram;
  // Points exported as a table: one readable block of four. (A line that starts with a
  // word and a space reads as a host command, as Klipper's `PRINT_START` does.)
  std::string table = "x,y\n1.0,2.0\n3.5,4.25\nG1 X1\n";
  for (const auto& [name, text, why] :
       {std::tuple{"noise.gcode", noise, "binary content: "}, std::tuple{"part.3mf", zipped, "a ZIP archive's signature"},
        std::tuple{"part.bgcode", bgcode, "a binary G-code (.bgcode) signature"},
        std::tuple{"points.csv", table, "3 of its 4 blocks cannot be read, the first at line 1"}}) {
    INFO(name);
    arcpress::test::write_file(d / name, text);
    arcpress::test::write_file(d / "out.nc", "kept\n");
    auto c = run_arcpress(fmt::format("'{}' -o '{}'", (d / name).string(), (d / "out.nc").string()));
    CHECK(c.exit_code == 2);
    CHECK(c.err.find(std::string(name) + ":") != std::string::npos);
    CHECK(c.err.find(": error: E-INPUT-NOT-GCODE: does not look like G-code (" + std::string(why)) != std::string::npos);
    CHECK(c.err.find("warning") == std::string::npos);  // its unreadable lines are no news
    CHECK(arcpress::test::read_file(d / "out.nc") == "kept\n");
    // To a pipe: not a byte.
    auto piped = run_arcpress("", text);
    CHECK(piped.exit_code == 2);
    CHECK(piped.out.empty());
    // diff never calls two such files the same.
    CHECK(run_arcpress(fmt::format("diff '{0}' '{0}'", (d / name).string())).exit_code == 2);
  }
}

TEST_CASE("a program with a few bad bytes or lines, NULs in comments or NUL padding is still G-code",
          "[cli][foreign]") {
  std::string program = "G21 G90\nG0 X0 Y0 Z1\nG1 Z0 F100\n";
  for (int k = 1; k <= 300; ++k) program += fmt::format("G1 X{:.3f} Y{:.3f}\n", 0.1 * k, std::sin(0.02 * k));
  // NUL bytes inside comments, and an SD card's NUL padding at the end.
  auto padded = run_arcpress("", "(note \x01\x02 here)\n; and \x03\x04\x05\x06 there\n" + program +
                                     std::string(4096, '\0'));
  CHECK(padded.exit_code == 0);
  // Seven control bytes outside comments: one short of the line, warned about, passed through.
  std::string seven = program;
  seven.insert(seven.find("G1 X0.500"), std::string("\x01\x02\x03\x04\x05\x06\x07\n", 8));
  auto bad = run_arcpress("", seven);
  CHECK(bad.exit_code == 0);
  CHECK(bad.err.find("warning: E-LEX-") != std::string::npos);
  CHECK(bad.out.find(std::string("\x01\x02\x03\x04\x05\x06\x07\n", 8)) != std::string::npos);
  // Eight in a short program: over the line.
  auto eight = run_arcpress("", "G21 G90\nG0 X0 Y0\n\x01\x02\x03\x04\x05\x06\x07\x08\nG1 X1 F100\nM2\n");
  CHECK(eight.exit_code == 2);
  // As many unreadable blocks as readable ones: still a program.
  auto half = run_arcpress("", "G21 G90\n1,2\nG1 X1 F100\n3,4\n");
  CHECK(half.exit_code == 0);
  auto more = run_arcpress("", "G21 G90\n1,2\nG1 X1 F100\n3,4\n5,6\n");
  CHECK(more.exit_code == 2);
  // Comments alone, or nothing, are programs with nothing to do.
  CHECK(run_arcpress("", "; only a comment\n(and another)\n").exit_code == 0);
  CHECK(run_arcpress("", "").exit_code == 0);
}
