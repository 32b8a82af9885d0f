// SPDX-License-Identifier: GPL-3.0-or-later
// The firmware rules for cutting arcs into chords, each against cases worked out by hand
// from the firmware's formula (dialects/README.md names the source of each).
#include <catch2/catch.hpp>

#include <cmath>
#include <initializer_list>
#include <vector>
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

/// An arc of `radius_mm` turning by `sweep_deg`, and the segments the firmware cuts it into.
struct Count {
  double radius_mm, sweep_deg;
  uint32_t segments;
};

void check_counts(const ArcSegmentation& s, std::initializer_list<Count> counts) {
  for (const Count& c : counts) {
    INFO("r " << c.radius_mm << " mm, " << c.sweep_deg << " deg");
    CHECK(executed_segments(s, c.radius_mm, deg(c.sweep_deg)) == c.segments);
  }
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
  check_counts(rrf, {{10, 90, 25},     // sqrt(0.4) = 0.632 mm: 24.84 + 0.8
                     {100, 90, 157},   // sqrt(4) = 2, clamped to 1 mm: 157.08 + 0.8
                     {0.01, 90, 1}});  // 0.02 mm segments: 0.785 + 0.8
}

TEST_CASE("Prusa's Buddy firmware counts as RepRapFirmware does with 0.02 mm deviation within 0.1 .. 2 mm",
          "[segmentation]") {
  const auto buddy = rule(Rule::PrusaBuddy, 2.0, 0.1, 0, 0.02);
  check_counts(buddy, {{10, 90, 13},     // sqrt(1.6) = 1.265 mm: 12.42 + 0.8
                       {100, 90, 79},    // sqrt(16) = 4, clamped to 2 mm: 78.54 + 0.8
                       {0.05, 90, 1}});  // 0.1 mm segments: 0.785 + 0.8
  // r 30, 2.38 mm of arc: 1.19 segments of 2 mm, rounded down to one chord 0.0236 mm off the
  // circle, where Marlin's rule at 2 mm would cut two (0.0059 mm off).
  CHECK(executed_segments(buddy, 30, 2.38 / 30) == 1);
  CHECK(executed_sagitta_mm(buddy, 30, 2.38 / 30) == Approx(0.0236).margin(1e-4));
  CHECK(executed_segments(rule(Rule::Marlin, 2.0, 0.1, 0, 0), 30, 2.38 / 30) == 2);
}

TEST_CASE("the MK3's firmware cuts segments of a 20th of the circle within 0.5 .. 1 mm and rounds their count up",
          "[segmentation]") {
  const auto mk3 = rule(Rule::PrusaMk3, 1.0, 0.5, 20, 0);
  CHECK(executed_segments(mk3, 10, deg(90)) == 16);   // 3.14 mm, held to 1 mm: 15.7 rounded up
  CHECK(executed_segments(mk3, 3, deg(100)) == 6);    // 0.942 mm: 5.56 rounded up
  CHECK(executed_segments(mk3, 1, deg(90)) == 4);     // 0.314 mm, held to 0.5 mm: 3.14 rounded up
  CHECK(executed_segments(mk3, 0.5, deg(90)) == 2);   // 0.785 mm of arc in 0.5 mm segments
  CHECK(executed_segments(mk3, 10, deg(90), 10) == 19);  // a helix: hypot(15.708, 10) = 18.62 mm
  // Without MIN_ARC_SEGMENTS, the longest segment.
  CHECK(executed_segments(rule(Rule::PrusaMk3, 1.0, 0.5, 0, 0), 1, deg(90)) == 2);
  // A dialect file names it (prusa-mk3.toml ships: its rule is checked below).
  const Dialect file = parse_dialect("name = \"mk3\"\n[arcs.executed]\nrule = \"prusa-mk3\"\nmax_segment_mm = 1.0\n"
                                    "min_segment_mm = 0.5\nmin_circle_segments = 20\n",
                                    "mk3.toml");
  CHECK(file.executed.rule == Rule::PrusaMk3);
  CHECK(executed_segments(file.executed, 3, deg(100)) == 6);
}

TEST_CASE("Grbl's mc_arc() makes floor(half the length / sqrt($12 (2r - $12))) segments, 0 meaning one chord",
          "[segmentation]") {
  const auto grbl = rule(Rule::Grbl, 0, 0, 0, 0.002);
  CHECK(executed_segments(grbl, 10, deg(90)) == 39);  // 7.854 / 0.19999 = 39.27
  // r 5, 3 degrees: 0.1309 / 0.1414 = 0.93: Grbl draws the chord, 5 (1 - cos 1.5 deg) off the circle.
  CHECK(executed_segments(grbl, 5, deg(3)) == 1);
  CHECK(executed_sagitta_mm(grbl, 5, deg(3)) == Approx(0.0017133).margin(1e-7));
  // Near half of $12 the count grows without bound; Grbl counts in 16 bits, and so does
  // arcpress, which writes no arc that needs as many.
  CHECK(executed_segments(grbl, 0.001 + 1e-15, deg(180)) == kMaxArcSegments);
  CHECK(executed_segments(grbl, 0.001, deg(180)) == 1);  // the circle lies within $12 of the chord
  CHECK(executed_segments(grbl, 1000, deg(180)) == 785);  // the largest radius arcpress writes by default
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
  CHECK(find_dialect("grblhal", path).executed.rule == Rule::GrblHAL);
  CHECK(find_dialect("prusa-mk3", path).executed.rule == Rule::PrusaMk3);
  CHECK(executed_segments(find_dialect("prusa-mk3", path).executed, 3, deg(100)) == 6);  // its variants' 1 / 0.5 mm, 20
  CHECK(find_dialect("prusa", path).executed.rule == Rule::PrusaBuddy);
  CHECK(find_dialect("prusa", path).executed.max_deviation_mm == 0.02);
  // Each names its correction period, as its firmware sets it.
  CHECK(find_dialect("marlin", path).executed.correction_period_or_default() == 25);
  CHECK(find_dialect("grbl", path).executed.correction_period == 12);
  CHECK(find_dialect("grblhal", path).executed.correction_period == 12);
  CHECK(find_dialect("smoothieware", path).executed.correction_period == 5);
  CHECK(find_dialect("reprapfirmware", path).executed.correction_period == 8);
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

namespace {

// Transcriptions of each firmware's loop, written as the firmware writes it (its variable
// names, its number types, its counter), for the golden tests below: the chord ends of an
// arc from the start (px, py) with centre offset (i, j), turning by `travel`, in `segments`.
struct Point {
  double x, y;
};

// Marlin 2.1 Marlin/src/gcode/motion/G2_G3.cpp, plan_arc().
std::vector<Point> marlin_plan_arc(float px, float py, float i, float j, float tx, float ty, bool clockwise, int segments,
                                   int n_arc_correction) {
  std::vector<Point> out;
  float rvec_a = -i, rvec_b = -j;
  const float center_P = px - rvec_a, center_Q = py - rvec_b, rt_X = tx - center_P, rt_Y = ty - center_Q;
  float angular_travel = std::atan2(rvec_a * rt_Y - rvec_b * rt_X, rvec_a * rt_X + rvec_b * rt_Y);
  if (angular_travel < 0) angular_travel += float(2 * M_PI);
  if (clockwise) angular_travel -= float(2 * M_PI);
  const float theta_per_segment = angular_travel / segments, sq_theta_per_segment = theta_per_segment * theta_per_segment,
              sin_T = theta_per_segment - sq_theta_per_segment * theta_per_segment / 6,
              cos_T = 1 - 0.5f * sq_theta_per_segment;
  int arc_recalc_count = n_arc_correction;
  for (int k = 1; k < segments; k++) {
    if (--arc_recalc_count) {
      const float r_new_Y = rvec_a * sin_T + rvec_b * cos_T;
      rvec_a = rvec_a * cos_T - rvec_b * sin_T;
      rvec_b = r_new_Y;
    } else {
      arc_recalc_count = n_arc_correction;
      const float cos_Ti = std::cos(k * theta_per_segment), sin_Ti = std::sin(k * theta_per_segment);
      rvec_a = -i * cos_Ti + j * sin_Ti;
      rvec_b = -i * sin_Ti - j * cos_Ti;
    }
    out.push_back({center_P + rvec_a, center_Q + rvec_b});
  }
  return out;
}

// Grbl 1.1 grbl/motion_control.c, mc_arc() (float, as on the AVR where double is float).
std::vector<Point> grbl_mc_arc(float px, float py, float i, float j, float tx, float ty, bool is_clockwise_arc,
                               int segments, int n_arc_correction) {
  std::vector<Point> out;
  const float center_axis0 = px + i, center_axis1 = py + j;
  float r_axis0 = -i, r_axis1 = -j;
  const float rt_axis0 = tx - center_axis0, rt_axis1 = ty - center_axis1;
  float angular_travel = std::atan2(r_axis0 * rt_axis1 - r_axis1 * rt_axis0, r_axis0 * rt_axis0 + r_axis1 * rt_axis1);
  if (is_clockwise_arc) {
    if (angular_travel >= -5E-7f) angular_travel -= float(2 * M_PI);
  } else {
    if (angular_travel <= 5E-7f) angular_travel += float(2 * M_PI);
  }
  const float theta_per_segment = angular_travel / segments;
  float cos_T = 2.0f - theta_per_segment * theta_per_segment;
  const float sin_T = theta_per_segment * 0.16666667f * (cos_T + 4.0f);
  cos_T *= 0.5f;
  int count = 0;
  for (int k = 1; k < segments; k++) {
    if (count < n_arc_correction) {
      const float r_axisi = r_axis0 * sin_T + r_axis1 * cos_T;
      r_axis0 = r_axis0 * cos_T - r_axis1 * sin_T;
      r_axis1 = r_axisi;
      count++;
    } else {
      const float cos_Ti = std::cos(k * theta_per_segment), sin_Ti = std::sin(k * theta_per_segment);
      r_axis0 = -i * cos_Ti + j * sin_Ti;
      r_axis1 = -i * sin_Ti - j * cos_Ti;
      count = 0;
    }
    out.push_back({center_axis0 + r_axis0, center_axis1 + r_axis1});
  }
  return out;
}

// grblHAL core motion_control.c, mc_arc(): the radius vector and centre in double.
std::vector<Point> grblhal_mc_arc(float px, float py, float i, float j, float tx, float ty, bool clockwise, int segments) {
  std::vector<Point> out;
  double rv_x = -(double)i, rv_y = -(double)j;
  const double center_x = (double)px - rv_x, center_y = (double)py - rv_y;
  const double rt_x = (double)tx - center_x, rt_y = (double)ty - center_y;
  float angular_travel = (float)atan2(rv_x * rt_y - rv_y * rt_x, rv_x * rt_x + rv_y * rt_y);
  if (!clockwise) {
    if (angular_travel <= 5E-7f) angular_travel += 2.0f * float(M_PI);
  } else if (angular_travel >= -5E-7f) {
    angular_travel -= 2.0f * float(M_PI);
  }
  const float theta_per_segment = angular_travel / segments;
  float cos_T = 2.0f - theta_per_segment * theta_per_segment;
  const float sin_T = theta_per_segment * 0.16666667f * (cos_T + 4.0f);
  cos_T *= 0.5f;
  int count = 0;
  for (int k = 1; k < segments; k++) {
    if (count < 12) {
      const double r_axisi = rv_x * sin_T + rv_y * cos_T;
      rv_x = rv_x * cos_T - rv_y * sin_T;
      rv_y = r_axisi;
      count++;
    } else {
      const float cos_Ti = std::cos(k * theta_per_segment), sin_Ti = std::sin(k * theta_per_segment);
      rv_x = -i * cos_Ti + j * sin_Ti;
      rv_y = -i * sin_Ti - j * cos_Ti;
      count = 0;
    }
    out.push_back({(float)(center_x + rv_x), (float)(center_y + rv_y)});
  }
  return out;
}

// Smoothieware src/modules/robot/Robot.cpp, append_arc().
std::vector<Point> smoothie_append_arc(float px, float py, float i, float j, float tx, float ty, bool is_clockwise,
                                       int segments, int arc_correction) {
  std::vector<Point> out;
  const float center_axis0 = px + i, center_axis1 = py + j;
  float r_axis0 = -i, r_axis1 = -j;
  const float rt_axis0 = tx - center_axis0, rt_axis1 = ty - center_axis1;
  float angular_travel = atan2f(r_axis0 * rt_axis1 - r_axis1 * rt_axis0, r_axis0 * rt_axis0 + r_axis1 * rt_axis1);
  if (is_clockwise) {
    if (angular_travel > 0) angular_travel -= float(2 * M_PI);
  } else {
    if (angular_travel < 0) angular_travel += float(2 * M_PI);
  }
  const float theta_per_segment = angular_travel / segments;
  const float cos_T = 1 - 0.5F * theta_per_segment * theta_per_segment, sin_T = theta_per_segment;
  int count = 0;
  for (int k = 1; k < segments; k++) {
    if (count < arc_correction) {
      const float r_axisi = r_axis0 * sin_T + r_axis1 * cos_T;
      r_axis0 = r_axis0 * cos_T - r_axis1 * sin_T;
      r_axis1 = r_axisi;
      count++;
    } else {
      const float cos_Ti = cosf(k * theta_per_segment), sin_Ti = sinf(k * theta_per_segment);
      r_axis0 = -i * cos_Ti + j * sin_Ti;
      r_axis1 = -i * sin_Ti - j * cos_Ti;
      count = 0;
    }
    out.push_back({center_axis0 + r_axis0, center_axis1 + r_axis1});
  }
  return out;
}

// Prusa-Firmware-Buddy lib/Marlin/Marlin/src/gcode/motion/G2_G3.cpp, plan_arc().
std::vector<Point> buddy_plan_arc(float px, float py, float i, float j, float tx, float ty, bool clockwise, int segments) {
  std::vector<Point> out;
  float rvec_a = -i, rvec_b = -j;
  const float center_P = px - rvec_a, center_Q = py - rvec_b, rt_X = tx - center_P, rt_Y = ty - center_Q;
  float angular_travel = atan2f(rvec_a * rt_Y - rvec_b * rt_X, rvec_a * rt_X + rvec_b * rt_Y);
  switch (((angular_travel < 0) << 1) | clockwise) {
    case 1: angular_travel -= float(2 * M_PI); break;
    case 2: angular_travel += float(2 * M_PI); break;
  }
  const float theta_per_segment = angular_travel / segments, cos_T = cosf(theta_per_segment),
              sin_T = sinf(theta_per_segment);
  int arc_recalc_count = 25;
  for (int k = 1; k < segments; k++) {
    if (--arc_recalc_count) {
      const float r_new_Y = rvec_a * sin_T + rvec_b * cos_T;
      rvec_a = rvec_a * cos_T - rvec_b * sin_T;
      rvec_b = r_new_Y;
    } else {
      arc_recalc_count = 25;
      const float Ti = k * theta_per_segment, cos_Ti = cosf(Ti), sin_Ti = sinf(Ti);
      rvec_a = -i * cos_Ti + j * sin_Ti;
      rvec_b = -i * sin_Ti - j * cos_Ti;
    }
    out.push_back({center_P + rvec_a, center_Q + rvec_b});
  }
  return out;
}

// Prusa-Firmware Firmware/motion_control.cpp, mc_arc() (floats, as on the AVR).
std::vector<Point> mk3_mc_arc(float px, float py, float i, float j, float tx, float ty, bool isclockwise, int segments) {
  std::vector<Point> out;
  float r_axis_x = -i, r_axis_y = -j;
  const float center_axis_x = px - r_axis_x, center_axis_y = py - r_axis_y, rt_x = tx - center_axis_x,
              rt_y = ty - center_axis_y;
  float angular_travel_total = atan2f(r_axis_x * rt_y - r_axis_y * rt_x, r_axis_x * rt_x + r_axis_y * rt_y);
  if (angular_travel_total < 0) angular_travel_total += float(2 * M_PI);
  if (isclockwise) angular_travel_total -= float(2 * M_PI);
  const float theta_per_segment = angular_travel_total / segments, sq_theta_per_segment = theta_per_segment * theta_per_segment,
              sin_T = theta_per_segment - sq_theta_per_segment * theta_per_segment / 6,
              cos_T = 1 - 0.5f * sq_theta_per_segment;
  unsigned char n_arc_correction = 25;
  for (int k = 1; k < segments; k++) {
    if (n_arc_correction-- == 0) {
      const float cos_Ti = cosf(k * theta_per_segment), sin_Ti = sinf(k * theta_per_segment);
      r_axis_x = -i * cos_Ti + j * sin_Ti;
      r_axis_y = -i * sin_Ti - j * cos_Ti;
      n_arc_correction = 25;
    } else {
      const float r_axisi = r_axis_x * sin_T + r_axis_y * cos_T;
      r_axis_x = r_axis_x * cos_T - r_axis_y * sin_T;
      r_axis_y = r_axisi;
    }
    out.push_back({center_axis_x + r_axis_x, center_axis_y + r_axis_y});
  }
  return out;
}

// RepRapFirmware 3 src/GCodes/GCodes.cpp, DoArcMove() and ReadMove().
std::vector<Point> rrf_read_move(float px, float py, float iParam, float jParam, float tx, float ty, bool clockwise,
                                 int totalSegments, int segmentsPerFullArcCalculation) {
  std::vector<Point> out;
  const float arcCentre0 = px + iParam, arcCentre1 = py + jParam;
  const float finalTheta = atan2f(ty - arcCentre1, tx - arcCentre0);
  const float arcRadius = sqrtf(iParam * iParam + jParam * jParam);
  float arcCurrentAngle = atan2f(-jParam, -iParam);
  float totalArc = clockwise ? arcCurrentAngle - finalTheta : finalTheta - arcCurrentAngle;
  if (totalArc < 0.0f) totalArc += float(2 * M_PI);
  float arcAngleIncrement = totalArc / totalSegments;
  if (clockwise) arcAngleIncrement = -arcAngleIncrement;
  const float angleIncrementSine = sinf(arcAngleIncrement), angleIncrementCosine = cosf(arcAngleIncrement);
  int segmentsTillNextFullCalc = 0;
  float currentAngleCosine = 0, currentAngleSine = 0;
  for (int segmentsLeft = totalSegments; segmentsLeft > 1; --segmentsLeft) {
    arcCurrentAngle += arcAngleIncrement;
    if (segmentsTillNextFullCalc == 0) {
      segmentsTillNextFullCalc = segmentsPerFullArcCalculation;
      currentAngleCosine = cosf(arcCurrentAngle);
      currentAngleSine = sinf(arcCurrentAngle);
    } else {
      --segmentsTillNextFullCalc;
      const float newCosine = currentAngleCosine * angleIncrementCosine - currentAngleSine * angleIncrementSine;
      const float newSine = currentAngleSine * angleIncrementCosine + currentAngleCosine * angleIncrementSine;
      currentAngleCosine = newCosine;
      currentAngleSine = newSine;
    }
    out.push_back({arcCentre0 + arcRadius * currentAngleCosine, arcCentre1 + arcRadius * currentAngleSine});
  }
  return out;
}

/// Largest distance between two lists of points, pairwise; infinite where their lengths differ.
double farthest(const std::vector<Vec2>& a, const std::vector<Point>& b) {
  if (a.size() != b.size()) return HUGE_VAL;
  double worst = 0;
  for (size_t k = 0; k < a.size(); ++k) worst = std::max(worst, std::hypot(a[k].x() - b[k].x, a[k].y() - b[k].y));
  return worst;
}

}  // namespace

TEST_CASE("golden: every rule's chord ends are the ones its firmware computes, drift and all, to 1e-6 mm",
          "[segmentation][golden]") {
  // A small circle cut into large steps, where the small-angle rotation drifts the most (as
  // in a printer's 0.3 mm arcs), and a larger arc with many chords, past several corrections.
  struct Case {
    double px, py, i, j, travel_rad;
    int segments;
  };
  for (const Case c : {Case{46.3, 18.77, 0.223, 0.1935, deg(300), 14}, Case{120.5, -3.25, -4.75, 2.5, deg(-350), 61},
                       Case{0.5, 0.25, 0.0, 12.0, deg(181), 40}}) {
    INFO("start " << c.px << ", " << c.py << " offset " << c.i << ", " << c.j << " turn " << c.travel_rad << " in "
                  << c.segments);
    const Vec2 start(c.px, c.py), centre(c.px + c.i, c.py + c.j);
    // The end point the program names: the start turned about the centre.
    const double ct = std::cos(c.travel_rad), st = std::sin(c.travel_rad);
    const Vec2 end(centre.x() - c.i * ct + c.j * st, centre.y() - c.i * st - c.j * ct);
    const float px = float(c.px), py = float(c.py), fi = float(c.i), fj = float(c.j), tx = float(end.x()),
                ty = float(end.y());
    const bool cw = c.travel_rad < 0;
    auto ends = [&](Rule r, int period) {
      ArcSegmentation s;
      s.rule = r;
      s.correction_period = period;
      std::vector<Vec2> out;
      executed_chord_ends(s, start, centre, end, c.travel_rad, uint32_t(c.segments), out);
      return out;
    };
    // Every end on the circle at equal turns, as the firmware would draw them in exact arithmetic.
    std::vector<Point> on_circle;
    for (int k = 1; k < c.segments; ++k) {
      const double a = std::atan2(-c.j, -c.i) + c.travel_rad * k / c.segments;
      const double r = std::hypot(c.i, c.j);
      on_circle.push_back({centre.x() + r * std::cos(a), centre.y() + r * std::sin(a)});
    }
    CHECK(farthest(ends(Rule::Marlin, 0), marlin_plan_arc(px, py, fi, fj, tx, ty, cw, c.segments, 25)) < 1e-6);
    CHECK(farthest(ends(Rule::Marlin, 5), marlin_plan_arc(px, py, fi, fj, tx, ty, cw, c.segments, 5)) < 1e-6);
    CHECK(farthest(ends(Rule::Grbl, 0), grbl_mc_arc(px, py, fi, fj, tx, ty, cw, c.segments, 12)) < 1e-6);
    CHECK(farthest(ends(Rule::GrblHAL, 0), grblhal_mc_arc(px, py, fi, fj, tx, ty, cw, c.segments)) < 1e-6);
    CHECK(farthest(ends(Rule::Smoothieware, 0), smoothie_append_arc(px, py, fi, fj, tx, ty, cw, c.segments, 5)) < 1e-6);
    CHECK(farthest(ends(Rule::RepRapFirmware, 0), rrf_read_move(px, py, fi, fj, tx, ty, cw, c.segments, 8)) < 1e-6);
    CHECK(farthest(ends(Rule::PrusaBuddy, 0), buddy_plan_arc(px, py, fi, fj, tx, ty, cw, c.segments)) < 1e-6);
    CHECK(farthest(ends(Rule::PrusaMk3, 0), mk3_mc_arc(px, py, fi, fj, tx, ty, cw, c.segments)) < 1e-6);
    CHECK(farthest(ends(Rule::Klipper, 0), on_circle) < 1e-9);
    // The small-angle rotations do pull the ends off the circle: a model that put them on it
    // would miss what these firmwares move along.
    if (c.segments == 14) {
      CHECK(farthest(ends(Rule::Marlin, 0), on_circle) > 1e-4);
      CHECK(farthest(ends(Rule::Smoothieware, 0), on_circle) > 1e-3);
    }
  }
}

TEST_CASE("the count is the firmware's own where floats and doubles round it apart", "[segmentation]") {
  // A Buddy arc from a PrusaSlicer benchy at 0.01 mm: 0.4134 mm of arc over 0.3445 mm segments
  // is 1.1999974 + 0.8 in floats, one chord 0.0285 mm off the circle; 1.2000020 + 0.8 in doubles.
  ArcSegmentation buddy;
  buddy.rule = Rule::PrusaBuddy;
  buddy.max_segment_mm = 2.0;
  buddy.min_segment_mm = 0.1;
  buddy.max_deviation_mm = 0.02;
  const Vec2 start(31.005, 57.632), centre(31.005 - 0.3563, 57.632 - 0.6505), end(30.607, 57.722);
  const double sweep = std::remainder(std::atan2(end.y() - centre.y(), end.x() - centre.x()) -
                                          std::atan2(start.y() - centre.y(), start.x() - centre.x()),
                                      2 * std::numbers::pi);
  REQUIRE(sweep > 0);
  CHECK(executed_segments(buddy, (start - centre).norm(), sweep) == 2);
  CHECK(executed_segments_read(buddy, start, centre, end, sweep) == 1);
}

TEST_CASE("where the firmware may cut more chords at a low feed, the ring holds every count from its own up",
          "[segmentation]") {
  // Polylines near arcs of 0.5 to 300 mm radius; for each, the chords of every count from the
  // firmware's to 40 more, their ends as the firmware computes them, lie no farther from the
  // polyline than ring_deviation() says.
  uint64_t seed = 12345;
  auto uniform = [&](double lo, double hi) {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * double(seed >> 11) / double(1ULL << 53);
  };
  for (const Rule r : {Rule::PrusaBuddy, Rule::RepRapFirmware}) {
    ArcSegmentation s;
    s.rule = r;
    s.max_segment_mm = r == Rule::PrusaBuddy ? 2.0 : 1.0;
    s.min_segment_mm = r == Rule::PrusaBuddy ? 0.1 : 0.02;
    s.max_deviation_mm = r == Rule::PrusaBuddy ? 0.02 : 0.005;
    for (int trial = 0; trial < 200; ++trial) {
      const double radius = std::exp(uniform(std::log(0.5), std::log(300.0))), sweep = uniform(0.05, 3.0) * (trial % 2 ? 1 : -1);
      const Vec2 centre(uniform(-100, 200), uniform(-100, 200));
      const double a0 = uniform(-3.1, 3.1);
      // The polyline: points along the arc, each off it radially by up to 0.01 mm.
      const int points = 3 + trial % 12;
      std::vector<Vec3> pts;
      for (int k = 0; k < points; ++k) {
        const double a = a0 + sweep * k / (points - 1), rr = radius + (k == 0 || k == points - 1 ? 0 : uniform(-0.01, 0.01));
        pts.emplace_back(centre.x() + rr * std::cos(a), centre.y() + rr * std::sin(a), 0);
      }
      const ArcGeom arc = ArcGeom::through(pts.front(), pts.back(), centre, sweep > 0);
      const Vec2 start(pts.front().x(), pts.front().y()), end(pts.back().x(), pts.back().y());
      const uint32_t n = executed_segments(s, radius, sweep);
      std::vector<Vec2> ends;
      executed_chord_ends(s, start, centre, end, sweep, n, ends);
      const Deviation ring = ring_deviation(s, pts, arc, ends);
      REQUIRE(ring.ordered);
      for (uint32_t more = n; more <= n + 40; ++more) {
        INFO(rule_name(r) << " radius " << radius << " sweep " << sweep << " chords " << more << " of " << n);
        std::vector<Vec2> other;
        executed_chord_ends(s, start, centre, end, sweep, more, other);
        const auto on_chords = chords_deviation_bound(pts, arc, other);
        REQUIRE(on_chords);
        CHECK(*on_chords <= ring.max_mm + 1e-12);
      }
    }
  }
}
