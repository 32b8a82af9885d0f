// SPDX-License-Identifier: GPL-3.0-or-later
// --band executed and `diff --executed`: the band held on the chords the firmware moves along.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "support.hpp"

using namespace arcpress::test;

namespace {

/// Half a circle of radius `r_mm` about (50, 50) in 1-degree G1 moves, printed to 3 decimals.
std::string half_circle(double r_mm) {
  std::string p = "G21 G90 G17\nG0 X" + fmt::format("{:.3f}", 50 + r_mm) + " Y50\nG1 F1200\n";
  for (int i = 1; i <= 180; ++i)
    p += fmt::format("G1 X{:.3f} Y{:.3f}\n", 50 + r_mm * std::cos(i * M_PI / 180), 50 + r_mm * std::sin(i * M_PI / 180));
  return p + "M2\n";
}

}  // namespace

TEST_CASE("with --band executed the chords the firmware cuts each arc into stay in the band, with --band program they "
          "may not, and diff --executed says so",
          "[cli][executed]") {
  auto dir = temp_dir("executed");
  const auto in = dir / "in.gcode";
  write_file(in, half_circle(3.0));
  // Klipper cuts a 3 mm radius into 1 mm chords, 0.04 mm inside the circle: four times the band.
  const std::string io = fmt::format("{} --tolerance 0.01 --dialect klipper", in.string());
  REQUIRE(run_arcpress(io + " --band program -o " + (dir / "program.gcode").string()).exit_code == 0);
  REQUIRE(run_arcpress(io + " -o " + (dir / "executed.gcode").string()).exit_code == 0);
  CHECK(read_file(dir / "program.gcode").find("G3") != std::string::npos);
  const std::string diff = fmt::format("diff {} ", in.string());
  auto programmed = run_arcpress(diff + (dir / "program.gcode").string() + " --dialect klipper --tolerance 0.01");
  CHECK(programmed.exit_code == 0);
  auto executed = run_arcpress(diff + (dir / "program.gcode").string() + " --dialect klipper --tolerance 0.01 --executed");
  CHECK(executed.exit_code == 1);
  CHECK(executed.out.find("DIFFERENT") != std::string::npos);
  auto held = run_arcpress(diff + (dir / "executed.gcode").string() + " --dialect klipper --tolerance 0.01 --executed");
  CHECK(held.exit_code == 0);
  INFO(held.out);
  CHECK(held.out.find("SAME") != std::string::npos);
}

TEST_CASE("every firmware rule's dialect holds the band on its executed path by default, at any radius",
          "[cli][executed]") {
  auto dir = temp_dir("executed_rules");
  for (const char* dialect : {"marlin", "klipper", "reprapfirmware", "grbl", "smoothieware", "prusa", "prusa-mk3"}) {
    for (double r : {0.8, 3.0, 40.0}) {
      INFO(dialect << " r " << r);
      const auto in = dir / "in.gcode", out = dir / "out.gcode";
      write_file(in, half_circle(r));
      auto c = run_arcpress(fmt::format("{} -o {} --tolerance 0.01 --dialect {} --stats", in.string(), out.string(), dialect));
      REQUIRE(c.exit_code == 0);
      CHECK(c.err.find("on the path") != std::string::npos);
      auto d = run_arcpress(
          fmt::format("diff {} {} --tolerance 0.01 --dialect {} --executed", in.string(), out.string(), dialect));
      CHECK(d.exit_code == 0);
    }
  }
}

TEST_CASE("the executed band (--band executed, diff --executed) is refused for a dialect whose controller moves on the circle", "[cli][executed]") {
  auto dir = temp_dir("executed_none");
  const auto in = dir / "in.gcode";
  write_file(in, half_circle(3.0));
  auto c = run_arcpress(fmt::format("{} --dialect fanuc --band executed", in.string()));
  CHECK(c.exit_code == 2);
  CHECK(c.err.find("names no arc segmentation") != std::string::npos);
  auto d = run_arcpress(fmt::format("diff {} {} --dialect fanuc --executed", in.string(), in.string()));
  CHECK(d.exit_code == 2);
}

TEST_CASE("printer programs compressed for Klipper, Marlin and RepRapFirmware read back the same with diff, on the "
          "programmed path and on the firmware's chords",
          "[cli][executed][printer]") {
  auto dir = temp_dir("printer_diff");
  for (const auto& f : corpus_files()) {
    if (f.parent_path().filename() != "printer" || std::filesystem::file_size(f) > 200000) continue;
    for (const char* dialect : {"klipper", "marlin", "reprapfirmware"}) {
      INFO(f.filename().string() << " as " << dialect);
      const auto out = dir / "out.gcode";
      REQUIRE(run_arcpress(fmt::format("'{}' -o {} --dialect {} -q", f.string(), out.string(), dialect)).exit_code == 0);
      const std::string diff = fmt::format("diff '{}' {} --dialect {}", f.string(), out.string(), dialect);
      auto program = run_arcpress(diff);
      CHECK(program.exit_code == 0);
      CHECK(program.out.find("SAME") != std::string::npos);
      CHECK(run_arcpress(diff + " --executed").exit_code == 0);
      const std::string written = read_file(out);
      CHECK((written.find("\nG2 ") != std::string::npos || written.find("\nG3 ") != std::string::npos));
    }
  }
}

TEST_CASE("a spiral vase (Z rising along the perimeter) becomes helical arcs for Marlin, inside the band on its chords",
          "[cli][executed][printer]") {
  auto dir = temp_dir("vase");
  std::string p = "; generated by a slicer in spiral vase mode\nG21 G90 M83\nG0 X70 Y50 Z0.2\nG1 F1800\n";
  for (int i = 1; i <= 3 * 360; ++i) {  // three turns of radius 20, 0.3 mm a turn, a move every 2 degrees
    if (i % 2) continue;
    const double a = i * M_PI / 180;
    p += fmt::format("G1 X{:.3f} Y{:.3f} Z{:.4f} E{:.5f}\n", 50 + 20 * std::cos(a), 50 + 20 * std::sin(a),
                     0.2 + 0.3 * i / 360.0, 0.0233);
  }
  const auto in = dir / "vase.gcode", out = dir / "out.gcode";
  write_file(in, p);
  auto c = run_arcpress(fmt::format("{} -o {} --dialect marlin --stats", in.string(), out.string()));
  REQUIRE(c.exit_code == 0);
  const std::string written = read_file(out);
  // Few blocks, each an arc that climbs.
  size_t arcs = 0, climbing = 0;
  for (size_t at = written.find("\nG3 "); at != std::string::npos; at = written.find("\nG3 ", at + 1)) {
    ++arcs;
    const std::string line = written.substr(at + 1, written.find('\n', at + 1) - at - 1);
    climbing += line.find(" Z") != std::string::npos;
  }
  CHECK(arcs >= 6);
  CHECK(arcs <= 60);
  CHECK(climbing == arcs);
  CHECK(run_arcpress(fmt::format("diff {} {} --dialect marlin --executed", in.string(), out.string())).exit_code == 0);
  CHECK(run_arcpress(fmt::format("diff {} {} --dialect marlin", in.string(), out.string())).exit_code == 0);
}

TEST_CASE("a program that already holds arcs (PrusaSlicer 2.6 and later, OrcaSlicer) is compressed around them: its "
          "own arcs are written back as they are",
          "[cli][printer]") {
  auto dir = temp_dir("arcs_in");
  // A slicer's perimeter: an arc it fitted itself, then 60 G1 moves along a circle, then its next arc.
  std::string p = "; generated by PrusaSlicer 2.7.1\nG21 G90 M83\nG0 X60 Y50\nG1 F1800\n";
  p += "G3 X50 Y60 I-10 J0 E.5\n";
  for (int i = 1; i <= 60; ++i) {
    const double a = M_PI / 2 + i * M_PI / 120;
    p += fmt::format("G1 X{:.3f} Y{:.3f} E.0131\n", 50 + 10 * std::cos(a), 50 + 10 * std::sin(a));
  }
  p += "G3 X60 Y50 I10 J0 E.5\nM2\n";
  const auto in = dir / "in.gcode", out = dir / "out.gcode";
  write_file(in, p);
  REQUIRE(run_arcpress(fmt::format("{} -o {} --dialect marlin", in.string(), out.string())).exit_code == 0);
  const std::string written = read_file(out);
  CHECK(written.find("\nG3 X50 Y60 I-10 J0 E.5\n") != std::string::npos);
  CHECK(written.find("\nG3 X60 Y50 I10 J0 E.5\n") != std::string::npos);
  CHECK(std::count(written.begin(), written.end(), '\n') < std::count(p.begin(), p.end(), '\n') - 50);
  CHECK(run_arcpress(fmt::format("diff {} {} --dialect marlin", in.string(), out.string())).exit_code == 0);
  CHECK(run_arcpress(fmt::format("diff {} {} --dialect marlin --executed", in.string(), out.string())).exit_code == 0);
}

TEST_CASE("no corpus output leaves the band on the chord ends its firmware computes: every printer dialect on the "
          "printer files, Grbl and grblHAL on the CNC files",
          "[cli][executed][corpus]") {
  auto dir = temp_dir("executed_corpus");
  size_t checked = 0;
  for (const auto& f : corpus_files()) {
    const std::string kind = f.parent_path().filename().string();
    if (kind != "printer" && kind != "cnc") continue;
    const auto dialects = kind == "printer" ? std::vector<std::string>{"marlin", "klipper", "reprapfirmware", "smoothieware", "prusa",
                                                                                "prusa-mk3"}
                                            : std::vector<std::string>{"grbl", "grblhal"};
    for (const std::string& dialect : dialects) {
      INFO(f.filename().string() << " as " << dialect);
      const auto out = dir / "out.gcode";
      REQUIRE(run_arcpress(fmt::format("'{}' -o {} --dialect {} --tolerance 0.01 -q", f.string(), out.string(), dialect))
                  .exit_code == 0);
      const std::string diff = fmt::format("diff '{}' {{}} --dialect {} --tolerance 0.01 --executed", f.string(), dialect);
      // A CNC program whose own moves cannot all be placed (moves by expressions, an R too
      // short) is incomplete against itself too; every other is the same as its output.
      const int itself =
          kind == "printer" ? 0 : run_arcpress(fmt::format(fmt::runtime(diff), "'" + f.string() + "'")).exit_code;
      auto d = run_arcpress(fmt::format(fmt::runtime(diff), out.string()));
      CHECK(d.exit_code == itself);
      CHECK(d.exit_code != 1);
      ++checked;
    }
  }
  if (checked == 0) WARN("corpus folder " ARCPRESS_CORPUS_DIR " is absent: skipped");
}
