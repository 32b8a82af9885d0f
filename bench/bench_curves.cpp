// Xu 2021's test curves (Table 2), sampled as the paper does, fitted at three tolerances:
// segments out, measured deviation, largest tangent change at smooth joints, time per curve.
// Then the fitter's throughput on the corpus runs. Figures only; nothing here is a test.
// Usage: bench_curves [REPEATS]
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <vector>

#include "arcpress/api/arcpress.hpp"

namespace fs = std::filesystem;
using clk = std::chrono::steady_clock;
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

std::string program(const Curve& c) {
  std::string s = "G21 G90 G17\n";
  for (int i = 0; i < c.samples; ++i) {
    double t = c.t0 + (c.t1 - c.t0) * i / (c.samples - 1);
    Vec2 p = c.f(t);
    s += i == 0 ? fmt::format("G0 X{:.4f} Y{:.4f} Z0\nG1 F1000\n", p.x(), p.y())
                : fmt::format("G1 X{:.4f} Y{:.4f}\n", p.x(), p.y());
  }
  return s + "M2\n";
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  std::vector<Curve> curves = {
      {"bezier1", [](double t) { return bezier({1, 1}, {5, 1}, {1, 2.75}, t); }, 0, 1, 1000, 5},
      {"bezier2", [](double t) { return bezier({0.54, 3.40}, {7.22, 3.61}, {7.39, 3.14}, t); }, 0, 1, 1000, 2},
      {"leaf", [](double t) { return Vec2(30 * t / (1 + t * t * t), 30 * t * t / (1 + t * t * t)); }, 0, 5, 1000, 7},
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
  fmt::print("Xu 2021 test curves, --min-radius 0 (B-spline 1 and 2 are left out: their control points are only in the paper)\n");
  fmt::print("{:<9} {:>6} {:>8} {:>6} {:>6} {:>6} {:>10} {:>10} {:>8} {:>8}\n", "curve", "points", "tol mm", "segs",
             "arcs", "Xu", "max dev", "max kink", "forced", "ms");
  for (const Curve& c : curves) {
    std::string text = program(c);
    for (double tol : {0.01, 0.005, 0.001}) {
      CompressOptions opt;
      opt.fit.tolerance_mm = tol;
      opt.fit.min_radius_mm = 0;  // Xu's problem has no smallest radius (plum's tips are 0.009 mm)
      DiagnosticSink sink;
      CompressResult r = compress(c.name, text, opt, sink);  // with verification, for the figures
      opt.verify = false;
      double best = 1e9;
      for (int k = 0; k < repeats; ++k) {
        DiagnosticSink s2;
        auto t0 = clk::now();
        CompressResult q = compress(c.name, text, opt, s2);
        best = std::min(best, std::chrono::duration<double, std::milli>(clk::now() - t0).count());
      }
      fmt::print("{:<9} {:>6} {:>8.3f} {:>6} {:>6} {:>6} {:>10.6f} {:>9.3f}° {:>8} {:>8.2f}\n", c.name, c.samples, tol,
                 r.stats.lines_out + r.stats.arcs_out, r.stats.arcs_out, tol == 0.01 ? std::to_string(c.xu_arcs) : "",
                 r.comparison.max_deviation_mm, r.comparison.max_smooth_kink_deg, r.forced_kinks, best);
    }
  }

  // Throughput on the corpus: whole pipeline without verification, per input point of the runs.
  std::vector<fs::path> files;
  if (fs::is_directory(ARCPRESS_CORPUS_DIR))
    for (const auto& e : fs::recursive_directory_iterator(ARCPRESS_CORPUS_DIR))
      if (e.is_regular_file() && e.path().extension() != ".md") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  size_t points = 0;
  double seconds = 0, seconds_keep = 0;
  for (const auto& f : files) {
    std::ifstream in(f, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    double best = 1e9, best_keep = 1e9;
    size_t n = 0;
    for (int k = 0; k < repeats; ++k) {
      for (bool keep : {false, true}) {
        CompressOptions opt;
        opt.verify = false;
        opt.fit.method = keep ? FitOptions::Method::Keep : FitOptions::Method::Arcs;
        DiagnosticSink sink;
        auto t0 = clk::now();
        CompressResult r = compress(f.string(), text, opt, sink);
        double s = std::chrono::duration<double>(clk::now() - t0).count();
        (keep ? best_keep : best) = std::min(keep ? best_keep : best, s);
        n = r.stats.moves_in;
      }
    }
    points += n;
    seconds += best;
    seconds_keep += best_keep;
  }
  if (points > 0) {
    double fit_s = std::max(seconds - seconds_keep, 1e-9);
    fmt::print("\ncorpus: {} run points in {} files; pipeline {:.3f} s, of which fitting {:.3f} s\n", points,
               files.size(), seconds, fit_s);
    fmt::print("fitter throughput: {:.2f} million input points/s (one core)\n", double(points) / fit_s / 1e6);
  }
  return 0;
}
