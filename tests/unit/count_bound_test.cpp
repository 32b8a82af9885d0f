// SPDX-License-Identifier: GPL-3.0-or-later
// Specifications of the lower bound on primitive counts (fit/count_bound), and of the fitter
// against it: no fit of a polyline has fewer primitives than the bound in the same band.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "arcpress/arcpress.hpp"
#include "arcpress/fit/count_bound.hpp"

using namespace arcpress;

namespace {

/// The points as a program prints them with 4 decimals, read back.
std::vector<Vec2> printed(const std::vector<Vec2>& pts) {
  std::vector<Vec2> out;
  for (const Vec2& p : pts) out.emplace_back(std::stod(fmt::format("{:.4f}", p.x())), std::stod(fmt::format("{:.4f}", p.y())));
  return out;
}

std::string program(const std::vector<Vec2>& pts) {
  std::string s = fmt::format("G21 G90 G17\nG0 X{:.4f} Y{:.4f} Z0\nG1 F600\n", pts[0].x(), pts[0].y());
  for (size_t i = 1; i < pts.size(); ++i) s += fmt::format("G1 X{:.4f} Y{:.4f}\n", pts[i].x(), pts[i].y());
  return s + "M2\n";
}

std::vector<Vec2> arc(const Vec2& c, double r, double a0_deg, double a1_deg, int moves) {
  std::vector<Vec2> p;
  for (int i = 0; i <= moves; ++i) {
    const double a = deg_to_rad(a0_deg + (a1_deg - a0_deg) * i / moves);
    p.push_back(c + r * Vec2(std::cos(a), std::sin(a)));
  }
  return p;
}

std::vector<Vec2> sampled(int moves, double t0, double t1, const std::function<Vec2(double)>& f) {
  std::vector<Vec2> p;
  for (int i = 0; i <= moves; ++i) p.push_back(f(t0 + (t1 - t0) * i / moves));
  return p;
}

/// Xu's loop, (10 (t³ − t), 10 (t² − 1)) / (t² + 1) for t in [−2, 2], in 999 moves.
std::vector<Vec2> loop_curve() {
  return sampled(999, -2, 2, [](double t) { return Vec2(10 * (t * t * t - t) / (t * t + 1), 10 * (t * t - 1) / (t * t + 1)); });
}

/// `raw` as a program fitted by `method` at `tol_mm`, with no smallest radius.
CompressResult fitted(const std::vector<Vec2>& raw, double tol_mm, FitOptions::Method method) {
  CompressOptions opt;
  opt.fit.tolerance_mm = tol_mm;
  opt.fit.min_radius_mm = 0;
  opt.fit.method = method;
  DiagnosticSink sink;
  return compress("t.nc", program(raw), opt, sink);
}

/// The options fitted() fits with at `tol_mm`, as the default dialect sets them (its finest
/// centre step decides the share of the band kept back for rounding).
FitOptions fitted_options(double tol_mm) {
  FitOptions o;
  o.tolerance_mm = tol_mm;
  return fit_options_for(o, Dialect{}, Frame{}, Plane::XY);
}

/// The lines and arcs `method` fits `raw` with at `tol_mm` (no smallest radius), after
/// requiring that the check paired every move, that no joint broke and the band held.
size_t tangent_fit_count(const std::vector<Vec2>& raw, double tol_mm, FitOptions::Method method) {
  const CompressResult r = fitted(raw, tol_mm, method);
  REQUIRE(r.comparison.matched);
  REQUIRE(r.forced_kinks == 0);
  CHECK(r.comparison.max_deviation_mm <= tol_mm);
  return r.stats.lines_out + r.stats.arcs_out;
}

}  // namespace

TEST_CASE("a polyline on one circle or one line needs one primitive, and nothing needs none", "[fit][bound]") {
  CHECK(min_primitive_count(printed(arc({0, 0}, 5, 0, 170, 80)), 0.01) == 1);
  CHECK(min_primitive_count(printed(arc({3, -2}, 0.5, 90, -200, 60)), 0.01) == 1);  // more than half a turn
  CHECK(min_primitive_count(sampled(50, 0, 1, [](double t) { return Vec2(10 * t, 3 * t); }), 0.001) == 1);
  CHECK(min_primitive_count(std::vector<Vec2>{{1, 1}}, 0.01) == 0);
  CHECK(min_primitive_count(std::vector<Vec2>{}, 0.01) == 0);
}

TEST_CASE("a zigzag wider than the band: any three vertices lie on a circle, but it bows 0.29 mm off the moves' "
          "middles, so each move is a primitive of its own", "[fit][bound]") {
  std::vector<Vec2> zigzag;
  for (int i = 0; i <= 10; ++i) zigzag.emplace_back(i, i % 2 ? 1.0 : 0.0);
  CHECK(min_primitive_count(zigzag, 0.01) == 10);
  zigzag.emplace_back(11, 1);
  CHECK(min_primitive_count(zigzag, 0.01) == 11);
  // Within a band wide enough for the middles (the circle through three vertices passes
  // 1 - 1/√2 mm inside them), two moves make one arc again.
  zigzag.pop_back();
  CHECK(min_primitive_count(zigzag, 0.3) == 5);
}

TEST_CASE("two arcs of different radii need two primitives, and a band wide enough for one circle needs one",
          "[fit][bound]") {
  auto first = arc({0, 0}, 10, -90, 0, 40);   // radius 10, ends at (10, 0) heading +y
  auto second = arc({8, 0}, 2, 0, 90, 40);    // radius 2, tangent there
  first.insert(first.end(), second.begin() + 1, second.end());
  CHECK(min_primitive_count(printed(first), 0.01) == 2);
  CHECK(min_primitive_count(printed(first), 0.01) <= min_primitive_count(printed(first), 0.001));
  CHECK(min_primitive_count(printed(first), 5.0) == 1);
}

TEST_CASE("tangent joints: one circle needs one arc, two tangent arcs of different radii two, and an S of two "
          "arcs at least two, and the tangent bound is never below the other", "[fit][bound]") {
  CHECK(min_g1_primitive_count(printed(arc({0, 0}, 5, 0, 170, 80)), 0.01, 0.5) == 1);
  auto two = arc({0, 0}, 10, -90, 0, 40);
  const auto small = arc({8, 0}, 2, 0, 90, 40);
  two.insert(two.end(), small.begin() + 1, small.end());
  CHECK(min_g1_primitive_count(printed(two), 0.01, 0.5) == 2);
  auto s_curve = arc({0, 0}, 3, 180, 90, 30);   // ends at (0, 3) heading +x
  const auto back = arc({0, 6}, 3, -90, 0, 30);  // starts there heading +x, turning left
  s_curve.insert(s_curve.end(), back.begin() + 1, back.end());
  CHECK(min_g1_primitive_count(printed(s_curve), 0.01, 0.5) == 2);
  // More than half a turn of one circle: one arc may sweep half a turn at most.
  CHECK(min_g1_primitive_count(printed(arc({1, 1}, 2, 0, 270, 90)), 0.01, 0.5) == 2);
  CHECK(min_primitive_count(printed(arc({1, 1}, 2, 0, 270, 90)), 0.01) == 1);
  const auto cubic = printed(sampled(400, -2, 2, [](double x) { return Vec2(x, x * x * x); }));
  for (double tol : {0.02, 0.005}) {
    INFO("y = x^3 at " << tol << " mm");
    CHECK(min_g1_primitive_count(cubic, tol, 0.5) >= min_primitive_count(cubic, tol));
    CHECK(min_g1_primitive_count(cubic, tol, 0.5) <= min_g1_primitive_count(cubic, tol / 2, 0.5));
  }
}

TEST_CASE("tangents fixed at the ends: a chain leaves and arrives along the moves it joins, within the G1 angle",
          "[fit][bound]") {
  auto dir = [](double deg) { return Vec2(std::cos(deg_to_rad(deg)), std::sin(deg_to_rad(deg))); };
  const auto line = sampled(10, 0, 10, [](double x) { return Vec2(x, 0); });
  CHECK(min_g1_primitive_count(line, 0.01, 0.5, {dir(0.3), dir(-0.3)}) == 1);
  // Leaving 10 degrees off the line, no arc gets back into the band before the next vertex
  // (over one 1 mm move it would bulge 0.044 mm): no tangent chain at all.
  CHECK(min_g1_primitive_count(line, 0.01, 0.5, {dir(10), std::nullopt}) == 0);
  CHECK(min_g1_primitive_count(line, 0.01, 0.5, {std::nullopt, dir(-10)}) == 0);
  CHECK(min_g1_primitive_count(line, 0.01, 0.5, {dir(180), std::nullopt}) == 0);  // backwards
  // A quarter circle from (5, 0) heading +y to (0, 5) heading -x.
  const auto quarter = printed(arc({0, 0}, 5, 0, 90, 45));
  CHECK(min_g1_primitive_count(quarter, 0.01, 0.5, {dir(90), dir(180)}) == 1);
  CHECK(min_g1_primitive_count(quarter, 0.01, 0.5, {dir(90.4), dir(179.6)}) == 1);
  // Joining a move that turns 3 degrees off the circle's tangent costs primitives, never saves them.
  const size_t free_count = min_g1_primitive_count(quarter, 0.01, 0.5);
  for (const EndTangents& joins : {EndTangents{dir(93), std::nullopt}, EndTangents{std::nullopt, dir(183)},
                                   EndTangents{dir(87), dir(177)}}) {
    const size_t fixed = min_g1_primitive_count(quarter, 0.01, 0.5, joins);
    CHECK((fixed == 0 || fixed > free_count));
  }
  const auto cubic = printed(sampled(400, -2, 2, [](double x) { return Vec2(x, x * x * x); }));
  const size_t cubic_free = min_g1_primitive_count(cubic, 0.01, 0.5);
  for (double off : {0.0, 1.0, 5.0}) {
    INFO("y = x^3 joined " << off << " degrees off its own tangent (slope 12)");
    const double along = rad_to_deg(std::atan(12.0));
    const size_t fixed = min_g1_primitive_count(cubic, 0.01, 0.5, {dir(along + off), dir(along - off)});
    CHECK((fixed == 0 || fixed >= cubic_free));
  }
}

TEST_CASE("a fit joining an input arc tangentially has no fewer primitives than the bound with that tangent",
          "[fit][bound]") {
  // G3 from (5, 0) to (0, 5) about the origin, arriving along -x; then G1 moves along
  // wobbling curves that leave (0, 5) along -x too.
  for (double wobble : {0.0, 0.05, 0.2}) {
    // (The lambda names its type: an Eigen sum returned as itself would refer to temporaries
    // that end with the call.)
    const auto curve = printed(sampled(120, 0, 1, [&](double t) -> Vec2 {
      const double a = deg_to_rad(90 + 150 * t);
      const double r = 3 + wobble * std::pow(std::sin(3 * kPi * t), 2);  // (no radial speed at t = 0)
      return Vec2(0, 2) + r * Vec2(std::cos(a), std::sin(a));
    }));
    std::string text = "G21 G90 G17\nG0 X5 Y0 Z0\nG1 F600\nG3 X0 Y5 I-5 J0\n";
    for (size_t i = 1; i < curve.size(); ++i) text += fmt::format("G1 X{:.4f} Y{:.4f}\n", curve[i].x(), curve[i].y());
    text += "M2\n";
    for (double tol : {0.01, 0.002}) {
      CompressOptions opt;
      opt.fit.tolerance_mm = tol;
      opt.fit.min_radius_mm = 0;
      DiagnosticSink sink;
      const CompressResult r = compress("t.nc", text, opt, sink);
      REQUIRE(r.ok);
      const size_t count = r.stats.lines_out + r.stats.arcs_out;
      const size_t bound = min_g1_primitive_count(curve, tol, opt.fit.g1_angle_deg, {Vec2(-1, 0), std::nullopt});
      INFO("wobble " << wobble << " at " << tol << " mm: " << count << " primitives, " << r.forced_kinks
                     << " forced kinks, bound " << bound);
      CHECK(bound >= 1);
      CHECK(r.comparison.max_smooth_kink_deg <= opt.fit.g1_angle_deg);
      if (r.forced_kinks == 0) CHECK(count >= bound);
    }
  }
}

TEST_CASE("a right-angle corner: no tangent chain gets round it inside the band, and repeated vertices are no obstacle",
          "[fit][bound]") {
  std::vector<Vec2> corner;
  for (int i = 0; i <= 10; ++i) corner.emplace_back(i, 0);
  for (int i = 1; i <= 10; ++i) corner.emplace_back(10, i);
  CHECK(min_g1_primitive_count(corner, 0.01, 0.5) == 0);
  CHECK(min_primitive_count(corner, 0.01) == 2);
  std::vector<Vec2> repeated = printed(arc({0, 0}, 5, 0, 90, 30));
  repeated.insert(repeated.begin() + 10, repeated[10]);
  repeated.insert(repeated.begin() + 20, 2, repeated[20]);
  CHECK(min_primitive_count(repeated, 0.01) == 1);
  CHECK(min_g1_primitive_count(repeated, 0.01, 0.5) == 1);
}

TEST_CASE("a long move's middle is held in the band too: no circle bows off it to meet the short moves either side",
          "[fit][bound]") {
  // Short moves turning 18 degrees either side of a 9 mm line. The circle through all four
  // vertices bows 0.7 mm off the line's middle, so only its own lines keep the band.
  const std::vector<Vec2> hat = {{0, 0.1}, {0.3, 0}, {9.3, 0}, {9.6, 0.1}};
  CHECK(min_primitive_count(hat, 0.01) == 3);
  CHECK(min_g1_primitive_count(hat, 0.01, 0.5) == 0);
  std::string text = "G21 G90 G17\nG0 X0 Y0.1 Z0\nG1 F600\n";
  for (size_t i = 1; i < hat.size(); ++i) text += fmt::format("G1 X{} Y{}\n", hat[i].x(), hat[i].y());
  text += "M2\n";
  CompressOptions opt;
  DiagnosticSink sink;
  const CompressResult r = compress("t.nc", text, opt, sink);
  REQUIRE(r.ok);
  CHECK(r.stats.lines_out + r.stats.arcs_out >= min_primitive_count(hat, opt.fit.tolerance_mm));
}

TEST_CASE("where every fit must end a primitive (extrusion stops), no primitive of the bound spans the vertex, and "
          "the tangent goes on across it", "[fit][bound]") {
  const auto line = sampled(10, 0, 10, [](double x) { return Vec2(x, 0); });
  const std::vector<uint8_t> two_ends = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  CHECK(min_primitive_count(line, 0.01) == 1);
  CHECK(min_primitive_count(line, 0.01, two_ends) == 3);
  CHECK(min_g1_primitive_count(line, 0.01, 0.5, {}, two_ends) == 3);
  // Ends at the first and last vertex, or none given, change nothing.
  CHECK(min_g1_primitive_count(line, 0.01, 0.5, {}, std::vector<uint8_t>{1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1}) == 1);
  // On one circle the two arcs either side of the end are tangent to each other.
  const auto quarter = printed(arc({0, 0}, 5, 0, 90, 40));
  std::vector<uint8_t> middle(quarter.size(), 0);
  middle[20] = 1;
  CHECK(min_g1_primitive_count(quarter, 0.01, 0.5, {}, middle) == 2);
  // A program that extrudes along the first half of the quarter and moves on without
  // extruding: every fit writes at least the bound's primitives.
  std::string text = fmt::format("G21 G90 G17 M83\nG0 X{:.4f} Y{:.4f} Z0\nG1 F600\n", quarter[0].x(), quarter[0].y());
  for (size_t i = 1; i < quarter.size(); ++i)
    text += fmt::format("G1 X{:.4f} Y{:.4f}{}\n", quarter[i].x(), quarter[i].y(), i <= 20 ? " E0.05" : "");
  text += "M2\n";
  for (const char* dialect : {"marlin", "rs274"}) {
    CompressOptions opt;
    opt.dialect = dialect_named(dialect);
    DiagnosticSink sink;
    const CompressResult r = compress("t.gcode", text, opt, sink);
    REQUIRE(r.ok);
    INFO(dialect << ": " << r.stats.lines_out + r.stats.arcs_out << " primitives");
    CHECK(r.forced_kinks == 0);
    CHECK(r.stats.lines_out + r.stats.arcs_out >= min_g1_primitive_count(quarter, opt.fit.tolerance_mm, opt.fit.g1_angle_deg, {}, middle));
  }
}

TEST_CASE("no fit has fewer primitives than the bound in the same band, whatever the method", "[fit][bound]") {
  const std::vector<std::pair<const char*, std::vector<Vec2>>> curves = {
      {"sine", sampled(400, 0, 4 * kPi, [](double t) { return Vec2(t, 2 * std::sin(t)); })},
      {"spiral", sampled(500, 0.5, 5 * kPi, [](double t) { return Vec2(t * std::cos(t), t * std::sin(t)); })},
      {"y=x^3", sampled(500, -2, 2, [](double x) { return Vec2(x, x * x * x); })},
  };
  for (const auto& [name, raw] : curves)
    for (double tol : {0.05, 0.01, 0.002}) {
      const size_t bound = min_primitive_count(printed(raw), tol);
      const size_t g1_bound = min_g1_primitive_count(printed(raw), tol, FitOptions{}.g1_angle_deg);
      const size_t fitted_bound = min_g1_primitive_count_as_fitted(printed(raw), fitted_options(tol));
      const size_t fitted_c0_bound = min_primitive_count_as_fitted(printed(raw), fitted_options(tol));
      for (auto method : {FitOptions::Method::Arcs, FitOptions::Method::Global, FitOptions::Method::Greedy,
                          FitOptions::Method::Stream, FitOptions::Method::Lowe}) {
        const CompressResult r = fitted(raw, tol, method);
        REQUIRE(r.ok);
        REQUIRE(r.comparison.matched);
        const size_t count = r.stats.lines_out + r.stats.arcs_out;
        INFO(name << " at " << tol << " mm, method " << int(method) << ": " << count << " primitives, "
                  << r.forced_kinks << " forced kinks; bounds " << bound << ", " << g1_bound << " tangent, "
                  << fitted_bound << " tangent as fitted");
        // (Both bound the same fits from below; the tangent bound's relaxation, tangent ranges
        // a quarter degree wide, may let it fall a primitive below the exact count at any
        // angle in a tight band, as on the spiral at 0.002 mm.)
        CHECK(bound >= 2);
        CHECK(count >= bound);
        CHECK(count >= fitted_c0_bound);
        CHECK(fitted_bound >= g1_bound);
        // A fit without forced kinks is a tangent chain, joined within the share of the G1
        // angle the fitter turns by; the seed methods' may break anywhere.
        if (r.forced_kinks == 0) CHECK(count >= fitted_bound);
      }
    }
}

TEST_CASE("on the loop at 0.005 mm, where following one tangent at a time misses two primitives, the ranges of "
          "tangents find the fewest the fitter's band and joints allow, in the global method and in the default, "
          "whose primitives there span more than 25 moves each", "[fit][bound]") {
  const auto raw = loop_curve();
  const size_t optimum = min_g1_primitive_count_as_fitted(printed(raw), fitted_options(0.005));
  const size_t global = tangent_fit_count(raw, 0.005, FitOptions::Method::Global);
  const size_t arcs = tangent_fit_count(raw, 0.005, FitOptions::Method::Arcs);
  const size_t greedy = tangent_fit_count(raw, 0.005, FitOptions::Method::Greedy);
  INFO("the fewest tangent primitives as fitted " << optimum << ", global " << global << ", arcs " << arcs
                                                  << ", greedy " << greedy);
  CHECK(global == optimum);
  CHECK(arcs == optimum);
  CHECK(greedy >= optimum + 2);
}

TEST_CASE("on the published test curves at 0.01 mm, the global method finds the fewest tangent primitives and the "
          "default search is at most one more", "[fit][bound]") {
  auto bezier = [](Vec2 p0, Vec2 p1, Vec2 p2) {
    return [=](double t) { return Vec2((1 - t) * (1 - t) * p0 + 2 * t * (1 - t) * p1 + t * t * p2); };
  };
  const std::vector<std::pair<const char*, std::vector<Vec2>>> curves = {
      {"bezier1", sampled(999, 0, 1, bezier({1, 1}, {5, 1}, {1, 2.75}))},
      {"bezier2", sampled(999, 0, 1, bezier({0.54, 3.40}, {7.22, 3.61}, {7.39, 3.14}))},
      {"leaf", sampled(999, 0, 5, [](double t) { return Vec2(30 * t / (1 + t * t * t), 30 * t * t / (1 + t * t * t)); })},
      {"y=x^3", sampled(1999, -2, 2, [](double x) { return Vec2(x, x * x * x); })},
      {"loop", loop_curve()},
  };
  for (const auto& [name, raw] : curves) {
    const size_t optimum = min_g1_primitive_count(printed(raw), 0.01, 0.5);
    INFO(name << ": the fewest tangent primitives " << optimum);
    CHECK(tangent_fit_count(raw, 0.01, FitOptions::Method::Global) == optimum);
    CHECK(tangent_fit_count(raw, 0.01, FitOptions::Method::Arcs) <= optimum + 1);
  }
}
