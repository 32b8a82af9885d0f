// SPDX-License-Identifier: GPL-3.0-or-later
// LinuxCNC's own interpreter as an independent judge of what arcpress writes for the
// linuxcnc dialect: `rs274 -i strict.ini -g` (the tightest arc-radius tolerance LinuxCNC
// allows, 0.001 mm) must read every compressed CNC corpus program exactly as far as it
// reads the original, and the path it reports must stay within the band of the path it
// reports for the original.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>

#include "arcpress/api/arcpress.hpp"
#include "arcpress/dialect/dialect_loader.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"
#include "support.hpp"

using namespace arcpress;
namespace fs = std::filesystem;

namespace {

/// What rs274 said about a program: its exit code, its error text, its canonical commands.
struct Rs274 {
  int exit_code = -1;
  std::string error;  ///< stderr without the "executing" banner
  std::string canon;  ///< stdout
};

Rs274 run_rs274(const fs::path& dir, const fs::path& program) {
  fs::path out = dir / "canon.txt", err = dir / "err.txt";
  // rs274 keeps its tool table in $HOME/.tool.mmap, truncated when it starts: with one HOME,
  // oracle tests running at once (ctest -j) would read each other's half-written tables.
  std::string cmd = fmt::format("HOME='{}' rs274 -i '{}' -t '{}' -g '{}' > '{}' 2> '{}'", dir.string(),
                                (dir / "strict.ini").string(), (dir / "tools.tbl").string(), program.string(),
                                out.string(), err.string());
  int status = std::system(cmd.c_str());
  Rs274 r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.canon = test::read_file(out);
  std::istringstream in(test::read_file(err));
  for (std::string line; std::getline(in, line);)
    if (line != "executing") r.error += line + "\n";
  return r;
}

/// Arguments of a canonical call "NAME(a, b, c)" as numbers.
std::vector<double> args_of(const std::string& line, size_t open) {
  std::vector<double> v;
  std::string inner = line.substr(open + 1, line.rfind(')') - open - 1);
  std::istringstream in(inner);
  for (std::string tok; std::getline(in, tok, ',');) v.push_back(std::strtod(tok.c_str(), nullptr));
  return v;
}

/// The motion of rs274's canonical output as a G-code program (absolute centres), so
/// arcpress's verifier can measure it. Coordinates are printed to 4 decimals by rs274.
std::string canon_to_gcode(const std::string& canon) {
  std::string g = "G90 G90.1 G17 G21\n";
  std::istringstream in(canon);
  const char* plane_axes[3][3] = {{"X", "Y", "Z"}, {"Z", "X", "Y"}, {"Y", "Z", "X"}};
  int plane = 0;
  std::string at;  // where the last move ended
  for (std::string line; std::getline(in, line);) {
    auto has = [&](const char* name) { return line.find(name); };
    if (size_t p = has("USE_LENGTH_UNITS("); p != std::string::npos) {
      g += line.find("INCHES") != std::string::npos ? "G20\n" : "G21\n";
    } else if (has("SELECT_PLANE(") != std::string::npos) {
      plane = line.find("_XZ") != std::string::npos ? 1 : line.find("_YZ") != std::string::npos ? 2 : 0;
      g += plane == 0 ? "G17\n" : plane == 1 ? "G18\n" : "G19\n";
    } else if (size_t t = has("STRAIGHT_TRAVERSE("); t != std::string::npos) {
      auto v = args_of(line, line.find('(', t));
      at = fmt::format("X{:.4f} Y{:.4f} Z{:.4f}", v[0], v[1], v[2]);
      g += "G0 " + at + "\n";
    } else if (size_t f = has("STRAIGHT_FEED("); f != std::string::npos) {
      auto v = args_of(line, line.find('(', f));
      // (A lone G1, which arcpress writes where flow control follows an arc, feeds to where
      // the tool is: no path.)
      const std::string to = fmt::format("X{:.4f} Y{:.4f} Z{:.4f}", v[0], v[1], v[2]);
      if (to != at) g += "G1 " + to + "\n";
      at = to;
    } else if (size_t a = has("ARC_FEED("); a != std::string::npos) {
      auto v = args_of(line, line.find('(', a));
      const char** ax = plane_axes[plane];
      const char* centre[3] = {"I", "J", "K"};
      auto centre_of = [&](const char* axis) { return centre[axis[0] - 'X']; };
      int rotation = int(v[4]);
      double end[3];
      end[ax[0][0] - 'X'] = v[0], end[ax[1][0] - 'X'] = v[1], end[ax[2][0] - 'X'] = v[5];
      at = fmt::format("X{:.4f} Y{:.4f} Z{:.4f}", end[0], end[1], end[2]);
      g += fmt::format("{} {}{:.4f} {}{:.4f} {}{:.4f} {}{:.4f} {}{:.4f}{}\n", rotation > 0 ? "G3" : "G2", ax[0], v[0],
                       ax[1], v[1], centre_of(ax[0]), v[2], centre_of(ax[1]), v[3], ax[2], v[5],
                       std::abs(rotation) > 1 ? fmt::format(" P{}", std::abs(rotation)) : "");
    }
  }
  return g;
}

bool rs274_available() { return std::system("command -v rs274 > /dev/null 2>&1") == 0; }

/// `text` compressed for the linuxcnc dialect, read back within the band.
CompressResult compressed_for_linuxcnc(const std::string& name, const std::string& text, double tolerance_mm = 0.01) {
  DiagnosticSink sink(name);
  CompressOptions opt;
  opt.fit.tolerance_mm = tolerance_mm;
  opt.dialect = load_dialect_file(ARCPRESS_SOURCE_DIR "/dialects/linuxcnc.toml");
  CompressResult r = compress(name, text, opt, sink);
  REQUIRE(r.ok);
  REQUIRE(r.within_band());
  return r;
}

/// Leaves the test case with a warning when LinuxCNC's rs274 is not installed.
#define RS274_OR_SKIP()                                                          \
  if (!rs274_available()) {                                                      \
    WARN("rs274 (Debian package linuxcnc-uspace) is not installed: skipped");    \
    return;                                                                      \
  }

/// A fresh folder holding what run_rs274() reads: the tightest arc-radius tolerance LinuxCNC
/// allows (0.001 mm), and a tool table with tools 1 .. `tools`.
test::TempDir rs274_folder(const std::string& tag, int tools = 1) {
  test::TempDir dir(tag);
  test::write_file(dir / "strict.ini",
                   "[RS274NGC]\nCENTER_ARC_RADIUS_TOLERANCE_MM = 0.001\nCENTER_ARC_RADIUS_TOLERANCE_INCH = 0.00004\n");
  std::string table;
  for (int t = 1; t <= tools; ++t) table += fmt::format("T{} P{} D3.0 ;\n", t, t);
  test::write_file(dir / "tools.tbl", table);
  return dir;
}

/// The path rs274 reads from the compressed program against the path it reads from the
/// original: move by move within the band. rs274 prints 4 decimals: end points and centres
/// each move by up to 0.00005 per axis, which moves an arc by up to 0.00015 mm.
void check_read_within_band(const Rs274& original, const Rs274& ours, double band_mm) {
  DiagnosticSink sa("rs274(original)"), sb("rs274(compressed)");
  Program pa = lex("rs274(original)", canon_to_gcode(original.canon), sa);
  Program pb = lex("rs274(compressed)", canon_to_gcode(ours.canon), sb);
  Interpretation ia = interpret(pa, sa), ib = interpret(pb, sb);
  CompareOptions co;
  co.tolerance_mm = band_mm;
  PathComparison c = compare_paths(pa, ia, pb, ib, co);
  INFO(c.mismatch);
  CHECK(c.matched);
  CHECK(c.max_deviation_mm <= band_mm + 0.00015);
}

}  // namespace

TEST_CASE("LinuxCNC's rs274 accepts every compressed CNC corpus program and reads it within the band",
          "[oracle][linuxcnc]") {
  RS274_OR_SKIP();
  ARCPRESS_CORPUS_FILES_OR_SKIP(files)
  auto dir = rs274_folder("rs274", 99);

  size_t judged = 0, arcs = 0;
  for (const auto& f : files) {
    if (f.parent_path().filename() == "printer") continue;  // CNC and laser programs only
    Rs274 original = run_rs274(dir, f);
    for (double tol : {0.01, 0.002}) {
      INFO(fmt::format("{} at tolerance {} mm", f.string(), tol));
      auto r = compressed_for_linuxcnc(f.string(), test::read_file(f), tol);
      arcs += r.stats.arcs_out;
      fs::path out = dir / "out.ngc";
      test::write_file(out, r.output);
      Rs274 ours = run_rs274(dir, out);
      // Accepted where the original is; where the original is refused (unknown M-codes, no
      // program end, its own arcs over the strict tolerance), refused for the same block.
      INFO("original: " << original.error << "compressed: " << ours.error);
      CHECK(ours.exit_code == original.exit_code);
      CHECK(ours.error == original.error);
      if (original.exit_code == 0) ++judged;

      // The path rs274 reads from our output against the path it reads from the original.
      check_read_within_band(original, ours, tol);
    }
  }
  CHECK(judged >= 5);
  CHECK(arcs > 1000);
}

namespace {

/// Parallel finishing over a dome (sphere of radius 15 mm, its top 5 mm above the floor),
/// under G17: passes along X at fixed Y, then passes along Y at fixed X, 0.2 mm steps,
/// coordinates printed to 4 decimals as CAM systems print them. The fixed coordinate steps
/// by `wander_mm` either way from move to move (a rotated frame's rounding), or stays.
std::string dome_raster(double wander_mm) {
  std::string g = "G21 G90 G17 G64\nG0 X-20 Y-6 Z5\nG1 Z0 F800\n";
  auto height = [](double u, double v) { return std::max(0.0, std::sqrt(std::max(0.0, 225 - u * u - v * v)) - 10); };
  // Six passes to and fro along X (along_x) or Y, the other coordinate fixed per pass.
  auto passes = [&](bool along_x) {
    for (int pass = 0; pass < 6; ++pass) {
      for (int k = 0; k <= 200; ++k) {
        double fixed = -5 + 2 * pass + wander_mm * ((k % 3) - 1);
        double u = (pass % 2 ? 20.0 : -20.0) + (pass % 2 ? -0.2 : 0.2) * k;
        double x = along_x ? u : fixed, y = along_x ? fixed : u;
        g += fmt::format("G1 X{:.4f} Y{:.4f} Z{:.4f}\n", x, y, height(x, y));
      }
    }
  };
  passes(true);
  g += "G0 Z5\nG0 X-6 Y-20\nG1 Z0\n";
  passes(false);
  g += "G0 Z5\nG2 X21 Y-20 I8 J0\nM2\n";
  return g;
}

/// Compresses `g` (dome_raster()) for LinuxCNC and checks that rs274 reads both programs, the
/// compressed one in G18 and G19 as well as G17, and the paths within the band.
void check_raster_planes(const std::string& g, const std::string& tag) {
  auto dir = rs274_folder(tag);
  test::write_file(dir / "raster.ngc", g);
  Rs274 original = run_rs274(dir, dir / "raster.ngc");
  REQUIRE(original.exit_code == 0);

  auto r = compressed_for_linuxcnc("raster.ngc", g);
  CHECK(r.stats.plane_words_added == 24);  // G18 or G19 before, G17 after, each pass
  CHECK(r.stats.arcs_out >= 12);
  CHECK(r.stats.arcs_out + r.stats.lines_out < 2000 / 10);  // 2424 moves in
  test::write_file(dir / "out.ngc", r.output);
  Rs274 ours = run_rs274(dir, dir / "out.ngc");
  INFO("compressed: " << ours.error);
  REQUIRE(ours.exit_code == 0);
  CHECK(ours.canon.find("SELECT_PLANE(CANON_PLANE_XZ)") != std::string::npos);
  CHECK(ours.canon.find("SELECT_PLANE(CANON_PLANE_YZ)") != std::string::npos);
  check_read_within_band(original, ours, r.band_mm);
}

}  // namespace

TEST_CASE("LinuxCNC's rs274 reads the G18 and G19 arcs of a raster finishing program within the band",
          "[oracle][linuxcnc][plane]") {
  RS274_OR_SKIP();
  check_raster_planes(dome_raster(0), "rs274-planes");
}

TEST_CASE("LinuxCNC's rs274 reads G18 and G19 arcs that carry a pass's wandering coordinate helically",
          "[oracle][linuxcnc][plane]") {
  RS274_OR_SKIP();
  // The fixed coordinate of each pass steps by a micron either way: within what a helical
  // arc carries, so the passes are still fitted in XZ and YZ.
  check_raster_planes(dome_raster(0.001), "rs274-planes-wander");
}

TEST_CASE("LinuxCNC's rs274 takes arcs that turn the A axis as they go, ending each at the input's A",
          "[oracle][linuxcnc][axes]") {
  RS274_OR_SKIP();
  // Half a circle of radius 10 mm in 1° steps; A turns 0.5° a step, then 1° a step.
  std::string g = "G21 G90 G17\nG0 X10.0000 Y0.0000 Z0 A0.0000\nG1 F600\n";
  for (int i = 1; i <= 180; ++i)
    g += fmt::format("G1 X{:.4f} Y{:.4f} A{:.4f}\n", 10 * std::cos(deg_to_rad(i)), 10 * std::sin(deg_to_rad(i)),
                     i <= 90 ? 0.5 * i : 45.0 + (i - 90));
  g += "M2\n";
  auto r = compressed_for_linuxcnc("rotary.ngc", g);
  REQUIRE(r.stats.arcs_out >= 2);

  auto dir = rs274_folder("rs274-rotary");
  test::write_file(dir / "out.ngc", r.output);
  Rs274 ours = run_rs274(dir, dir / "out.ngc");
  INFO("compressed: " << ours.error << r.output);
  REQUIRE(ours.exit_code == 0);
  // ARC_FEED(first end, second end, first centre, second centre, turn, normal end, A, B, C):
  // every arc ends at an A the input has at that place (a multiple of 0.5° up to 45°, of 1°
  // after), one of them where the rate changes.
  std::istringstream in(ours.canon);
  size_t arcs = 0;
  bool at_change = false;
  for (std::string line; std::getline(in, line);) {
    size_t p = line.find("ARC_FEED(");
    if (p == std::string::npos) continue;
    auto v = args_of(line, line.find('(', p));
    REQUIRE(v.size() >= 7);
    const double a = v[6], step = a <= 45 ? 0.5 : 1.0;
    CHECK(std::abs(a / step - std::round(a / step)) < 1e-6);
    at_change = at_change || std::abs(a - 45) < 1e-6;
    ++arcs;
  }
  CHECK(arcs == r.stats.arcs_out);
  CHECK(at_change);
}

namespace {

/// Compresses `g` for LinuxCNC and checks that rs274 accepts both programs and reads the
/// compressed one's path within the band of the original's; returns the compression.
CompressResult check_read_alike(const std::string& g, const std::string& tag) {
  auto dir = rs274_folder(tag);
  test::write_file(dir / "in.ngc", g);
  Rs274 original = run_rs274(dir, dir / "in.ngc");
  INFO("original: " << original.error);
  REQUIRE(original.exit_code == 0);
  CompressResult r = compressed_for_linuxcnc(tag + ".ngc", g);
  test::write_file(dir / "out.ngc", r.output);
  Rs274 ours = run_rs274(dir, dir / "out.ngc");
  INFO("compressed: " << ours.error << r.output);
  REQUIRE(ours.exit_code == 0);
  check_read_within_band(original, ours, r.band_mm);
  return r;
}

}  // namespace

TEST_CASE("LinuxCNC's rs274 reads the G18 arcs of a lathe program that never writes Y within the band",
          "[oracle][linuxcnc][lathe]") {
  RS274_OR_SKIP();
  // Radius mode (G8): a convex profile of two quarter circles, 1° steps, X and Z only.
  std::string g = "G21 G18 G8 G90\nG0 X0 Z1\nG1 Z0 F50\n";
  for (int k = 1; k <= 90; ++k)
    g += fmt::format("G1 X{:.4f} Z{:.4f}\n", 6 * std::sin(deg_to_rad(k)), 6 * std::cos(deg_to_rad(k)) - 6);
  for (int k = 1; k <= 90; ++k)
    g += fmt::format("G1 X{:.4f} Z{:.4f}\n", 6 + 4 * (1 - std::cos(deg_to_rad(k))), -6 - 4 * std::sin(deg_to_rad(k)));
  g += "G0 X12\nM2\n";
  CompressResult r = check_read_alike(g, "rs274-lathe");
  CHECK(r.stats.arcs_out >= 2);
  CHECK(r.stats.arcs_out + r.stats.lines_out <= 5);
  CHECK(r.output.find('Y') == std::string::npos);
}

TEST_CASE("LinuxCNC's rs274 reads a compressed 2-D laser program that never writes Z within the band",
          "[oracle][linuxcnc][2d]") {
  RS274_OR_SKIP();
  // A rounded rectangle, 30 x 20 mm with 5 mm corners in 3° steps, power on every move.
  std::string g = "G21 G90\nG0 X5 Y0\nM4 S0\n";
  auto corner = [&](double cx, double cy, int from_deg) {
    for (int k = 1; k <= 30; ++k) {
      const double a = deg_to_rad(from_deg + 3 * k);
      g += fmt::format("G1 X{:.4f} Y{:.4f} F1500 S700\n", cx + 5 * std::cos(a), cy + 5 * std::sin(a));
    }
  };
  g += "G1 X25 Y0 F1500 S700\n";
  corner(25, 5, -90);
  g += "G1 X30 Y15 F1500 S700\n";
  corner(25, 15, 0);
  g += "G1 X5 Y20 F1500 S700\n";
  corner(5, 15, 90);
  g += "G1 X0 Y5 F1500 S700\n";
  corner(5, 5, 180);
  g += "M5\nM2\n";
  CompressResult r = check_read_alike(g, "rs274-laser");
  CHECK(r.stats.arcs_out == 4);
  CHECK(r.stats.lines_out == 4);
  CHECK(r.output.find('Z') == std::string::npos);
}

TEST_CASE("LinuxCNC's rs274 reads a program's subroutines, called in G91 and leaving G91 and G18, within the band",
          "[oracle][linuxcnc][subroutines]") {
  RS274_OR_SKIP();
  // A quarter circle of radius 10 mm in 30 moves, as increments (`relative`) or absolute
  // from (x0, y0).
  auto quarter = [](bool relative, double x0, double y0, const char* axes = "XY") {
    std::string t;
    for (int k = 1; k <= 30; ++k) {
      const double a = deg_to_rad(3 * k), b = deg_to_rad(3 * (k - 1));
      const double u = relative ? 10 * (std::sin(a) - std::sin(b)) : x0 + 10 * std::sin(a);
      const double v = relative ? 10 * (std::cos(a) - std::cos(b)) : y0 + 10 * std::cos(a) - 10;
      t += fmt::format("G1 {}{:.4f} {}{:.4f}\n", axes[0], u, axes[1], v);
    }
    return t;
  };
  // o100's increments run in the G91 of its call; o200 states G91 itself and leaves G91 and
  // G18 in force after its call (rs274 -g), so the program's next moves are increments in XZ.
  std::string g = "G21 G17 G90\nG1 F300\n";
  g += "o100 sub\n" + quarter(true, 0, 0) + "o100 endsub\n";
  g += "o200 sub\nG91\n" + quarter(true, 0, 0) + "G18\no200 endsub\n";
  g += "G0 X0 Y0 Z0\nG91\no100 call\nG90\nG0 X40 Y0\no200 call\n" + quarter(true, 0, 0, "XZ");
  g += "G90 G17\nG0 X0 Y40\n" + quarter(false, 0, 40) + "M2\n";
  const CompressResult r = check_read_alike(g, "rs274-subroutines");
  // Every quarter becomes one arc but o100's, whose mode is its caller's.
  CHECK(r.stats.arcs_out == 3);
  CHECK(r.output.find("o100 sub\n" + quarter(true, 0, 0) + "o100 endsub\n") != std::string::npos);
}

TEST_CASE("LinuxCNC's rs274 reads the moves after an O-word if or loop whose branch changed G90 or G91 within the band",
          "[oracle][linuxcnc][subroutines]") {
  RS274_OR_SKIP();
  std::string quarter;
  for (int k = 1; k <= 30; ++k)
    quarter += fmt::format("G1 X{:.4f} Y{:.4f}\n", 10 * std::sin(deg_to_rad(3 * k)), 10 * std::cos(deg_to_rad(3 * k)) - 10);
  // The branch is not taken (rs274 evaluates #1): the moves after it are increments, though the
  // branch's G90 is the last distance word before them in the text.
  const std::string head = "G21 G17 G90\n#1 = 1\nG0 X0 Y0\nG1 F300\nG91\n";
  for (const std::string block : {"o1 if [#1 GT 2]\n  G90\no1 endif\n",
                                  "o1 if [#1 GT 2]\n  G90\no1 else\n  M3 S100\no1 endif\n",
                                  "o2 while [#1 GT 2]\n  G90\n  #1 = [#1 - 1]\no2 endwhile\n",
                                  "o3 repeat [0]\n  G90\no3 endrepeat\n"}) {
    INFO(block);
    const CompressResult r = check_read_alike(head + block + quarter + "M2\n", "rs274-o-blocks");
    CHECK(r.stats.arcs_out == 0);
    // Once the program states G90, its moves are fitted.
    CHECK(check_read_alike(head + block + "G90\n" + quarter + "M2\n", "rs274-o-blocks").stats.arcs_out == 1);
  }
}

TEST_CASE("LinuxCNC's rs274 runs a loop's first moves again in the modes its end leaves, and arcpress writes them as they are",
          "[oracle][linuxcnc]") {
  RS274_OR_SKIP();
  std::string quarter;  // absolute places within 10 mm of the origin
  for (int k = 1; k <= 30; ++k)
    quarter += fmt::format("G1 X{:.4f} Y{:.4f}\n", 10 * std::sin(deg_to_rad(3 * k)), 10 * std::cos(deg_to_rad(3 * k)) - 10);
  const std::string g91 = "G21 G17 G90\nG0 X0 Y0\nG1 F300\no1 repeat [2]\n" + quarter + "G91 G1 Z0.2\no1 endrepeat\nG90\nM2\n";
  auto dir = rs274_folder("rs274-loop-modes");
  test::write_file(dir / "in.ngc", g91);
  const Rs274 original = run_rs274(dir, dir / "in.ngc");
  REQUIRE(original.exit_code == 0);
  // The second time round, rs274 reads the same words as increments: it goes far past 10 mm.
  double farthest_mm = 0;
  std::istringstream canon(original.canon);
  for (std::string line; std::getline(canon, line);)
    if (const size_t open = line.find("STRAIGHT_FEED("); open != std::string::npos)
      farthest_mm = std::max(farthest_mm, std::abs(args_of(line, open + 13).at(0)));
  CHECK(farthest_mm > 50);
  // A loop that ends in G18: the same moves, in XY the first time, are the lines of the XZ
  // plane after; an arc fitted in XY would be one in XZ (J read in the XZ plane, which rs274
  // refuses).
  const std::string g18 = "G21 G17 G90\nG0 X0 Y0 Z0\nG1 F300\n#1=0\no2 do\n" + quarter + "G18\n#1=[#1+1]\no2 while [#1 LT 2]\nM2\n";
  // No one output of those words runs both passes: they are written as they are, and rs274
  // runs the output as it runs the input.
  for (const auto& [g, tag] : {std::pair{g91, "rs274-loop-g91"}, std::pair{g18, "rs274-loop-g18"}}) {
    INFO(tag);
    CHECK(check_read_alike(g, tag).stats.arcs_out == 0);
    CompressOptions opt;
    opt.dialect = load_dialect_file(ARCPRESS_SOURCE_DIR "/dialects/linuxcnc.toml");
    DiagnosticSink sink;
    CHECK(compress("loop.ngc", g, opt, sink).ok);
    CHECK(std::any_of(sink.all().begin(), sink.all().end(), [](const Diagnostic& d) { return d.code == "W-FLOW-LOOP-MODES"; }));
  }
  // With the modes stated at the loop's start, both passes are the quarter circle, fitted as
  // rs274 reads it.
  std::string stated = g91;
  stated.insert(stated.find("o1 repeat [2]\n") + 14, "G90\n");
  CHECK(check_read_alike(stated, "rs274-loop-g90").stats.arcs_out >= 1);
  std::string planed = g18;
  planed.insert(planed.find("o2 do\n") + 6, "G17\n");
  CHECK(check_read_alike(planed, "rs274-loop-g17").stats.arcs_out >= 1);
}

namespace {

/// A LinuxCNC program of flow control drawn from `seed`: arcs written as short lines in the
/// plane in force, in blocks (`if`/`else`, `do`, `while`, `repeat`, nested) between which the
/// plane, the units, G90 and the motion change, as rs274 follows them.
std::string random_flow_program(uint32_t seed) {
  std::mt19937 rng(seed);
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  auto pick = [&](int n) { return int(rng() % uint32_t(n)); };
  std::string g = fmt::format("G21 G17 G90 G94\nG0 X0 Y0 Z0\nG1 F300\n#2={}\n", pick(2));
  int plane = 0;
  auto arc = [&] {  // an arc of 10 to 40 lines in the plane in force
    const double r = uniform(3, 20), a0 = uniform(0, 6.28), sweep = uniform(0.5, 2.5) * (pick(2) ? 1 : -1);
    const double cx = uniform(-5, 5), cy = uniform(-5, 5);
    const int n = 10 + pick(31);
    const char* axes[3][2] = {{"X", "Y"}, {"Z", "X"}, {"Y", "Z"}};
    std::string t;
    for (int i = 0; i <= n; ++i) {
      const double a = a0 + sweep * i / n;
      t += fmt::format("{}{:.4f} {}{:.4f}\n", axes[plane][0], cx + r * std::cos(a), axes[plane][1], cy + r * std::sin(a));
    }
    return t;
  };
  struct Open {
    int label;
    int kind;  // 0 if, 1 do, 2 while, 3 repeat
  };
  std::vector<Open> open;
  auto close = [&](const Open& o) {
    const int counter = o.label + 10;
    if (o.kind == 0) g += fmt::format("o{} endif\n", o.label);
    if (o.kind == 1) g += fmt::format("#{0}=[#{0}+1]\no{1} while [#{0} LT 2]\n", counter, o.label);
    if (o.kind == 2) g += fmt::format("#{0}=[#{0}+1]\no{1} endwhile\n", counter, o.label);
    if (o.kind == 3) g += fmt::format("o{} endrepeat\n", o.label);
  };
  int label = 10;
  for (int k = 3 + pick(10); k > 0; --k) {
    const int t = pick(100);
    if (t < 25) {
      g += "G1 " + arc();
    } else if (t < 35) {
      plane = pick(3);
      g += fmt::format("G{}\n", 17 + plane);
    } else if (t < 42) {
      const char* modes[] = {"G90", "G0 Z1", "G1", "G20", "G21"};
      g += std::string(modes[pick(5)]) + "\n";
    } else if (t < 55 && open.size() < 3) {
      const Open o{++label, pick(4)};
      if (o.kind == 0) g += fmt::format("o{} if [#2 EQ {}]\n", o.label, pick(2));
      if (o.kind == 1) g += fmt::format("#{}=0\no{} do\n", o.label + 10, o.label);
      if (o.kind == 2) g += fmt::format("#{0}=0\no{1} while [#{0} LT 2]\n", o.label + 10, o.label);
      if (o.kind == 3) g += fmt::format("o{} repeat [2]\n", o.label);
      open.push_back(o);
    } else if (t < 62 && !open.empty()) {
      if (open.back().kind == 0 && pick(2)) {
        g += fmt::format("o{} else\n", open.back().label);
        continue;
      }
      close(open.back());
      open.pop_back();
    } else {
      g += arc();
    }
  }
  for (; !open.empty(); open.pop_back()) close(open.back());
  return g + "M2\n";
}

}  // namespace

TEST_CASE("LinuxCNC's rs274 runs random programs of flow control as arcpress's output of them, within the band",
          "[oracle][linuxcnc][property]") {
  RS274_OR_SKIP();
  // Blocks, loops and branches between which the plane, the units, G90 and the motion
  // change: rs274 runs each output as it runs its input (before loops were read as jumps
  // back, 25 of the first 400 such programs came out as arcs rs274 refuses, "J word given
  // for arc in xz plane", or runs elsewhere).
  auto dir = rs274_folder("rs274-flow");
  size_t compared = 0;
  for (uint32_t seed = 0; seed < 120; ++seed) {
    const std::string g = random_flow_program(seed);
    test::write_file(dir / "in.ngc", g);
    const Rs274 original = run_rs274(dir, dir / "in.ngc");
    if (original.exit_code != 0 || !original.error.empty()) continue;  // (a program rs274 itself refuses)
    INFO("seed " << seed << "\n" << g);
    const CompressResult r = compressed_for_linuxcnc("flow.ngc", g);
    test::write_file(dir / "out.ngc", r.output);
    const Rs274 ours = run_rs274(dir, dir / "out.ngc");
    INFO("compressed: " << ours.error << r.output);
    REQUIRE(ours.exit_code == 0);
    CHECK(ours.error.empty());
    // (rs274 prints lengths to 4 decimals of the unit in force: in inches, 0.00127 mm.)
    check_read_within_band(original, ours, r.band_mm + (g.find("G20") != std::string::npos ? 0.00127 : 0));
    ++compared;
  }
  CHECK(compared >= 100);
}
