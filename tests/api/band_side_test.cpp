// SPDX-License-Identifier: GPL-3.0-or-later
// A one-sided band (--band-side): every point of the output lies on the named side of the
// input path, relative to the direction of travel, or on it, within the band; the check
// measures the side and refuses the wrong one.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "arcpress/api/arcpress.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"
#include "arcpress/verify/move_geometry.hpp"
#include "support.hpp"

using namespace arcpress;

namespace {

/// A closed contour of `n` G1 moves around a circle of radius `r` about (50, 50), turning
/// left (`ccw`) or right, with a bump every eighth vertex so that it is no circle: a path
/// that bends both ways, convex and concave stretches in turn.
std::string contour(bool ccw, int n = 720, double r = 20) {
  std::string t = "G21 G90 G17\nG0 X70 Y50 Z1\nG1 Z-1 F300\nG1 F1200\n";
  for (int i = 1; i <= n; ++i) {
    const double a = (ccw ? 1 : -1) * 2 * M_PI * i / n;
    const double rr = r + 1.5 * std::sin(8 * 2 * M_PI * i / n);
    t += fmt::format("G1 X{:.4f} Y{:.4f}\n", 50 + rr * std::cos(a), 50 + rr * std::sin(a));
  }
  return t + "G0 Z5\nM2\n";
}

/// The feed path of `text` sampled every `step_mm` or closer (arcs along their circle).
std::vector<Vec2> sampled(const std::string& text, double step_mm) {
  DiagnosticSink sink("s.nc");
  Program p = lex("s.nc", text, sink);
  Interpretation in = interpret(p, sink);
  std::vector<Vec2> out;
  for (size_t i = 0; i < in.moves.size(); ++i) {
    const Move& m = in.moves[i];
    if (!is_feed(m.kind) || m.to[kZ] > 0) continue;
    const AxisValues& f = in.from(i);
    if (is_arc(m.kind)) {
      const ArcGeom g = arc_of_move(in, i);
      const int k = std::max(2, int(std::ceil(g.radius_mm * std::abs(g.sweep) / step_mm)));
      for (int s = 0; s <= k; ++s) {
        const Vec3 q = g.point_at(double(s) / k);
        out.emplace_back(q.x(), q.y());
      }
    } else {
      const Vec2 a(f[kX], f[kY]), b(m.to[kX], m.to[kY]);
      const int k = std::max(1, int(std::ceil((b - a).norm() / step_mm)));
      for (int s = 0; s <= k; ++s) out.push_back(a + (b - a) * (double(s) / k));
    }
  }
  return out;
}

/// Brute force, independent of the library's measure: for each point of `path`, its offset
/// from the input polyline `input` (nearest point over every segment), positive to the left of
/// the segment's direction; the greatest offset to the forbidden side, and the greatest distance.
struct SideReading {
  double wrong_mm = 0, distance_mm = 0;
};
SideReading read_side(const std::vector<Vec2>& path, const std::vector<Vec2>& input, BandSide side) {
  SideReading r;
  for (const Vec2& p : path) {
    double best = 1e300, offset = 0;
    for (size_t s = 0; s + 1 < input.size(); ++s) {
      const Vec2 a = input[s], d = input[s + 1] - a;
      const double len2 = d.squaredNorm();
      if (len2 == 0) continue;
      const double t = std::clamp((p - a).dot(d) / len2, 0.0, 1.0);
      const Vec2 q = a + t * d;
      const double dist = (p - q).norm();
      if (dist < best) {
        best = dist;
        offset = (d.x() * (p - q).y() - d.y() * (p - q).x()) / std::sqrt(len2);  // left > 0
      }
    }
    r.distance_mm = std::max(r.distance_mm, best);
    r.wrong_mm = std::max(r.wrong_mm, side == BandSide::Left ? -offset : offset);
  }
  return r;
}

CompressResult compressed(const std::string& text, BandSide side, double tol = 0.01) {
  CompressOptions opt;
  opt.fit.tolerance_mm = tol;
  opt.fit.band_side = side;
  DiagnosticSink sink("c.nc");
  return compress("c.nc", text, opt, sink);
}

}  // namespace

TEST_CASE("with a one-sided band the output lies on that side of the input, turning either way",
          "[band_side]") {
  for (bool ccw : {true, false}) {
    const std::string in = contour(ccw);
    const std::vector<Vec2> input = sampled(in, 1e9);  // (its vertices)
    for (BandSide side : {BandSide::Left, BandSide::Right}) {
      INFO((ccw ? "turning left, " : "turning right, ") << (side == BandSide::Left ? "left" : "right"));
      const CompressResult r = compressed(in, side);
      REQUIRE(r.ok);
      REQUIRE(r.within_band());
      CHECK(r.stats.arcs_out > 0);
      CHECK(r.stats.lines_out + r.stats.arcs_out < 720 / 3);
      const SideReading s = read_side(sampled(r.output, 0.01), input, side);
      CHECK(s.distance_mm <= 0.01 + 1e-6);
      // On the allowed side but for the rounding of printed centres (3 % of the band).
      CHECK(s.wrong_mm <= 0.0003 + 1e-6);
      CHECK(r.comparison.max_wrong_side_mm <= r.side_allowance_mm);
    }
  }
}

TEST_CASE("a two-sided fit strays to both sides, and the one-sided check and diff say where", "[band_side]") {
  const std::string in = contour(true);
  const std::vector<Vec2> input = sampled(in, 1e9);
  const CompressResult both = compressed(in, BandSide::Both);
  REQUIRE(both.within_band());
  const std::vector<Vec2> out = sampled(both.output, 0.01);
  // The brute force sees the two-sided output on both sides, by much more than rounding ...
  CHECK(read_side(out, input, BandSide::Left).wrong_mm > 0.003);
  CHECK(read_side(out, input, BandSide::Right).wrong_mm > 0.003);
  // ... and so does arcpress diff --band-side, which then says DIFFERENT (exit 1).
  const test::TempDir dir = test::temp_dir("side");
  test::write_file(dir / "in.nc", in);
  test::write_file(dir / "both.nc", both.output);
  const std::string a = (dir / "in.nc").string(), b = (dir / "both.nc").string();
  for (const char* side : {"left", "right"}) {
    const test::Command d = test::run_arcpress(fmt::format("diff '{}' '{}' --band-side {}", a, b, side));
    CHECK(d.exit_code == 1);
    CHECK(d.out.find(fmt::format("band side {}: B lies at most 0.00", side)) != std::string::npos);
  }
  CHECK(test::run_arcpress(fmt::format("diff '{}' '{}'", a, b)).exit_code == 0);
  // A program whose moves do not end on A's vertices cannot be measured by side: INCOMPLETE.
  test::write_file(dir / "moved.nc", contour(true, 720, 20.002));  // (no vertex of A)
  const test::Command moved = test::run_arcpress(
      fmt::format("diff '{}' '{}' --band-side left --tolerance 5", a, (dir / "moved.nc").string()));
  CHECK(moved.exit_code == 2);
  CHECK(moved.out.find("band side left: not measured") != std::string::npos);
}

TEST_CASE("under cutter compensation the side is the programmed contour's: G41 keeps the tool left, so --band-side "
          "left keeps the output off the material on the right",
          "[band_side]") {
  // The part's outline, clockwise, with the tool on its left (G41): the material is on the right.
  std::string in = contour(false);
  in.replace(in.find("G1 F1200\n"), 9, "G41 D1\nG1 F1200\n");
  in.replace(in.find("G0 Z5\n"), 6, "G40\nG0 Z5\n");
  const CompressResult r = compressed(in, BandSide::Left);
  REQUIRE(r.ok);
  REQUIRE(r.within_band());
  CHECK(r.output.find("G41 D1") != std::string::npos);  // written back as it was
  const SideReading s = read_side(sampled(r.output, 0.01), sampled(in, 1e9), BandSide::Left);
  CHECK(s.wrong_mm <= 0.0003 + 1e-6);
}

TEST_CASE("a one-sided band on a firmware's chords is refused: they cut inside each arc", "[band_side][cli]") {
  const std::string in = contour(true);
  const test::Command refused = test::run_arcpress("--dialect marlin --band-side left", in);
  CHECK(refused.exit_code == 2);
  CHECK(refused.err.find("add --band program") != std::string::npos);
  const test::Command programmed = test::run_arcpress("--dialect marlin --band-side left --band program --stats", in);
  CHECK(programmed.exit_code == 0);
  CHECK(programmed.err.find("band side      left: the output lies at most 0.000") != std::string::npos);
}
