// The firmware rules for cutting arcs into chords, each against cases worked out by hand
// from the firmware's formula (dialects/README.md names the source of each).
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "arcpress/dialect/arc_segmentation.hpp"
#include "arcpress/dialect/dialect_loader.hpp"

using namespace arcpress;
using Rule = ArcSegmentation::Rule;

namespace {

double deg(double d) { return d * std::numbers::pi / 180; }

ArcSegmentation rule(Rule r, double max_mm, double min_mm, int per_circle, double deviation_mm) {
  ArcSegmentation s;
  s.rule = r;
  s.max_segment_mm = max_mm;
  s.min_segment_mm = min_mm;
  s.min_circle_segments = per_circle;
  s.max_deviation_mm = deviation_mm;
  return s;
}

}  // namespace

TEST_CASE("Marlin 2.1 cuts an arc into whole 1 mm segments, at least 72 a circle, none under 0.1 mm", "[segmentation]") {
  const auto marlin = rule(Rule::Marlin, 1.0, 0.1, 72, 0);
  // r 10, a quarter turn: 15.708 mm, 15 whole segments, but 72 a circle asks 18 (0.873 mm each).
  CHECK(executed_segments(marlin, 10, deg(90)) == 18);
  // r 100, a quarter turn: 157 whole segments would be 1.0005 mm: ceil(157.08) = 158 instead.
  CHECK(executed_segments(marlin, 100, deg(90)) == 158);
  // r 0.5, a quarter turn: 18 segments would be 0.044 mm: floor(0.785 / 0.1) = 7 instead.
  CHECK(executed_segments(marlin, 0.5, deg(-90)) == 7);
  // r 1, 12 degrees: 3 segments of 0.070 mm are too short, floor(0.209 / 0.1) = 2.
  CHECK(executed_segments(marlin, 1, deg(12)) == 2);
  // An arc shorter than 0.1 mm is one chord.
  CHECK(executed_segments(marlin, 1, deg(5)) == 1);
}

TEST_CASE("Klipper cuts an arc into floor(length / resolution) segments, one chord under the resolution",
          "[segmentation]") {
  const auto klipper = rule(Rule::Klipper, 1.0, 0, 0, 0);
  CHECK(executed_segments(klipper, 10, deg(90)) == 15);       // 15.708 mm
  CHECK(executed_segments(klipper, 10, deg(90), 10) == 18);   // a helix: hypot(15.708, 10) = 18.62 mm
  CHECK(executed_segments(klipper, 1, deg(30)) == 1);         // 0.524 mm: one straight line
  // r 3, half a turn: 9 chords of 20 degrees, each 3 (1 - cos 10 deg) = 0.045577 mm inside the circle.
  CHECK(executed_segments(klipper, 3, deg(180)) == 9);
  CHECK(executed_sagitta_mm(klipper, 3, deg(180)) == Approx(0.0455767).margin(1e-7));
}

TEST_CASE("RepRapFirmware sizes segments for 0.005 mm deviation within 0.02 .. 1 mm and rounds up from 0.2",
          "[segmentation]") {
  const auto rrf = rule(Rule::RepRapFirmware, 1.0, 0.02, 0, 0.005);
  CHECK(executed_segments(rrf, 10, deg(90)) == 25);     // sqrt(0.4) = 0.632 mm: 24.84 + 0.8
  CHECK(executed_segments(rrf, 100, deg(90)) == 157);   // sqrt(4) = 2, clamped to 1 mm: 157.08 + 0.8
  CHECK(executed_segments(rrf, 0.01, deg(90)) == 1);    // 0.02 mm segments: 0.785 + 0.8
}

TEST_CASE("Grbl's mc_arc() makes floor(half the length / sqrt($12 (2r - $12))) segments, 0 meaning one chord",
          "[segmentation]") {
  const auto grbl = rule(Rule::Grbl, 0, 0, 0, 0.002);
  CHECK(executed_segments(grbl, 10, deg(90)) == 39);  // 7.854 / 0.19999 = 39.27
  // r 5, 3 degrees: 0.1309 / 0.1414 = 0.93: Grbl draws the chord, 5 (1 - cos 1.5 deg) off the circle.
  CHECK(executed_segments(grbl, 5, deg(3)) == 1);
  CHECK(executed_sagitta_mm(grbl, 5, deg(3)) == Approx(0.0017133).margin(1e-7));
}

TEST_CASE("Smoothieware sizes segments from mm_max_arc_error and takes their floor, one chord below two",
          "[segmentation]") {
  const auto smoothie = rule(Rule::Smoothieware, 0, 0, 0, 0.01);
  CHECK(executed_segments(smoothie, 10, deg(90)) == 17);  // 2 sqrt(0.01 x 19.99) = 0.894 mm: 17.57
  CHECK(executed_segments(smoothie, 1, deg(45)) == 2);    // 0.282 mm: 2.78
  CHECK(executed_segments(smoothie, 1, deg(15)) == 1);    // 0.93
  // A set mm_per_arc_segment longer than the error's segment wins.
  CHECK(executed_segments(rule(Rule::Smoothieware, 5, 0, 0, 0.01), 10, deg(90)) == 3);
}

TEST_CASE("a controller that moves on the circle has no chords and no sagitta", "[segmentation]") {
  const ArcSegmentation none;
  CHECK_FALSE(none.moves_on_chords());
  CHECK(executed_segments(none, 10, deg(90)) == 0);
  CHECK(executed_sagitta_mm(none, 10, deg(90)) == 0);
}

TEST_CASE("the shipped printer and Grbl dialects name their firmware's rule, and a wrong rule is refused with its place",
          "[segmentation][dialect]") {
  const auto path = dialect_search_path("");
  CHECK(find_dialect("marlin", path).executed.rule == Rule::Marlin);
  CHECK(find_dialect("klipper", path).executed.rule == Rule::Klipper);
  CHECK(find_dialect("reprapfirmware", path).executed.rule == Rule::RepRapFirmware);
  CHECK(find_dialect("grbl", path).executed.rule == Rule::Grbl);
  CHECK(find_dialect("grblhal", path).executed.rule == Rule::Grbl);
  CHECK(find_dialect("smoothieware", path).executed.rule == Rule::Smoothieware);
  CHECK_FALSE(find_dialect("fanuc", path).executed.moves_on_chords());
  CHECK(find_dialect("klipper", path).executed.max_segment_mm == 1.0);
  try {
    parse_dialect("name = \"x\"\n[arcs.executed]\nrule = \"marlin2\"\n", "bad.toml");
    FAIL("a wrong rule was read");
  } catch (const std::exception& e) {
    CHECK(std::string(e.what()).find("bad.toml:3:") != std::string::npos);
    CHECK(std::string(e.what()).find("arcs.executed.rule") != std::string::npos);
  }
}
