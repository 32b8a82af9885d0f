// SPDX-License-Identifier: GPL-3.0-or-later
// Xu 2021's test curves (Table 2), sampled as the paper does, fitted at three tolerances:
// segments out, measured deviation, largest tangent change at smooth joints, time per curve.
// Then contours of the kind CAM writes, against the lines and arcs that drew them, smooth 3-D
// finishing passes with each method's time, and the fitter's throughput on the corpus runs.
// Figures only; nothing here is a test.
// Usage: bench_curves [REPEATS] [--corpus]   (--corpus: the throughput on the corpus alone, and
// what a smaller search would save there)
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <random>
#include <string_view>
#include <thread>
#include <vector>

#include "corpus_files.hpp"
#include "timed_compress.hpp"
#include "arcpress/api/arcpress.hpp"
#include "arcpress/fit/count_bound.hpp"

namespace fs = std::filesystem;
using namespace arcpress;

namespace {

struct Curve {
  const char* name;
  std::function<Vec2(double)> f;
  double t0, t1;
  int samples;
  int xu_arcs;  // Xu 2021, Table 2
};

Vec2 bezier(const Vec2& p0, const Vec2& p1, const Vec2& p2, double t) {
  return (1 - t) * (1 - t) * p0 + 2 * t * (1 - t) * p1 + t * t * p2;
}

/// The curve's samples as the program prints them (4 decimals).
std::vector<Vec2> samples(const Curve& c) {
  std::vector<Vec2> out;
  for (int i = 0; i < c.samples; ++i) {
    Vec2 p = c.f(c.t0 + (c.t1 - c.t0) * i / (c.samples - 1));
    out.emplace_back(std::stod(fmt::format("{:.4f}", p.x())), std::stod(fmt::format("{:.4f}", p.y())));
  }
  return out;
}

/// A program that moves along `pts` (printed to 4 decimals, as samples() reads them).
std::string program(const std::vector<Vec2>& pts) {
  std::string s = "G21 G90 G17\n";
  for (size_t i = 0; i < pts.size(); ++i)
    s += i == 0 ? fmt::format("G0 X{:.4f} Y{:.4f} Z0\nG1 F1000\n", pts[i].x(), pts[i].y())
                : fmt::format("G1 X{:.4f} Y{:.4f}\n", pts[i].x(), pts[i].y());
  return s + "M2\n";
}

/// ∫|dκ/ds|^(1/3) ds of the curve, from 200 000 samples (turning angle per length).
/// The asymptotic count of a G1 arc spline inside a band ε is 0.200·ε^(-1/3) times this
/// (reference/algorithms.md §5): the yardstick under a max-deviation band.
double curvature_rate_integral(const Curve& c) {
  const int n = 200000;
  std::vector<Vec2> p(n);
  for (int i = 0; i < n; ++i) p[i] = c.f(c.t0 + (c.t1 - c.t0) * i / (n - 1));
  std::vector<double> k(n, 0.0), ds(n, 0.0);
  for (int i = 1; i + 1 < n; ++i) {
    Vec2 a = p[i] - p[i - 1], b = p[i + 1] - p[i];
    ds[i] = 0.5 * (a.norm() + b.norm());
    k[i] = ds[i] > 0 ? std::atan2(cross2(a, b), a.dot(b)) / ds[i] : 0;
  }
  double sum = 0;
  for (int i = 2; i + 2 < n; ++i) {
    double span = ds[i - 1] + ds[i + 1];
    if (span > 0) sum += std::cbrt(std::abs(k[i + 1] - k[i - 1]) / span) * ds[i];
  }
  return sum;
}

/// Cubic B-spline with clamped uniform knots over control points `cp`, at t in [0, 1]
/// (de Boor's algorithm).
Vec2 bspline(const std::vector<Vec2>& cp, double t) {
  const int deg = 3, n = int(cp.size());
  const int spans = n - deg;  // knot intervals of non-zero length
  std::vector<double> knots;
  for (int i = 0; i < deg; ++i) knots.push_back(0);
  for (int i = 0; i <= spans; ++i) knots.push_back(double(i) / spans);
  for (int i = 0; i < deg; ++i) knots.push_back(1);
  int k = std::min(deg + int(t * spans), n - 1);  // knots[k] <= t < knots[k + 1]
  std::vector<Vec2> d(cp.begin() + (k - deg), cp.begin() + k + 1);
  for (int r = 1; r <= deg; ++r)
    for (int j = deg; j >= r; --j) {
      int i = j + k - deg;
      double den = knots[i + deg - r + 1] - knots[i];
      double a = den > 0 ? (t - knots[i]) / den : 0;
      d[j] = (1 - a) * d[j - 1] + a * d[j];
    }
  return d[deg];
}

const std::vector<Vec2> kBspline1 = {{0, 0}, {1, 5}, {4, 5}, {6, 1}, {9, -3}, {11, -4}, {12, 5}, {14, 6}, {17, -2}, {20, -2}, {21, 1}};
const std::vector<Vec2> kBspline2 = {{0, 10}, {1, 8},   {4, 7.5}, {5, 10}, {6, 10}, {7, 8.5}, {8, 8.3},
                                     {12, 11}, {12, -1}, {6, 4.3}, {4, 10}, {2, 8},  {1, 7.5}, {0, 0},
                                     {3, 0},  {5, 2.7}, {8, 7},   {10, 7}, {11, 3}, {7.3, -1}, {9.3, -2}};

/// A CAM contour drawn from lines and arcs, sampled into G1 moves: what a CAM system writes
/// when it may not write arcs. `drawn` is how many lines and arcs drew it.
struct Shape {
  const char* name;
  std::vector<Vec2> pts;
  size_t drawn = 0;
  int decimals = 3;

  /// A line to `to` in `moves` moves.
  Shape& line(const Vec2& to, int moves) {
    const Vec2 from = pts.back();
    for (int k = 1; k <= moves; ++k) pts.push_back(from + (to - from) * (double(k) / moves));
    ++drawn;
    return *this;
  }
  /// An arc about `centre` turning by `turn_deg` (> 0 counter-clockwise) in `moves` moves.
  Shape& arc(const Vec2& centre, double turn_deg, int moves) {
    const Vec2 r = pts.back() - centre;
    for (int k = 1; k <= moves; ++k) {
      const double a = deg_to_rad(turn_deg) * k / moves;
      pts.push_back(centre + Vec2(r.x() * std::cos(a) - r.y() * std::sin(a), r.x() * std::sin(a) + r.y() * std::cos(a)));
    }
    ++drawn;
    return *this;
  }
  std::string text() const {
    std::string s = fmt::format("G21 G90 G17\nG0 X{:.{}f} Y{:.{}f} Z0\nG1 F1000\n", pts[0].x(), decimals, pts[0].y(), decimals);
    for (size_t i = 1; i < pts.size(); ++i) s += fmt::format("G1 X{:.{}f} Y{:.{}f}\n", pts[i].x(), decimals, pts[i].y(), decimals);
    return s + "M2\n";
  }
};

/// Contours of the kind CAM writes, for the search's choices beyond Xu's curves.
std::vector<Shape> cam_shapes() {
  std::vector<Shape> out;
  auto rounded = [](const char* name, double w, double h, double r, double step_mm, int fillet_moves, int decimals) {
    Shape s{name, {{r, 0}}};
    s.decimals = decimals;
    auto moves = [&](double len) { return std::max(1, int(std::lround(len / step_mm))); };
    s.line({w - r, 0}, moves(w - 2 * r)).arc({w - r, r}, 90, fillet_moves);
    s.line({w, h - r}, moves(h - 2 * r)).arc({w - r, h - r}, 90, fillet_moves);
    s.line({r, h}, moves(w - 2 * r)).arc({r, h - r}, 90, fillet_moves);
    s.line({0, r}, moves(h - 2 * r)).arc({r, r}, 90, fillet_moves);
    return s;
  };
  out.push_back(rounded("rounded rectangle", 20, 10, 1, 0.2, 16, 3));
  out.push_back(rounded("fine rounded rectangle", 10, 5, 0.5, 0.05, 20, 4));
  Shape slot{"slot", {{0, 0}}};
  slot.line({30, 0}, 60).arc({30, 5}, 180, 40).line({0, 10}, 60).arc({0, 5}, 180, 40);
  out.push_back(slot);
  Shape s_curve{"S-curve", {{-10, 0}}};
  s_curve.line({0, 0}, 20).arc({0, 10}, 90, 50).arc({20, 10}, -90, 50).line({30, 20}, 20);
  out.push_back(s_curve);
  Shape cam{"cam profile", {{20, 0}}};
  cam.arc({0, 0}, 90, 60).arc({0, 15}, 90, 30).arc({15, 15}, 90, 60).arc({15, 0}, 90, 30);
  out.push_back(cam);
  // A pass over a dome clipped to the floor at both ends: a hook of 10° at each clip.
  Shape dome{"dome pass, clipped", {}};
  dome.decimals = 4;
  for (int k = 0; k <= 112; ++k) {
    const double x = -11.2 + 0.2 * k;
    dome.pts.push_back({x, std::max(0.0, std::sqrt(std::max(0.0, 224 - x * x)) - 10)});
  }
  dome.drawn = 3;  // the dome's arc and, at a forced kink each, the two clipped ends
  out.push_back(dome);
  return out;
}

/// Finishing passes over a smooth surface, as 3-D CAM writes them without arcs: 20 raster
/// passes 1 mm apart in Y, each 2 000 moves of 0.05 mm along X, the height following
/// z = 2·sin(x/7)·cos(y/9) + 0.5·sin(x/3.1) (the runs are fitted in the XZ plane, G18). Long
/// smooth stretches of long primitives: where a wider search costs the most for the least.
std::string raster_program() {
  std::string s = "G21 G90 G17\nG0 Z5\nG0 X0 Y0\nG1 Z0 F500\nG1 F1200\n";
  for (int pass = 0; pass < 20; ++pass) {
    const double y = pass;
    s += fmt::format("G1 Y{:.3f}\n", y);
    for (int i = 0; i <= 2000; ++i) {
      const double x = 0.05 * (pass % 2 ? 2000 - i : i);
      s += fmt::format("G1 X{:.3f} Z{:.4f}\n", x, 2 * std::sin(x / 7) * std::cos(y / 9) + 0.5 * std::sin(x / 3.1));
    }
  }
  return s + "G0 Z5\nM2\n";
}

/// A contour drawn at random from `seed`, as CAM writes one: 3 to 12 pieces, each a line of
/// 1-20 mm or an arc of 0.5-30 mm radius (log-uniform) turning 15-170° either way, joined
/// tangentially or, one time in seven, at a corner of 40-120°; lines in moves of at most
/// 0.1, 0.5 or 2 mm, arcs in chords whose middle lies 0.001, 0.002 or 0.005 mm off the
/// circle (and no longer than the lines' moves), printed to 3 or 4 decimals.
Shape random_contour(unsigned seed) {
  std::mt19937 gen(seed);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * (double(gen()) / 4294967296.0); };
  auto pick = [&](std::initializer_list<double> xs) { return *(xs.begin() + gen() % xs.size()); };
  Shape s{"random", {{0, 0}}};
  s.decimals = gen() % 3 == 0 ? 4 : 3;
  const double chord_error = pick({0.001, 0.002, 0.005}), move = pick({0.1, 0.5, 2.0});
  double heading = uniform(0, 2 * kPi);
  bool last_line = false;
  const int pieces = 3 + int(gen() % 10);
  for (int i = 0; i < pieces; ++i) {
    if (i > 0 && gen() % 7 == 0) heading += (gen() % 2 ? 1 : -1) * deg_to_rad(uniform(40, 120));
    const Vec2 at = s.pts.back();
    if (!last_line && gen() % 5 < 2) {
      const double len = uniform(1, 20);
      s.line(at + len * Vec2(std::cos(heading), std::sin(heading)), std::max(1, int(std::ceil(len / move))));
      last_line = true;
      continue;
    }
    const double radius = std::exp(uniform(std::log(0.5), std::log(30.0)));
    const double turn = uniform(15, 170) * (gen() % 2 ? 1 : -1);
    const Vec2 centre = at + radius * (turn > 0 ? 1 : -1) * Vec2(-std::sin(heading), std::cos(heading));
    const double step = std::min(2 * std::acos(1 - chord_error / radius), move / radius);
    s.arc(centre, turn, std::max(1, int(std::ceil(deg_to_rad(std::abs(turn)) / step))));
    heading += deg_to_rad(turn);
    last_line = false;
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const bool corpus_only = argc > 2 && std::string_view(argv[2]) == "--corpus";
  std::vector<Curve> curves = {
      {"bezier1", [](double t) { return bezier({1, 1}, {5, 1}, {1, 2.75}, t); }, 0, 1, 1000, 5},
      {"bezier2", [](double t) { return bezier({0.54, 3.40}, {7.22, 3.61}, {7.39, 3.14}, t); }, 0, 1, 1000, 2},
      {"leaf", [](double t) { return Vec2(30 * t / (1 + t * t * t), 30 * t * t / (1 + t * t * t)); }, 0, 5, 1000, 7},
      {"bspline1", [](double t) { return bspline(kBspline1, t); }, 0, 1, 1000, 9},
      {"bspline2", [](double t) { return bspline(kBspline2, t); }, 0, 1, 1000, 11},
      {"y=x^3", [](double x) { return Vec2(x, x * x * x); }, -2, 2, 2000, 8},
      {"plum",
       [](double t) {
         double r = 10 - 9 * std::pow(std::sin(2.5 * t), 2);
         return Vec2(r * std::cos(t), r * std::sin(t));
       },
       0, 1.5 * kPi, 4700, 30},
      {"loop", [](double t) { return Vec2(10 * (t * t * t - t) / (t * t + 1), 10 * (t * t - 1) / (t * t + 1)); }, -2, 2,
       1000, 7},
  };
  if (!corpus_only) {
    fmt::print("Xu 2021 test curves, --min-radius 0 (B-splines: cubic, clamped uniform knots, the paper's control points)\n");
    fmt::print("Xu's ε bounds a mean square; 'estimate' is the asymptotic G1 count under a max-deviation band;\n");
    fmt::print("bounds: the fewest lines and arcs joined at vertices with every vertex in the band;\n");
    fmt::print("'C0' tangent or not (at 0.01 mm only, where the paper's counts are compared: seconds on plum),\n");
    fmt::print("'G1' tangent within the G1 angle and at most half a turn each (no fit joined so has fewer),\n");
    fmt::print("'fitted' the same in the band and angle the fitter works to (the rest kept for printed centres)\n");
    fmt::print("stream, lowe (seed methods, tangent only where their adjustment reaches): segments/forced kinks\n");
    fmt::print("{:<9} {:>6} {:>8} {:>6} {:>6} {:>6} {:>9} {:>5} {:>5} {:>6} {:>10} {:>10} {:>8} {:>8} {:>7} {:>9} {:>7} {:>8} {:>8}\n", "curve",
               "points", "tol mm", "segs", "arcs", "Xu", "estimate", "C0", "G1", "fitted", "max dev", "max kink", "forced", "ms", "global",
               "global ms", "greedy", "stream", "lowe");
    for (const Curve& c : curves) {
      const std::vector<Vec2> pts = samples(c);
      const std::string text = program(pts);
      const double rate_integral = curvature_rate_integral(c);
      for (double tol : {0.01, 0.005, 0.001}) {
        CompressOptions opt;
        opt.fit.tolerance_mm = tol;
        opt.fit.min_radius_mm = 0;  // Xu's problem has no smallest radius (plum's tips are 0.009 mm)
        DiagnosticSink sink;
        CompressResult r = compress(c.name, text, opt, sink);  // with verification, for the figures
        opt.verify = false;
        const double best = 1000 * timed_compress(c.name, text, opt, repeats).first;  // ms
        opt.fit.method = FitOptions::Method::Global;  // the wider search, and its time
        const auto [global_s, gl] = timed_compress(c.name, text, opt, repeats);
        const double global_ms = 1000 * global_s;
        opt.fit.method = FitOptions::Method::Greedy;  // segments the one-step method needs, for comparison
        DiagnosticSink s3;
        CompressResult g = compress(c.name, text, opt, s3);
        opt.fit.method = FitOptions::Method::Stream;  // ... and the seeds' methods, whose joints may break
        DiagnosticSink s4;
        CompressResult st = compress(c.name, text, opt, s4);
        opt.fit.method = FitOptions::Method::Lowe;
        DiagnosticSink s5;
        CompressResult lw = compress(c.name, text, opt, s5);
        auto seed = [](const CompressResult& x) {
          return fmt::format("{}/{}", x.stats.lines_out + x.stats.arcs_out, x.forced_kinks);
        };
        fmt::print("{:<9} {:>6} {:>8.3f} {:>6} {:>6} {:>6} {:>9.1f} {:>5} {:>5} {:>6} {:>10.6f} {:>9.3f}° {:>8} {:>8.2f} {:>7} {:>9.2f} {:>7} {:>8} {:>8}\n", c.name,
                   c.samples, tol, r.stats.lines_out + r.stats.arcs_out, r.stats.arcs_out,
                   tol == 0.01 ? std::to_string(c.xu_arcs) : "", 0.200 * std::cbrt(1 / tol) * rate_integral, tol == 0.01 ? std::to_string(min_primitive_count(pts, tol)) : "", min_g1_primitive_count(pts, tol, opt.fit.g1_angle_deg),
                   min_g1_primitive_count_as_fitted(pts, fit_options_for(opt.fit, opt.dialect, Frame{}, Plane::XY)),
                   r.comparison.max_deviation_mm,
                   r.comparison.max_smooth_kink_deg, r.forced_kinks, best, gl.stats.lines_out + gl.stats.arcs_out,
                   global_ms, g.stats.lines_out + g.stats.arcs_out,
                   seed(st), seed(lw));
      }
    }

    // CAM contours: blocks (and forced kinks) per method against the lines and arcs that drew them.
    fmt::print("\nCAM contours in G1 moves at 0.01 mm: blocks/forced kinks; 'drawn': the lines and arcs that drew them\n");
    fmt::print("{:<24} {:>6} {:>6} {:>9} {:>9} {:>9} {:>10}\n", "contour", "moves", "drawn", "arcs", "global", "greedy",
               "max dev");
    for (const Shape& shape : cam_shapes()) {
      auto run = [&](FitOptions::Method m) {
        CompressOptions opt;
        opt.fit.method = m;
        DiagnosticSink sink;
        return compress(shape.name, shape.text(), opt, sink);
      };
      const CompressResult d = run(FitOptions::Method::Arcs), gl = run(FitOptions::Method::Global),
                           gr = run(FitOptions::Method::Greedy);
      auto cell = [](const CompressResult& r) { return fmt::format("{}/{}", r.stats.lines_out + r.stats.arcs_out, r.forced_kinks); };
      fmt::print("{:<24} {:>6} {:>6} {:>9} {:>9} {:>9} {:>10.6f}\n", shape.name, shape.pts.size() - 1, shape.drawn, cell(d),
                 cell(gl), cell(gr), d.comparison.max_deviation_mm);
    }

    // Random CAM contours: how often, and by how much, each method needs more blocks than drew
    // the contour (two arcs the same way with close radii may also come out as one).
    {
      const unsigned count = 200;
      struct Sum {
        size_t blocks = 0, over = 0, most = 0, kinks = 0;
      };
      std::array<Sum, 3> sums;
      size_t moves = 0, drawn = 0;
      double worst_dev = 0;
      for (unsigned seed = 1; seed <= count; ++seed) {
        const Shape shape = random_contour(seed);
        moves += shape.pts.size() - 1;
        drawn += shape.drawn;
        const std::array methods{FitOptions::Method::Arcs, FitOptions::Method::Global, FitOptions::Method::Greedy};
        for (size_t m = 0; m < methods.size(); ++m) {
          CompressOptions opt;
          opt.fit.method = methods[m];
          DiagnosticSink sink;
          const CompressResult r = compress("random contour", shape.text(), opt, sink);
          const size_t blocks = r.stats.lines_out + r.stats.arcs_out;
          sums[m].blocks += blocks;
          sums[m].kinks += r.forced_kinks;
          sums[m].over += blocks > shape.drawn;
          sums[m].most = std::max(sums[m].most, blocks > shape.drawn ? blocks - shape.drawn : 0);
          worst_dev = std::max(worst_dev, r.comparison.max_deviation_mm);
        }
      }
      auto cell = [](const Sum& x) { return fmt::format("{}/{}", x.blocks, x.kinks); };
      auto over = [&](const Sum& x) { return fmt::format("{} (+{})", x.over, x.most); };
      fmt::print("{:<24} {:>6} {:>6} {:>9} {:>9} {:>9} {:>10.6f}\n", fmt::format("{} random contours", count), moves,
                 drawn, cell(sums[0]), cell(sums[1]), cell(sums[2]), worst_dev);
      fmt::print("{:<24} {:>6} {:>6} {:>9} {:>9} {:>9}\n", "  contours over drawn", "", "", over(sums[0]), over(sums[1]),
                 over(sums[2]));
    }

    // Smooth 3-D finishing passes: blocks, forced kinks and time per method.
    // (At least the best of 3 even when the curves are timed once: a run takes a second at most,
    // and one run on a shared machine can be off by half.)
    fmt::print("\nSmooth 3-D finishing passes (20 x 2 000 moves, XZ runs): blocks/forced kinks, and ms on one thread"
               " (best of {})\n", std::max(repeats, 3));
    fmt::print("{:<8} {:>7} {:>9} {:>8} {:>9} {:>8} {:>9} {:>8}\n", "tol mm", "moves", "arcs", "ms", "global", "ms", "greedy",
               "ms");
    const std::string raster = raster_program();
    for (double tol : {0.01, 0.005}) {
      std::string row = fmt::format("{:<8.3f}", tol);
      for (auto m : {FitOptions::Method::Arcs, FitOptions::Method::Global, FitOptions::Method::Greedy}) {
        CompressOptions opt;
        opt.fit.tolerance_mm = tol;
        opt.fit.method = m;
        opt.threads = 1;
        opt.verify = false;
        const auto [seconds, r] = timed_compress("raster", raster, opt, std::max(repeats, 3));
        if (m == FitOptions::Method::Arcs) row += fmt::format(" {:>7}", r.stats.moves_in);
        row += fmt::format(" {:>9} {:>8.1f}", fmt::format("{}/{}", r.stats.lines_out + r.stats.arcs_out, r.forced_kinks),
                           1000 * seconds);
      }
      fmt::print("{}\n", row);
    }
  }

  // Throughput on the corpus: whole pipeline without verification, per input point of the runs.
  const std::vector<fs::path> files = corpus_files();
  // Whole pipeline without verification, best of the repeats, per method, on one thread and
  // on every hardware thread; the fitter's share is the time over the pipeline that keeps
  // every G1.
  struct Tally {
    const char* name;
    FitOptions::Method method;
    size_t points = 0, blocks = 0;
    double seconds = 0, seconds_all = 0;
  };
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  std::vector<Tally> tallies = {{"keep", FitOptions::Method::Keep},
                                {"arcs", FitOptions::Method::Arcs},
                                {"global", FitOptions::Method::Global},
                                {"greedy", FitOptions::Method::Greedy},
                                {"stream", FitOptions::Method::Stream},
                                {"lowe", FitOptions::Method::Lowe}};
  // The default's search made smaller, on one thread: what each step down saves in time and
  // what it costs in blocks.
  struct Search {
    const char* name;
    std::function<void(FitOptions&)> narrow;
    size_t blocks = 0;
    double seconds = 0;
  };
  std::vector<Search> searches = {
      {"the default", [](FitOptions&) {}},
      {"beam width 6", [](FitOptions& o) { o.beam_width = 6; }},
      {"beam width 4", [](FitOptions& o) { o.beam_width = 4; }},
      {"beam width 2", [](FitOptions& o) { o.beam_width = 2; }},
      {"branch 2", [](FitOptions& o) { o.beam_branch = 2; }},
      {"no merging", [](FitOptions& o) { o.merge = false; }},
      {"width 4, branch 2, no merging", [](FitOptions& o) { o.beam_width = 4; o.beam_branch = 2; o.merge = false; }},
      {"no search at the count first", [](FitOptions& o) { o.bound_search = false; }},
  };
  for (const auto& f : files) {
    const std::string text = file_text(f);
    for (Tally& t : tallies) {
      for (unsigned threads : {1u, hw}) {
        CompressOptions opt;
        opt.verify = false;
        opt.fit.method = t.method;
        opt.threads = threads;
        const auto [best, r] = timed_compress(f, text, opt, repeats);
        if (threads == 1) {
          t.points += r.stats.moves_in;
          t.blocks += r.stats.lines_out + r.stats.arcs_out;
          t.seconds += best;
        } else {
          t.seconds_all += best;
        }
      }
    }
    for (Search& v : searches) {
      CompressOptions opt;
      opt.verify = false;
      opt.threads = 1;
      v.narrow(opt.fit);
      const auto [best, r] = timed_compress(f, text, opt, repeats);
      v.blocks += r.stats.lines_out + r.stats.arcs_out;
      v.seconds += best;
    }
  }
  if (tallies[0].points > 0) {
    fmt::print("\ncorpus: {} run points in {} files (default options, rs274)\n", tallies[0].points, files.size());
    fmt::print("{:<8} {:>12} {:>8} {:>12} {:>12} {:>18} {:>18}\n", "method", "blocks out", "ratio", "pipeline s",
               "fitting s", "fitter M points/s", fmt::format("... {} threads", hw));
    for (const Tally& t : tallies) {
      const bool keep = t.method == FitOptions::Method::Keep;
      const double fit_s = std::max(t.seconds - tallies[0].seconds, 1e-9);
      const double fit_all_s = std::max(t.seconds_all - tallies[0].seconds_all, 1e-9);
      auto rate = [&](double s) { return keep ? std::string("-") : fmt::format("{:.2f}", double(t.points) / s / 1e6); };
      fmt::print("{:<8} {:>12} {:>7.1f}% {:>12.3f} {:>12.3f} {:>18} {:>18}\n", t.name, t.blocks,
                 100.0 * double(t.blocks) / double(t.points), t.seconds, keep ? 0.0 : fit_s, rate(fit_s), rate(fit_all_s));
    }
    fmt::print("\nthe default (arcs) with a smaller search, 1 thread: blocks, and fitting time as above\n");
    fmt::print("{:<32} {:>12} {:>14} {:>12} {:>18}\n", "search", "blocks out", "over default", "fitting s",
               "fitter M points/s");
    auto over_default = [&](size_t blocks) {
      const long more = long(blocks) - long(searches[0].blocks);
      return fmt::format("{:+} ({:+.2f}%)", more, 100.0 * double(more) / double(searches[0].blocks));
    };
    for (const Search& v : searches) {
      const double fit_s = std::max(v.seconds - tallies[0].seconds, 1e-9);
      fmt::print("{:<32} {:>12} {:>14} {:>12.3f} {:>18.2f}\n", v.name, v.blocks, over_default(v.blocks), fit_s,
                 double(tallies[0].points) / fit_s / 1e6);
    }
    const auto greedy = std::find_if(tallies.begin(), tallies.end(),
                                     [](const Tally& t) { return t.method == FitOptions::Method::Greedy; });
    fmt::print("{:<32} {:>12} {:>14}   (the table above)\n", "greedy method", greedy->blocks,
               over_default(greedy->blocks));
  }
  return 0;
}
