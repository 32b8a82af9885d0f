// SPDX-License-Identifier: GPL-3.0-or-later
// `arcpress diff` as a specification: what it measures for known differences.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <regex>
#include <vector>

#include "arcpress/api/arcpress.hpp"
#include "arcpress/dialect/dialect_loader.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"
#include "arcpress/verify/diff_plot.hpp"
#include "arcpress/verify/executed_path.hpp"
#include "arcpress/verify/program_diff.hpp"
#include "support.hpp"

using namespace arcpress;

namespace {

ProgramDiff diff_of(const std::string& a, const std::string& b, double tol = 0.01) {
  DiffOptions opt;
  opt.tolerance_mm = tol;
  return test::diff_texts(a, b, opt);
}

/// A zig-zag cut: rapid in, spindle on, ten feed moves, rapid out.
std::string zigzag(double moved_y_at_5 = 0.0, const std::string& spindle = "M3 S1000") {
  std::string t = "G21 G90\nG0 X0 Y0 Z1\n" + spindle + "\nG1 Z0 F300\n";
  for (int k = 1; k <= 10; ++k)
    t += fmt::format("G1 X{} Y{:.4f}\n", k, k == 5 ? moved_y_at_5 : 0.0);  // a straight line along X
  return t + "G0 Z5\nM5\nM2\n";
}

}  // namespace

TEST_CASE("identical programs differ by nothing", "[diff]") {
  ProgramDiff d = diff_of(zigzag(), zigzag());
  CHECK(d.max_deviation_mm == 0.0);
  CHECK(d.feed_compared_share == 1.0);
  CHECK(d.findings.empty());
  CHECK(d.same(0.01));
  CHECK(d.a.feed_moves == 11);
  CHECK(d.a.sections == 1);
}

TEST_CASE("one point moved by a known amount is found with that amount, at its lines", "[diff]") {
  ProgramDiff d = diff_of(zigzag(), zigzag(0.0123));
  CHECK(d.max_deviation_mm == Approx(0.0123).margin(1e-9));
  REQUIRE_FALSE(d.worst.empty());
  CHECK(d.worst[0].deviation_mm == Approx(0.0123).margin(1e-9));
  CHECK(d.worst[0].line_b == 9);  // "G1 X5 Y0.0123"
  CHECK(d.worst[0].at.x() == Approx(5.0));
  CHECK_FALSE(d.same(0.01));
  CHECK(d.same(0.013));
}

TEST_CASE("an arc replaced by its chord differs by the arc's sagitta", "[diff]") {
  // 60 degrees of radius 10 about (0, 0): sagitta 10 * (1 - cos 30 degrees).
  std::string arc = "G21 G90 G17\nG0 X10 Y0 Z0\nG3 X5 Y8.660254 I-10 J0 F100\nM2\n";
  std::string chord = "G21 G90 G17\nG0 X10 Y0 Z0\nG1 X5 Y8.660254 F100\nM2\n";
  double sagitta = 10 * (1 - std::cos(kPi / 6));
  ProgramDiff d = diff_of(arc, chord);
  CHECK(d.max_deviation_mm == Approx(sagitta).margin(d.arc_chord_mm));
  CHECK(d.arc_chord_mm <= 1e-5);
  REQUIRE_FALSE(d.worst.empty());
  CHECK(d.worst[0].line_a == 3);
  CHECK(d.worst[0].line_b == 3);
}

TEST_CASE("arcs are measured as arcs, not as chords: concentric arcs lie apart by their radii's difference",
          "[diff]") {
  // Half turns of radius 10 and 10.003 mm about the origin are 0.003 mm apart everywhere, both
  // ways; chords of either would read up to their sagitta more or less.
  std::string a = "G21 G90 G17\nG0 X10 Y0 Z0\nG3 X-10 Y0 I-10 J0 F100\nM2\n";
  std::string b = "G21 G90 G17\nG0 X10.003 Y0 Z0\nG3 X-10.003 Y0 I-10.003 J0 F100\nM2\n";
  for (double tol : {0.01, 0.1}) {
    INFO("band " << tol << " mm");
    CHECK(diff_of(a, b, tol).max_deviation_mm == Approx(0.003).margin(1e-9));
    CHECK(diff_of(b, a, tol).max_deviation_mm == Approx(0.003).margin(1e-9));
  }
  // The same half turn written as one block and as three: nothing apart.
  std::string thirds = "G21 G90 G17\nG0 X10 Y0 Z0\nG3 X5 Y8.6602540378 I-10 J0 F100\n"
                       "G3 X-5 Y8.6602540378 I-5 J-8.6602540378\nG3 X-10 Y0 I5 J-8.6602540378\nM2\n";
  CHECK(diff_of(a, thirds).max_deviation_mm < 1e-9);
  CHECK(diff_of(thirds, a).max_deviation_mm < 1e-9);
}

namespace {

/// A feed move in XY for the brute-force measure below: a line, or an arc about `c`.
struct DrawnMove {
  Vec2 from, to, c;
  bool arc = false, ccw = true;
  /// Point at fraction t along it (an arc by angle, its radius taken at the start).
  Vec2 at(double t) const {
    if (!arc) return from + t * (to - from);
    const Vec2 s = from - c, e = to - c;
    double sweep = std::atan2(cross2(s, e), s.dot(e));
    if (ccw && sweep <= 0) sweep += 2 * kPi;
    if (!ccw && sweep >= 0) sweep -= 2 * kPi;
    const double a = std::atan2(s.y(), s.x()) + t * sweep, r = s.norm();
    return c + r * Vec2(std::cos(a), std::sin(a));
  }
  /// Signed sweep from `from` to `to` about `c`.
  double sweep() const {
    const Vec2 s = from - c, e = to - c;
    double w = std::atan2(cross2(s, e), s.dot(e));
    if (ccw && w <= 0) w += 2 * kPi;
    if (!ccw && w >= 0) w -= 2 * kPi;
    return w;
  }
  double length() const { return arc ? (from - c).norm() * std::abs(sweep()) : (to - from).norm(); }
  /// Distance from p: to the segment, or to the arc (p's own angle if the arc passes it,
  /// else the nearer end).
  double distance(const Vec2& p) const {
    if (!arc) {
      const Vec2 d = to - from;
      const double t = d.squaredNorm() > 0 ? std::clamp((p - from).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      return (from + t * d - p).norm();
    }
    const Vec2 s = from - c, v = p - c;
    double turn = std::atan2(cross2(s, v), s.dot(v));  // from the start to p's angle, signed
    const double w = sweep();
    if (w > 0 && turn < 0) turn += 2 * kPi;
    if (w < 0 && turn > 0) turn -= 2 * kPi;
    if (std::abs(turn) <= std::abs(w)) return std::abs(v.norm() - s.norm());
    return std::min((p - from).norm(), (p - at(1)).norm());
  }
};

/// The largest distance from points every `step_mm` along `a` to the path `b`: a lower bound
/// of the true largest distance, short of it by at most half a step.
double sampled_max(const std::vector<DrawnMove>& a, const std::vector<DrawnMove>& b, double step_mm) {
  double worst = 0;
  for (const DrawnMove& m : a) {
    const int n = std::max(2, int(m.length() / step_mm));
    for (int k = 0; k <= n; ++k) {
      const Vec2 p = m.at(double(k) / n);
      double best = HUGE_VAL;
      for (const DrawnMove& o : b) best = std::min(best, o.distance(p));
      worst = std::max(worst, best);
    }
  }
  return worst;
}

std::string program_of(const std::vector<DrawnMove>& moves) {
  std::string t = fmt::format("G21 G90 G17\nG0 X{:.9f} Y{:.9f} Z0\n", moves[0].from.x(), moves[0].from.y());
  for (const DrawnMove& m : moves) {
    if (m.arc)
      t += fmt::format("G{} X{:.9f} Y{:.9f} I{:.9f} J{:.9f} F500\n", m.ccw ? 3 : 2, m.to.x(), m.to.y(),
                       m.c.x() - m.from.x(), m.c.y() - m.from.y());
    else
      t += fmt::format("G1 X{:.9f} Y{:.9f} F500\n", m.to.x(), m.to.y());
  }
  return t + "M2\n";
}

}  // namespace

TEST_CASE("on random lines and arcs the measure finds every distance a dense sampling finds", "[diff]") {
  // A path of lines and arcs (radii 0.5 to 20 mm) and another near it: ends moved by up to
  // 0.02 mm, arcs re-centred through them, one in three drawn as a line. The diff never reads
  // less than the farthest of points every 0.002 mm along either path from the other,
  // less the measure's precision, nor more than the distance can grow between two of them.
  std::mt19937 gen(7);
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(gen); };
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<DrawnMove> a, b;
    Vec2 at(0, 0), bt(0, 0);
    for (int k = 0; k < 4; ++k) {
      DrawnMove m;
      m.from = at;
      m.arc = k % 2 == 1 || uniform(0, 1) < 0.5;
      const double len = uniform(0.5, 8), dir = uniform(0, 2 * kPi);
      m.to = at + len * Vec2(std::cos(dir), std::sin(dir));
      if (m.arc) {
        // Centre on the chord's bisector: radius at least half the chord.
        const Vec2 mid = (m.from + m.to) / 2, n = left_normal((m.to - m.from).normalized());
        const double r = uniform(len / 2 + 0.01, std::max(len / 2 + 0.02, 20.0));
        m.c = mid + n * std::sqrt(r * r - len * len / 4) * (uniform(0, 1) < 0.5 ? 1 : -1);
        m.ccw = uniform(0, 1) < 0.5;
      }
      a.push_back(m);
      DrawnMove w = m;
      w.from = bt;
      w.to = m.to + Vec2(uniform(-0.02, 0.02), uniform(-0.02, 0.02));
      if (w.arc && uniform(0, 1) < 0.33) w.arc = false;
      if (w.arc) {  // the point of A's centre's bisector line nearest it, so both ends are on the circle
        const Vec2 mid = (w.from + w.to) / 2, n = left_normal((w.to - w.from).normalized());
        w.c = mid + n * n.dot(m.c - mid);
      }
      b.push_back(w);
      at = m.to;
      bt = w.to;
    }
    INFO("trial " << trial << "\nA:\n" << program_of(a) << "B:\n" << program_of(b));
    const ProgramDiff d = diff_of(program_of(a), program_of(b), 0.05);
    const double precision = d.arc_chord_mm;
    const double sampled = std::max(sampled_max(a, b, 0.002), sampled_max(b, a, 0.002));
    CHECK(d.max_deviation_mm >= sampled - precision - 1e-9);
    // ... and no more than the distance can grow between two samples.
    CHECK(d.max_deviation_mm <= sampled + 0.001 + 1e-9);
  }
}

TEST_CASE("a bulge between the samples of either path is not missed", "[diff]") {
  // B takes a long straight line where A makes a detour in the middle: A's vertices are all
  // on B's line except one; B's vertices are all on A's path.
  std::string a = "G21 G90\nG0 X0 Y0 Z0\nG1 X4.9 Y0 F100\nX5 Y0.05\nX5.1 Y0\nX10 Y0\nM2\n";
  std::string b = "G21 G90\nG0 X0 Y0 Z0\nG1 X10 Y0 F100\nM2\n";
  CHECK(diff_of(a, b).max_deviation_mm == Approx(0.05).margin(1e-9));
  CHECK(diff_of(b, a).max_deviation_mm == Approx(0.05).margin(1e-9));
}

TEST_CASE("the maximum and the worst places are the same on any number of threads", "[diff][threads]") {
  // A long line along X whose copy has six bumps of known heights spread along it, so that
  // the measure's shares each hold some and their lists must be merged. Each bump's vertex
  // lies a quarter of the way along the line's move, so the farthest point of the line
  // from the copy there lies between the line's vertices, where only a split finds it, and
  // no point of either path is equally near two moves of the other.
  const int moves = 150000;
  const std::vector<std::pair<int, double>> bumps = {{20, 0.004},     {40075, 0.009},  {61110, 0.002},
                                                     {99160, 0.007}, {120230, 0.005}, {149290, 0.003}};
  auto line = [&](bool bumped) {
    std::string t = "G21 G90\nG0 X0 Y0 Z0\nG1 F300\n";
    for (int k = 1; k <= moves; ++k) {
      double x = k, y = 0;
      for (auto [at, h] : bumps)
        if (bumped && k == at) x = k + 0.25, y = h;
      t += fmt::format("G1 X{:.2f} Y{:.4f}\n", x, y);
    }
    return t + "M2\n";
  };
  DiagnosticSink sa("a.nc"), sb("b.nc");
  Program pa = lex("a.nc", line(false), sa), pb = lex("b.nc", line(true), sb);
  Interpretation ia = interpret(pa, sa), ib = interpret(pb, sb);
  std::vector<DiffPlace> one_thread;
  for (unsigned threads : {1u, 2u, 3u, 7u}) {
    INFO(threads << " threads");
    DiffOptions opt;
    opt.top = 5;
    opt.threads = threads;
    ProgramDiff d = diff_programs(pa, ia, pb, ib, opt);
    CHECK(d.max_deviation_mm == Approx(0.009).margin(1e-9));
    REQUIRE(d.worst.size() == 5);
    // The copy's "G1 X40075.25 ..." is its line 40 078, over the line's move to X40076.
    CHECK(d.worst[0].line_b == 40078);
    CHECK(d.worst[0].line_a == 40079);
    // Each place lies at one of the two largest bumps, within its height.
    for (const DiffPlace& p : d.worst) {
      const bool at_bump = std::abs(p.at.x() - 40075.25) < 1 || std::abs(p.at.x() - 99160.25) < 1;
      CHECK(at_bump);
      CHECK(p.deviation_mm <= 0.009 + 1e-9);
    }
    if (threads == 1) {
      one_thread = d.worst;
      continue;
    }
    for (size_t k = 0; k < 5; ++k) {
      CHECK(d.worst[k].deviation_mm == one_thread[k].deviation_mm);
      CHECK(d.worst[k].line_a == one_thread[k].line_a);
      CHECK(d.worst[k].line_b == one_thread[k].line_b);
    }
  }
}

TEST_CASE("a swapped M-code is reported even where the paths agree", "[diff]") {
  ProgramDiff d = diff_of(zigzag(), zigzag(0, "M4 S1000"));
  CHECK(d.max_deviation_mm == 0.0);
  CHECK(d.non_motion_differences == 1);
  REQUIRE(d.findings.size() == 1);
  CHECK(d.findings[0] == "non-motion block differs: A line 3 'M3 S1000', B line 3 'M4 S1000'");
  CHECK_FALSE(d.same(0.01));
}

TEST_CASE("non-motion blocks are compared by their M, T and S words, dwell and comment, in any case and spacing, and "
          "one more on either side is counted", "[diff]") {
  const std::string a = "G21 G90\nM3 S1000 (spindle on)\nG1 X10 F100\nM5\nG4 P1\nT2 M6\nM2\n";
  const std::string b = "G21 G90\nm3  s1000 (SPINDLE ON)\nG1 X10 F100\nM5\nG4 P2\nT2 M6\nM2\nM30\n";
  ProgramDiff d = diff_of(a, b);
  CHECK(d.max_deviation_mm == 0.0);
  CHECK(d.a.non_motion == 5);
  CHECK(d.b.non_motion == 6);
  CHECK(d.non_motion_differences == 2);
  REQUIRE(d.findings.size() == 2);
  CHECK(d.findings[0] == "non-motion block differs: A line 5 'G4 P1', B line 5 'G4 P2'");
  CHECK(d.findings[1] == "non-motion blocks (M, T, S, dwell, comments): 5 in A, 6 in B");
  CHECK_FALSE(d.same(0.01));
  CHECK(diff_of(a, a).non_motion_differences == 0);
  CHECK(diff_of(b, b).same(0.01));
}

TEST_CASE("changed extrusion and feed are reported", "[diff]") {
  std::string a = "G21 G90 M82\nG0 X0 Y0 Z0.2\nG1 X10 Y0 E1.0 F1200\nG1 X10 Y10 E2.0\nG0 Z1\n";
  std::string more_e = "G21 G90 M82\nG0 X0 Y0 Z0.2\nG1 X10 Y0 E1.0 F1200\nG1 X10 Y10 E2.1\nG0 Z1\n";
  ProgramDiff e = diff_of(a, more_e);
  CHECK(e.max_deviation_mm == 0.0);
  CHECK(e.max_extrusion_difference_mm == Approx(0.1));
  CHECK_FALSE(e.same(0.01));
  std::string slower = "G21 G90 M82\nG0 X0 Y0 Z0.2\nG1 X10 Y0 E1.0 F1200\nG1 X10 Y10 E2.0 F600\nG0 Z1\n";
  ProgramDiff f = diff_of(a, slower);
  CHECK(f.max_feed_difference_pct == Approx(50.0));
  CHECK(f.worst_feed.line_b == 4);
  CHECK_FALSE(f.same(0.01));
}

TEST_CASE("feed is compared with the move at the same place in program order", "[diff]") {
  // A prints along X at F1200, travels back and then retraces the printed line at F7800,
  // 0.005 mm to the side. B prints the same line 0.004 mm to the side, in two moves: the
  // travel is nearer B's print than A's print is, but comes later in the program.
  auto program = [](const std::string& print) {
    return "G21 G90 M83\nG0 X0 Y0 Z0.2\n" + print + "G1 X0 Y0.005 F7800\nG1 X10 Y0.005\nG0 Z1\n";
  };
  std::string a = program("G1 X10 Y0 E1.0 F1200\n");
  std::string b = program("G1 X5 Y0.004 E0.5 F1200\nG1 X10 Y0.004 E0.5\n");
  ProgramDiff same = diff_of(a, b);
  CHECK(same.max_feed_difference_pct == 0.0);
  CHECK(same.findings.empty());
  std::string b_slow = program("G1 X5 Y0.004 E0.5 F1200\nG1 X10 Y0.004 E0.5 F1000\n");
  ProgramDiff slow = diff_of(a, b_slow);
  CHECK(slow.max_feed_difference_pct == Approx(100.0 * 200 / 1200));
  CHECK(slow.worst_feed.line_a == 3);
  CHECK(slow.worst_feed.line_b == 4);
  // Where the feed changes at a joint, points within the band of it are not compared: the
  // first chord of B's arc starts where the travel ends.
  std::string travel_then_arc = "G21 G90 M83\nG0 X0 Y0 Z0.2\nG1 X10 Y0 F7800\nG1 X20 Y0 E1 F1200\n";
  std::string travel_then_arc_b = "G21 G90 M83\nG0 X0 Y0 Z0.2\nG1 X10 Y0 F7800\nG2 X20 Y0 I5 J-200 E1 F1200\n";
  ProgramDiff joint = diff_of(travel_then_arc, travel_then_arc_b, 0.1);
  CHECK(joint.max_feed_difference_pct == 0.0);
}

TEST_CASE("a piece that bends off a short move stays paired with it rather than with a later pass nearby", "[diff]") {
  // A prints a short move (1, 0) -> (1.128, 0) and turns back down; later a wipe at F7200
  // passes the end of that move at 45°. B writes the short move as an arc that bulges 0.037 mm
  // below it (inside the 0.05 mm band), so its last pieces head 45° to 60° off the move:
  // they are still the move's, and its feed is the one to compare.
  auto program = [](const std::string& short_move) {
    return "G21 G90 M83\nG0 X0 Y0 Z0.2\nG1 X1 Y0 E0.1 F1200\n" + short_move +
           "G1 X0.9 Y-0.2 E0.1\nG1 E-1 F2400\nG1 X1.08 Y-0.06 F7200\nG1 X1.16 Y0.02 E-0.1\nG1 X2 Y2\nG0 Z1\n";
  };
  std::string a = program("G1 X1.128 Y0 E0.02\n");
  std::string b = program("G3 X1.128 Y0 I0.064 J0.03695 E0.02\n");
  ProgramDiff d = diff_of(a, b, 0.05);
  CHECK(d.max_deviation_mm < 0.05);
  CHECK(d.max_feed_difference_pct == 0.0);
  CHECK(d.findings.empty());
  // A feed that did change on that move is still caught.
  std::string b_slow = program("G3 X1.128 Y0 I0.064 J0.03695 E0.02 F900\n");
  b_slow.replace(b_slow.find("G1 X0.9 Y-0.2 E0.1"), 18, "G1 X0.9 Y-0.2 E0.1 F1200");
  ProgramDiff slow = diff_of(a, b_slow, 0.05);
  CHECK(slow.max_feed_difference_pct == Approx(25.0));
}

TEST_CASE("a small arc beside a long plunge, in a band wider than the arc, is paired with its own move", "[diff]") {
  // Both plunge 11 mm and circle at the bottom (radius 0.5 mm, F400); A ramps down in steps at
  // F100, B in one line. In a 2 mm band B's arcs lie within the band of A's plunge, and
  // head square to it: they are paired with A's own arcs, ahead, not with the plunge at
  // F100 (which does not lie within the band of them).
  auto program = [](const std::string& descent) {
    return "G21 G90\nG0 X0 Y0 Z1\n" + descent +
           "G3 X1 Y0.5 I0 J0.5 F400\nG3 X0 Y0.5 I-0.5 J0\nG3 X0.5 Y0 I0.5 J0\nG0 Z5\nM2\n";
  };
  std::string a =
      program("G1 Z-10 F100\nG1 X0.1 Z-10.2\nG1 X0.2 Z-10.4\nG1 X0.3 Z-10.6\nG1 X0.4 Z-10.8\nG1 X0.5 Z-11\n");
  std::string b = program("G1 X0.5 Z-11 F100\n");
  ProgramDiff d = diff_of(a, b, 2.0);
  CHECK(d.max_deviation_mm < 2.0);
  CHECK(d.max_feed_difference_pct == 0.0);
  CHECK(d.findings.empty());
  CHECK(d.same(2.0));
  // The circle's first 2 mm along the path lie within the band of the joint where the feed
  // changes, so their feed is not compared, and the report says so: of B's 15.2 mm feed
  // path, the descent (12 mm) and the last 1.1 mm of the circle (give or take a piece).
  const double descent_mm = std::sqrt(0.5 * 0.5 + 12.0 * 12.0), circle_mm = kPi;
  CHECK(d.feed_compared_share == Approx((descent_mm + circle_mm - 2) / (descent_mm + circle_mm)).epsilon(0.01));
  CHECK(d.feed_unpaired_mm == 0);
}

TEST_CASE("where moves are shorter than the band, a feed change a few moves away is as near as the next joint",
          "[diff]") {
  // Moves of 0.2 mm along X; the feed goes from F1000 to F1010 at X0.6 in A, and at `change`
  // in B. Within a 1 mm band which of the moves around a change a point belongs to is
  // ambiguous, so the feed there is not compared, however many joints away the change is.
  auto program = [](double change) {
    std::string t = "G21 G90\nG0 X0 Y0 Z0\n";
    for (int k = 1; k <= 30; ++k) {
      const double x = 0.2 * k;
      t += fmt::format("G1 X{:.1f} F{}\n", x, x <= change + 1e-9 ? 1000 : 1010);
    }
    return t + "G0 Z5\nM2\n";
  };
  const std::string a = program(0.6);
  ProgramDiff shifted = diff_of(a, program(1.4), 1.0);  // the change 0.8 mm further on
  CHECK(shifted.max_feed_difference_pct == 0.0);
  CHECK(shifted.same(1.0));
  CHECK(shifted.feed_compared_share < 0.8);  // 2.4 of B's 6 mm lie within 1 mm of a change
  // A change moved by more than the band is found.
  ProgramDiff moved = diff_of(a, program(3.0), 1.0);
  CHECK(moved.max_feed_difference_pct == Approx(100.0 * 10 / 1010));
  CHECK(moved.verdict(1.0) == ProgramDiff::Verdict::Different);
}

TEST_CASE("a feed that B changes on one block shorter than the band, where A's stays the same, is a difference",
          "[diff]") {
  // Which move a point stands for is ambiguous only near a change of A's feed: a change
  // that B makes and A does not is found at its line, however wide the band.
  auto program = [](int slow_move) {
    std::string t = "G21 G90\nG0 X0 Y0 Z0\n";
    for (int k = 1; k <= 30; ++k) t += fmt::format("G1 X{:.1f} F{}\n", 0.2 * k, k == slow_move ? 900 : 1000);
    return t + "G0 Z5\nM2\n";
  };
  ProgramDiff d = diff_of(program(0), program(15), 1.0);
  CHECK(d.max_feed_difference_pct == Approx(10.0));
  CHECK(d.worst_feed.line_b == 17);  // "G1 X3.0 F900"
  CHECK(d.verdict(1.0) == ProgramDiff::Verdict::Different);
  CHECK(diff_of(program(0), program(0), 1.0).same(1.0));
}

TEST_CASE("a piece of B within the band of A that no piece of A can stand for leaves the check incomplete",
          "[diff]") {
  // B prints the same E over the first half of the line and travels the second half, where A
  // prints: a travel is not paired with a move that prints, so the feed along the travel is
  // not compared, and the check does not pass what it did not compare.
  const std::string a = "G21 G90 M83\nG0 X0 Y0 Z0.2\nG1 X10 E1 F1200\nG0 Z5\nM2\n";
  const std::string b = "G21 G90 M83\nG0 X0 Y0 Z0.2\nG1 X5 E1 F1200\nG1 X10\nG0 Z5\nM2\n";
  ProgramDiff d = diff_of(a, b, 0.05);
  CHECK(d.max_deviation_mm == 0.0);
  CHECK(d.agrees(0.05));
  CHECK(d.feed_unpaired_mm == Approx(5.0));
  CHECK(d.feed_unpaired_line_b == 4);
  CHECK(d.feed_compared_share == Approx(0.5));
  CHECK(d.verdict(0.05) == ProgramDiff::Verdict::Incomplete);
  // B as A: all of it paired.
  ProgramDiff same = diff_of(a, a, 0.05);
  CHECK(same.feed_unpaired_mm == 0);
  CHECK(same.verdict(0.05) == ProgramDiff::Verdict::Same);
}

TEST_CASE("with comments left out, another tool's header comments are no difference, but M, T, S and dwells are",
          "[diff]") {
  const std::string a =
      "; sliced\nG21 G90 M83\nM104 S210\nG0 X0 Y0 Z0.2\n;TYPE:WALL\nG1 X10 Y0 E1 F1200\nG4 P100\nM107\n";
  const std::string b = "; sliced\n; post-processed by another tool\nG21 G90 M83\nM104 S210\nG0 X0 Y0 Z0.2\n"
                        ";TYPE:WALL (arcs)\nG1 X10 Y0 E1 F1200\nG4 P100\nM107\n";
  DiffOptions opt;
  opt.tolerance_mm = 0.01;
  const ProgramDiff with = test::diff_texts(a, b, opt);
  CHECK(with.comments_compared);
  CHECK(with.non_motion_differences > 0);
  CHECK_FALSE(with.same(0.01));
  opt.comments = false;
  const ProgramDiff without = test::diff_texts(a, b, opt);
  CHECK_FALSE(without.comments_compared);
  CHECK(without.non_motion_differences == 0);
  CHECK(without.a.non_motion == 4);  // M83, M104 S210, G4 P100, M107
  CHECK(without.same(0.01));
  for (const auto& [was, changed] : {std::pair("M104 S210", "M104 S215"), std::pair("G4 P100", "G4 P200"),
                                     std::pair("M107", "M106")}) {
    std::string c = b;
    c.replace(c.find(was), std::string(was).size(), changed);
    INFO(changed);
    CHECK_FALSE(test::diff_texts(a, c, opt).same(0.01));
  }
}

TEST_CASE("the same path in inches and in millimetres is the same", "[diff]") {
  std::string mm = "G21 G90\nG0 X0 Y0 Z0\nG1 X25.4 Y0 F254\nG2 X50.8 Y0 I12.7 J0\nM2\n";
  std::string inch = "G20 G90\nG0 X0 Y0 Z0\nG1 X1 Y0 F10\nG2 X2 Y0 I0.5 J0\nM2\n";
  ProgramDiff d = diff_of(mm, inch);
  CHECK(d.max_deviation_mm < 1e-9);
  CHECK(d.findings.empty());
  CHECK(d.same(0.001));
}

TEST_CASE("a different number of rapids or cutting sections is a difference", "[diff]") {
  std::string one = "G21 G90\nG0 X0 Y0 Z0\nG1 X10 F100\nG1 X20\nM2\n";
  std::string two = "G21 G90\nG0 X0 Y0 Z0\nG1 X10 F100\nG0 X10\nG1 X20\nM2\n";
  ProgramDiff d = diff_of(one, two);
  CHECK(d.max_deviation_mm < 1e-9);
  CHECK(d.b.sections == 2);
  CHECK_FALSE(d.same(0.01));
}

TEST_CASE("arcpress diff on the command line: text, JSON, exit codes", "[diff][cli]") {
  auto dir = test::temp_dir("diff-cli");
  test::write_file(dir / "a.nc", zigzag());
  test::write_file(dir / "b.nc", zigzag(0.0123));
  auto same = test::run_arcpress(fmt::format("diff {0}/a.nc {0}/a.nc", dir.string()));
  CHECK(same.exit_code == 0);
  CHECK(same.out.find("SAME: max deviation 0.000000 mm within the 0.01 mm band") != std::string::npos);
  auto diff = test::run_arcpress(fmt::format("diff {0}/a.nc {0}/b.nc --top 2", dir.string()));
  CHECK(diff.exit_code == 1);
  CHECK(diff.out.find("#1 0.012300 mm at X5.0000 Y0.0123 Z0.0000") != std::string::npos);
  CHECK(diff.out.find("DIFFERENT") != std::string::npos);
  auto json = test::run_arcpress(fmt::format("diff {0}/a.nc {0}/b.nc --json", dir.string()));
  CHECK(json.exit_code == 1);
  CHECK(json.out.find("\"verdict\": \"different\"") != std::string::npos);
  CHECK(json.out.find("\"max_deviation_mm\": 0.012300000") != std::string::npos);
  CHECK(json.out.find("\"line_b\": 9") != std::string::npos);
  auto ok = test::run_arcpress(fmt::format("diff {0}/a.nc {0}/b.nc --tolerance 0.02 --json", dir.string()));
  CHECK(ok.exit_code == 0);
  CHECK(ok.out.find("\"verdict\": \"same\"") != std::string::npos);
  // Another tool's header comment: a difference, unless comments are left out.
  test::write_file(dir / "c.nc", "(post-processed)\n" + zigzag());
  auto commented = test::run_arcpress(fmt::format("diff {0}/a.nc {0}/c.nc", dir.string()));
  CHECK(commented.exit_code == 1);
  auto ignored = test::run_arcpress(fmt::format("diff {0}/a.nc {0}/c.nc --ignore-comments", dir.string()));
  CHECK(ignored.exit_code == 0);
  CHECK(ignored.out.find("non-motion blocks (M, T, S, dwell; comments not compared)") != std::string::npos);
  auto ignored_json = test::run_arcpress(fmt::format("diff {0}/a.nc {0}/c.nc --ignore-comments --json", dir.string()));
  CHECK(ignored_json.out.find("\"comments\": false") != std::string::npos);
}

TEST_CASE("the SVG plot's text stays inside the picture and off the drawing, however long the file names",
          "[diff][plot]") {
  auto dir = test::temp_dir("plot-text");
  const std::filesystem::path deep = dir / std::string(180, 'n') / "Ø-pièce 部品 with a long name.nc";
  std::filesystem::create_directories(deep.parent_path());
  std::string a = "G21 G90\nG0 X10 Y0 Z0\n", b = a;
  for (int k = 1; k <= 360; ++k) {
    const double t = 2 * kPi * k / 360, r = k == 90 ? 10.02 : 10.0;
    a += fmt::format("G1 X{:.4f} Y{:.4f} F300\n", 10 * std::cos(t), 10 * std::sin(t));
    b += fmt::format("G1 X{:.4f} Y{:.4f} F300\n", r * std::cos(t), r * std::sin(t));
  }
  test::write_file(deep, a);
  test::write_file(dir / "b.nc", b);
  auto c = test::run_arcpress(fmt::format("diff '{}' '{}/b.nc' --plot '{}/plot.svg'", deep.string(), dir.string(),
                                          dir.string()));
  CHECK(c.exit_code == 1);
  const std::string svg = test::read_file(dir / "plot.svg");
  // The lowest point any path or the worst place's ring reaches.
  double drawing_bottom = 0;
  const std::regex coordinate("[MLA ]-?[0-9.]+ (-?[0-9.]+)"), ring("cy=\"([0-9.]+)\"");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), coordinate); it != std::sregex_iterator(); ++it)
    drawing_bottom = std::max(drawing_bottom, std::stod((*it)[1]));
  std::smatch m;
  REQUIRE(std::regex_search(svg, m, ring));
  drawing_bottom = std::max(drawing_bottom, std::stod(m[1]) + 9);
  // Every line of text, counted in characters (a UTF-8 sequence is one) at the widest a
  // 14 px sans-serif character is (9 px), ends inside the 1200 px; all but the title lies
  // below the drawing.
  const std::regex text_element("<text x=\"([0-9.]+)\" y=\"([0-9.]+)\"[^>]*>([^<]*)</text>");
  size_t lines = 0;
  bool names_shown = false;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), text_element); it != std::sregex_iterator(); ++it) {
    std::string t = std::regex_replace((*it)[3].str(), std::regex("&[a-z]+;"), "&");
    size_t chars = 0;
    for (char ch : t) chars += (static_cast<unsigned char>(ch) & 0xC0) != 0x80;
    INFO(t);
    CHECK(std::stod((*it)[1]) + 9.0 * double(chars) <= 1200);
    if (lines++ > 0) CHECK(std::stod((*it)[2]) > drawing_bottom);
    names_shown |= t.find("long name.nc") != std::string::npos;
  }
  CHECK(lines >= 6);
  CHECK(names_shown);  // a long path keeps its file name
  CHECK(svg.find("DIFFERENT: ") != std::string::npos);
}

TEST_CASE("the SVG plot renders in headless Chromium: not blank, legend and worst place shown", "[diff][plot]") {
  if (std::system("command -v chromium > /dev/null 2>&1") != 0) {
    WARN("chromium is not installed (Debian package chromium): skipped");
    return;
  }
  auto dir = test::temp_dir("plot");
  // A circle as 360 lines, and a copy with one vertex pushed out.
  std::string a = "G21 G90\nG0 X10 Y0 Z0\n", b = a;
  for (int k = 1; k <= 360; ++k) {
    double t = 2 * kPi * k / 360, r = k == 90 ? 10.02 : 10.0;
    a += fmt::format("G1 X{:.4f} Y{:.4f} F300\n", 10 * std::cos(t), 10 * std::sin(t));
    b += fmt::format("G1 X{:.4f} Y{:.4f} F300\n", r * std::cos(t), r * std::sin(t));
  }
  test::write_file(dir / "a.nc", a);
  test::write_file(dir / "b.nc", b);
  auto c = test::run_arcpress(fmt::format("diff {0}/a.nc {0}/b.nc --plot {0}/plot.svg", dir.string()));
  CHECK(c.exit_code == 1);
  std::string svg = test::read_file(dir / "plot.svg");
  CHECK(svg.find("id=\"legend\"") != std::string::npos);
  CHECK(svg.find("worst 0.020000 mm (ringed): ") != std::string::npos);
  // A blank page of the same size, to compare the screenshots with.
  test::write_file(dir / "blank.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"1200\" height=\"1210\">"
                                      "<rect width=\"100%\" height=\"100%\" fill=\"white\"/></svg>\n");
  auto shot = [&](const std::string& name) {
    std::string cmd = fmt::format(
        "cd {0} && timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
        "--disable-background-networking --disable-component-update --disable-sync --user-data-dir={0}/profile "
        "--window-size=1200,1210 --screenshot={0}/{1}.png file://{0}/{1}.svg > {0}/chromium.log 2>&1",
        dir.string(), name);
    CHECK(std::system(cmd.c_str()) == 0);
    return std::filesystem::exists(dir / (name + ".png")) ? std::filesystem::file_size(dir / (name + ".png")) : 0;
  };
  auto plot_png = shot("plot"), blank_png = shot("blank");
  INFO(test::read_file(dir / "chromium.log"));
  REQUIRE(blank_png > 0);
  // Drawn paths, text and the legend's gradient compress far worse than an empty page.
  CHECK(plot_png > 5 * blank_png);
}

TEST_CASE("compress checks its own output with the code of arcpress diff: an altered output is refused", "[diff]") {
  // A quarter circle of short moves between a spindle start and a comment.
  std::string t = "G21 G90 G17\nG0 X10 Y0 Z0\nM3 S1000\nG1 F300\n";
  for (int k = 1; k <= 30; ++k)
    t += fmt::format("X{:.4f} Y{:.4f}\n", 10 * std::cos(k * M_PI / 60), 10 * std::sin(k * M_PI / 60));
  t += "(done)\nM5\nM30\n";
  DiagnosticSink sink("q.nc");
  CompressOptions opt;
  CompressResult r = compress("q.nc", t, opt, sink);
  REQUIRE(r.verified);
  CHECK(r.within_band());
  CHECK(r.check.max_deviation_mm <= 0.01);
  CHECK(r.check.max_deviation_mm == Approx(r.comparison.max_deviation_mm).margin(r.check.arc_chord_mm));

  Program prog = lex("q.nc", t, sink);
  Interpretation in = interpret(prog, sink);
  auto verified = [&](std::string output) {
    CompressResult v = r;
    v.output = std::move(output);
    verify_output(prog, in, opt, v);
    return v;
  };
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string o = r.output;
    size_t at = o.find(from);
    REQUIRE(at != std::string::npos);
    return o.replace(at, from.size(), to);
  };
  CHECK(verified(r.output).within_band());
  // The arc's end moved 0.02 mm: outside the band. Moved 0.05 mm, off its circle by more
  // than the controller's radius check: no arc it runs, so nothing to pass.
  CompressResult moved = verified(replaced("Y10.0000 ", "Y10.0200 "));
  CHECK_FALSE(moved.within_band());
  CHECK(moved.check.max_deviation_mm > 0.01);
  CHECK_FALSE(verified(replaced("Y10.0000 ", "Y10.0500 ")).within_band());
  // The path untouched, but the spindle turns the other way, a comment is lost, the feed changed.
  CompressResult m4 = verified(replaced("M3", "M4"));
  CHECK(m4.check.max_deviation_mm <= 0.01);
  CHECK_FALSE(m4.within_band());
  CompressResult no_comment = verified(replaced("(done)\n", ""));
  CHECK_FALSE(no_comment.within_band());
  CompressResult slower = verified(replaced("F300", "F200"));
  CHECK_FALSE(slower.within_band());
}

TEST_CASE("compression checks its feed move by move, so a path no wider than its band may change feed",
          "[verify][feed]") {
  // The whole path lies within 0.05 mm of itself: pairing the output with the input by place
  // alone, as `arcpress diff` must, can take the stretch at F1000 for the one at F1100.
  // compress() knows which input moves each output move stands for and compares those.
  std::string t = "G21 G90 G18\nG0 X0 Y0 Z0\nG1 F1000\n";
  for (const char* xyz : {"X0.0315 Y-0.0001 Z0.0001", "X0.0330 Y0.0001 Z0.0001", "X0.0475 Y0.0024 Z0.0002",
                          "X0.0540 Y0.0034 Z0.0002", "X0.0598 Y0.0043 Z0.0003", "X0.0612 Y0.0045 Z0.0003"})
    t += fmt::format("G1 {}\n", xyz);
  t += "G1 F1100\n";
  for (const char* xyz : {"X0.0749 Y0.0099 Z0.0001", "X0.0814 Y0.0129 Z0.0001", "X0.0830 Y0.0136 Z0.0002",
                          "X0.0843 Y0.0143 Z0.0002", "X0.0857 Y0.0149 Z0.0002", "X0.0870 Y0.0156 Z0.0002",
                          "X0.0884 Y0.0162 Z0.0002", "X0.0897 Y0.0169 Z0.0002"})
    t += fmt::format("G1 {}\n", xyz);
  t += "M2\n";
  DiagnosticSink sink("f.nc");
  CompressOptions opt;
  opt.fit.tolerance_mm = 0.05;
  opt.fit.min_radius_mm = 0;
  CompressResult r = compress("f.nc", t, opt, sink);
  REQUIRE(r.verified);
  INFO(r.output << r.comparison.mismatch);
  CHECK(r.within_band());
  CHECK(r.stats.lines_out + r.stats.arcs_out < 14);
  // ... and a feed that did change is still caught, move by move.
  std::string slower = r.output;
  slower.replace(slower.find("F1100"), 5, "F1050");
  Program prog = lex("f.nc", t, sink);
  Interpretation in = interpret(prog, sink);
  CompressResult v = r;
  v.output = slower;
  verify_output(prog, in, opt, v);
  CHECK_FALSE(v.within_band());
}

// Programs that never write an axis (2-D laser, plasma and router programs never write Z;
// lathes never write Y) are compared like any other: an axis that is not moved stays where
// it is, and nothing the diff could not place is ever passed.

TEST_CASE("a 2-D program's arc and its chord differ by the arc's sagitta", "[diff][2d]") {
  // A quarter turn of radius 10 mm: sagitta 10 (1 - cos 45°) = 2.928932 mm.
  const std::string arc = "G21 G90\nG0 X10 Y0\nG2 X0 Y-10 I-10 J0 F100\nM2\n";
  const std::string chord = "G21 G90\nG0 X10 Y0\nG1 X0 Y-10 F100\nM2\n";
  ProgramDiff d = diff_of(arc, chord);
  CHECK(d.compared_all());
  CHECK(d.a.feed_moves == 1);
  CHECK(d.b.feed_moves == 1);
  CHECK(d.max_deviation_mm == Approx(10 * (1 - std::cos(kPi / 4))).margin(d.arc_chord_mm));
  CHECK(d.verdict(0.01) == ProgramDiff::Verdict::Different);
}

TEST_CASE("a 2-D program with one vertex moved 0.1 mm differs by that much at that line", "[diff][2d]") {
  auto contour = [](double moved) {
    std::string t = "G21 G90\nG0 X0 Y0\nM3 S100\n";
    for (int k = 1; k <= 20; ++k) t += fmt::format("G1 X{} Y{:.4f} F600\n", k, k == 12 ? moved : 0.0);
    return t + "M5\nM2\n";
  };
  ProgramDiff d = diff_of(contour(0), contour(0.1));
  CHECK(d.max_deviation_mm == Approx(0.1).margin(1e-9));
  REQUIRE_FALSE(d.worst.empty());
  CHECK(d.worst[0].line_b == 15);  // "G1 X12 Y0.1000"
  CHECK(d.verdict(0.01) == ProgramDiff::Verdict::Different);
  CHECK(d.verdict(0.11) == ProgramDiff::Verdict::Same);
}

TEST_CASE("after homing in the middle, the moves until the position is known again are compared by their end "
          "points, never as if from zero", "[diff][unknown]") {
  auto program = [](double after_home_x) {
    return fmt::format("G21 G90\nG0 X0 Y0 Z1\nG1 Z0 F300\nG1 X10\nG1 X10 Y10\nG28\n"
                       "G1 X{} Y5 F300\nG1 Z-1\nG1 X20 Y20\nG1 X25\nM2\n", after_home_x);
  };
  ProgramDiff same = diff_of(program(5), program(5));
  // From home: "G1 X5 Y5" (X and Y), "G1 Z-1" (Z); the two after them are placed.
  CHECK(same.a.entry_moves == 2);
  CHECK(same.a.first_entry_line == 7);
  CHECK(same.a.entry_reason == "position unknown after homing or bed probing (G28/G29/G30) at line 6");
  CHECK(same.a.feed_moves == 5);
  CHECK(same.compared_all());
  CHECK(same.verdict(0.01) == ProgramDiff::Verdict::Same);
  // The first move after homing ends 0.5 mm away: found at its line.
  ProgramDiff moved = diff_of(program(5), program(5.5));
  CHECK(moved.max_entry_mm == Approx(0.5));
  CHECK(moved.worst_entry.line_a == 7);
  CHECK(moved.verdict(0.01) == ProgramDiff::Verdict::Different);
}

TEST_CASE("feed moves whose end cannot be placed make the verdict incomplete, never same", "[diff][unknown]") {
  const std::string a = "G21 G90\nG0 X0 Y0 Z0\nG1 X[#1] F100\nG1 X5 Y1\nM2\n";
  const std::string b = "G21 G90\nG0 X0 Y0 Z0\nG1 X[#1] F100\nG1 X5 Y1\nM2\n";
  ProgramDiff d = diff_of(a, b);
  CHECK(d.a.unplaced_feed_moves == 1);  // X[#1]; "G1 X5 Y1" starts from it but ends known
  CHECK(d.a.first_unplaced_line == 3);
  CHECK(d.a.unplaced_reason == "position unknown after an expression at line 3");
  CHECK_FALSE(d.compared_all());
  CHECK_FALSE(d.same(0.01));
  CHECK(d.verdict(0.01) == ProgramDiff::Verdict::Incomplete);
  // A difference in what was compared still says different.
  ProgramDiff e = diff_of(a, "G21 G90\nG0 X0 Y0 Z0\nG1 X[#1] F100\nG1 X5 Y2\nM2\n");
  CHECK(e.verdict(0.01) == ProgramDiff::Verdict::Different);
}

TEST_CASE("the laser power (S) along the path is compared", "[diff][laser]") {
  auto contour = [](int power) {
    std::string t = "G21 G90\nG0 X0 Y0\nM4 S0\n";
    for (int k = 1; k <= 10; ++k) t += fmt::format("G1 X{} Y0 F1000 S{}\n", k, k <= 5 ? 300 : power);
    return t + "M5\nM2\n";
  };
  CHECK(diff_of(contour(300), contour(300)).same(0.01));
  ProgramDiff d = diff_of(contour(300), contour(400));
  REQUIRE(d.findings.size() == 1);
  CHECK(d.findings[0].find("S (spindle speed or laser power) differs") != std::string::npos);
  CHECK(d.verdict(0.01) == ProgramDiff::Verdict::Different);
}

TEST_CASE("golden: Klipper moves a half circle of radius 3 as 9 chords of 20 degrees, the last ending at the arc's end",
          "[verify][executed]") {
  DiagnosticSink sink;
  Program p = lex("k.gcode", "G21 G90 G17\nG0 X3 Y0\nG3 X-3 Y0 I-3 J0 E2 F600\n", sink);
  Interpretation in = interpret(p, sink);
  ArcSegmentation klipper;
  klipper.rule = ArcSegmentation::Rule::Klipper;
  klipper.max_segment_mm = 1.0;
  const Interpretation ex = executed_path(in, klipper);
  REQUIRE(ex.moves.size() == 1 + 9);
  for (size_t k = 1; k <= 9; ++k) {
    INFO("chord " << k);
    const Move& m = ex.moves[k];
    CHECK(m.kind == MoveKind::Line);
    CHECK(m.block == in.moves[1].block);
    CHECK(m.to[kX] == Approx(3 * std::cos(k * M_PI / 9)).margin(1e-12));
    CHECK(m.to[kY] == Approx(3 * std::sin(k * M_PI / 9)).margin(1e-12));
    CHECK(m.to[kE] == Approx(2.0 * k / 9).margin(1e-12));  // E carried evenly
  }
  CHECK(ex.move_of_block[2] == 9);
  // A controller that moves on the circle keeps the arc.
  CHECK(executed_path(in, ArcSegmentation{}).moves.size() == 2);
}

TEST_CASE("a path traced again measures as it does traced once, and the worst place is on its first trace",
          "[diff]") {
  // A circle as 36 moves, against a copy with one vertex pushed out, traced 1 and 40 times:
  // the index keeps one of each repeated segment, which must change nothing measured.
  auto laps = [](int n, double pushed_mm, double radius_mm = 10) {
    std::string t = fmt::format("G21 G90\nG0 X{} Y0 Z0\nG1 F600\n", radius_mm);
    for (int lap = 0; lap < n; ++lap)
      for (int k = 1; k <= 36; ++k) {
        const double a = 2 * kPi * k / 36, r = k == 9 ? radius_mm + pushed_mm : radius_mm;
        t += fmt::format("G1 X{:.4f} Y{:.4f}\n", r * std::cos(a), r * std::sin(a));
      }
    return t + "M2\n";
  };
  const ProgramDiff once = diff_of(laps(1, 0), laps(1, 0.004));
  const ProgramDiff many = diff_of(laps(40, 0), laps(40, 0.004));
  REQUIRE(once.max_deviation_mm > 0.003);
  CHECK(many.max_deviation_mm == Approx(once.max_deviation_mm).epsilon(1e-9));
  REQUIRE_FALSE(many.worst.empty());
  CHECK(many.worst.front().line_b == once.worst.front().line_b);  // ties go to the first trace
  // The same with the output's arcs: a circle of arcs traced many times against its moves.
  DiagnosticSink sink;
  CompressOptions copt;
  const std::string input = laps(40, 0, 1);
  const CompressResult r = compress("laps.nc", input, copt, sink);
  REQUIRE(r.stats.arcs_out > 0);
  const ProgramDiff arcs = diff_of(input, r.output);
  const ProgramDiff arcs_once = diff_of(laps(1, 0, 1), compress("lap.nc", laps(1, 0, 1), copt, sink).output);
  CHECK(arcs.same(0.01));
  CHECK(arcs.max_deviation_mm == Approx(arcs_once.max_deviation_mm).margin(1e-6));
}

namespace {

/// A circle of 400 moves, radius 10 mm, at X = 1e12 mm: too far from the origin to measure.
std::string circle_at_1e12() {
  std::string t = "G21 G90\nG0 X1000000000000 Y0 Z0\nG1 F600\n";
  for (int k = 1; k <= 400; ++k)
    t += fmt::format("G1 X{:.4f} Y{:.4f}\n", 1e12 + 10 * std::cos(2 * kPi * k / 400) - 10,
                     10 * std::sin(2 * kPi * k / 400));
  return t;
}

/// `n` arcs of radius 1e15 mm, each over a 0.05 mm chord, turning either way.
std::string huge_radius_arcs(int n) {
  std::string t = "G21 G90\nG0 X0 Y0 Z0\nG1 F100\n";
  for (int k = 1; k <= n; ++k) t += fmt::format("G{} X{:.3f} Y0 R1000000000000000\n", 2 + k % 2, 0.05 * k);
  return t;
}

}  // namespace

TEST_CASE("a program compared with itself is the same in every dialect, whatever its numbers", "[diff][extreme]") {
  const std::string far_circle = circle_at_1e12();
  const std::string huge_arcs = huge_radius_arcs(200);
  const std::vector<std::string> programs = {
      // A minor arc of radius 1e15 over a chord of 136 mm: next to its chord, no full circle.
      "G0 X33.7363 Y136.29\nG3 Y0 R1000000000000000 F100\n",
      // Coordinates near -1e15, too far to measure within any band: the same moves both sides.
      "G21 G90\nG0 X-1000000000000000 Y-1000000000000000\nG1 X-999999999999999 Y-1000000000000000 F100\n"
      "G1 X-999999999999998 Y-999999999999999\n",
      // A major arc of radius 1e15 (R negative): a circle of 6.3e15 mm, too big to follow.
      "G21 G90\nG0 X0 Y0\nG2 X0.05 Y0 R-1000000000000000 F100\n",
      far_circle, huge_arcs};
  const std::vector<Dialect> dialects = list_dialects({ARCPRESS_SOURCE_DIR "/dialects"});
  REQUIRE(dialects.size() >= 17);
  for (const Dialect& d : dialects) {
    for (const std::string& p : programs) {
      INFO(d.name << ":\n" << p.substr(0, 200));
      DiffOptions opt;
      const ProgramDiff r = test::diff_texts(p, p, opt, d);
      CHECK(r.verdict(opt.tolerance_mm) == ProgramDiff::Verdict::Same);
      CHECK(r.max_deviation_mm == 0);
    }
  }
}

TEST_CASE("text written back as it was passes the check, and moves too far to check are not fitted", "[diff][extreme]") {
  const std::string far_circle = circle_at_1e12();
  const std::string huge_arcs = huge_radius_arcs(2000);
  for (const auto method : {FitOptions::Method::Arcs, FitOptions::Method::Keep})
    for (const std::string& p : {std::string("G0 X33.7363 Y136.29\nG3 Y0 R1000000000000000 F100\n"), huge_arcs,
                                 far_circle}) {
      INFO(p.substr(0, 120));
      DiagnosticSink sink;
      CompressOptions opt;
      opt.fit.method = method;
      opt.header = false;
      const CompressResult r = compress("x.nc", p, opt, sink);
      CHECK(r.ok);
      CHECK(r.within_band());
      CHECK(r.output == p);
      CHECK(r.check.compared_all());
    }
  DiagnosticSink sink;
  const CompressResult r = compress("far.nc", far_circle, CompressOptions{}, sink);
  REQUIRE(r.not_fitted.size() == 1);
  CHECK(r.not_fitted.front().why == Unfit::FarFromOrigin);
  CHECK(r.not_fitted.front().moves == 400);
}

TEST_CASE("a rotary or extra axis is compared along the path: programs that differ only in it are different", "[diff][axes]") {
  // A straight cut along X while A turns by 3 degrees a millimetre (a 4th-axis wrap), then a
  // rapid that turns B.
  auto wrap = [](double a_at_5, double b_after) {
    std::string t = "G21 G90\nG0 X0 Y0 Z1 A0 B0\nG1 Z0 F300\n";
    for (int k = 1; k <= 10; ++k) t += fmt::format("G1 X{} A{:.3f}\n", k, k == 5 ? a_at_5 : 3.0 * k);
    return t + fmt::format("G0 Z5 B{}\nM2\n", b_after);
  };
  const ProgramDiff same = diff_of(wrap(15, 90), wrap(15, 90));
  CHECK(same.extra_axes_compared);
  CHECK(same.max_extra_axis == 0.0);
  CHECK(same.same(0.01));
  SECTION("A off by 2 degrees at one vertex: found there, by the feed's pairing, though the XYZ path is the same") {
    const ProgramDiff d = diff_of(wrap(15, 90), wrap(17, 90));
    CHECK(d.max_deviation_mm == 0.0);
    CHECK(d.extra_axis == kA);
    CHECK(d.max_extra_axis > 0.9);  // at the middle of a move next to it: half of 2 degrees
    CHECK(d.max_extra_axis <= 2.0);
    CHECK((d.worst_extra_axis.line_b == 8 || d.worst_extra_axis.line_b == 9));  // "G1 X5 A17.000" or the move after
    CHECK(d.verdict(0.01) == ProgramDiff::Verdict::Different);
    CHECK(d.same(1.0));  // a band of a degree lets it pass
  }
  SECTION("A left out of the cut altogether") {
    std::string flat = "G21 G90\nG0 X0 Y0 Z1 A0 B0\nG1 Z0 F300\n";
    for (int k = 1; k <= 10; ++k) flat += fmt::format("G1 X{}\n", k);
    flat += "G0 Z5 B90\nM2\n";
    const ProgramDiff d = diff_of(wrap(15, 90), flat);
    CHECK(d.max_deviation_mm == 0.0);
    CHECK(d.max_extra_axis == 30.0);  // where the rapid after the cut ends, A at 30 against 0
    CHECK_FALSE(d.same(0.01));
  }
  SECTION("B at the rapid's end") {
    const ProgramDiff d = diff_of(wrap(15, 90), wrap(15, 45));
    CHECK(d.max_rapid_mm == 0.0);
    CHECK(d.extra_axis == kB);
    CHECK(d.max_extra_axis == 45.0);
    CHECK(d.worst_extra_axis.line_b == 14);
    CHECK_FALSE(d.same(0.01));
  }
  SECTION("a program where no extra axis moves compares none") {
    CHECK_FALSE(diff_of(zigzag(), zigzag()).extra_axes_compared);
  }
}
