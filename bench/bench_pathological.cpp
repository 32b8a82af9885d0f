// SPDX-License-Identifier: GPL-3.0-or-later
// Work on small or simple programs that once grew without bound: each case generated at 1x,
// 2x and 4x its size (moves, length, radius or turns), compressed with verification and
// compared with its output by `arcpress diff` on one thread, each run as a child process. Prints seconds and
// peak memory per size and the ratio from one size to the next: time and memory follow the
// number of moves (about 2x per doubling of them, <= 2.3x) and never a length, a radius or
// a number of turns (about 1x when those double). Ratios of runs under 50 ms are noise and
// shown as "-". Exit 1 when a ratio above 2.3 is measured (the case is named).
//   bench_pathological [SCALE]   SCALE multiplies every size (default 1)
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "child_process.hpp"

namespace fs = std::filesystem;
using arcpress::bench::ChildRun;
using arcpress::bench::run_child;

namespace {

struct Case {
  std::string name;
  std::string grows;                             ///< what doubles
  std::function<std::string(double size)> text;  ///< the program at a size
  double size;                                   ///< the 1x size
};

std::string head() { return "G21 G90\nG0 X0 Y0 Z0\nG1 F600\n"; }

std::vector<Case> cases() {
  std::vector<Case> c;
  c.push_back({"one long line", "length", [](double n) { return head() + fmt::format("G1 X{:.0f}\nM2\n", n); }, 1e8});
  c.push_back({"noisy straight line", "moves", [](double n) {
                 std::string t = head();
                 for (int i = 1; i <= int(n); ++i)  // 2000 mm long, +-0.002 mm across
                   t += fmt::format("G1 X{:.4f} Y{:.4f}\n", 2000.0 * i / n, 0.002 * ((i * 7919) % 5 - 2) / 2.0);
                 return t + "M2\n";
               }, 20000});
  c.push_back({"zigzag after a plunge", "moves", [](double n) {
                 std::string t = head() + "G1 Z-1\n";
                 for (int i = 1; i <= int(n); ++i) t += fmt::format("G1 X{:.4f} Y{:.4f}\n", i * 0.001, (i % 2) * 0.001);
                 return t + "M2\n";
               }, 31000});
  c.push_back({"plunge in tiny steps", "moves", [](double n) {
                 // Straight down in steps of 0.1 um: no direction in the plane anywhere.
                 std::string t = head();
                 for (int i = 1; i <= int(n); ++i) t += fmt::format("G1 Z{:.4f}\n", -0.0001 * i);
                 return t + "M2\n";
               }, 40000});
  c.push_back({"circle retraced", "moves", [](double n) {
                 std::string t = head();
                 for (int i = 1; i <= int(n); ++i) {
                   const double a = 2 * M_PI * i / 100;
                   t += fmt::format("G1 X{:.4f} Y{:.4f}\n", 10 * std::cos(a) - 10, 10 * std::sin(a));
                 }
                 return t + "M2\n";
               }, 25000});
  c.push_back({"small circle retraced", "moves", [](double n) {
                 // 36 moves a lap, written as two arcs a lap: the output's pieces all overlap.
                 std::string t = "G21 G90\nG0 X1 Y0 Z0\nG1 F600\n";
                 for (int i = 1; i <= int(n); ++i) {
                   const double a = 2 * M_PI * i / 36;
                   t += fmt::format("G1 X{:.4f} Y{:.4f}\n", std::cos(a), std::sin(a));
                 }
                 return t + "M2\n";
               }, 36000});
  c.push_back({"huge radius arcs", "radius", [](double r) {
                 return head() + fmt::format("G2 X0 Y19 R-{:.0f}\nG3 X1 Y0 R{:.0f}\nG2 X-{:.0f} Y0 I1.74\nM2\n", r, r, r);
               }, 1e8});
  c.push_back({"helix, many turns", "turns", [](double p) {
                 return head() + fmt::format("G3 X0 Y0 Z1e6 I0 J0.5 P{:.0f}\nM2\n", p);
               }, 1000});
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  const double scale = argc > 1 ? std::atof(argv[1]) : 1.0;
  const fs::path dir = fs::temp_directory_path() / fmt::format("arcpress-pathological-{}", ::getpid());
  fs::create_directories(dir);
  constexpr double kMaxRatio = 2.3, kNoiseSeconds = 0.05;
  bool over = false;
  fmt::print("{:<24}{:>8}{:>14}  {:>10}{:>10}{:>8}{:>8}  {:>10}{:>10}{:>8}{:>8}\n", "case", "grows", "size",
             "compress s", "MiB", "t ratio", "m ratio", "diff s", "MiB", "t ratio", "m ratio");
  for (const Case& c : cases()) {
    ChildRun last_compress, last_diff;
    for (int k = 0; k < 3; ++k) {
      const double size = c.size * scale * double(1 << k);
      const fs::path file = dir / "case.nc";
      std::ofstream(file) << c.text(size);
      const fs::path out = dir / "out.nc";
      const ChildRun compress = run_child({ARCPRESS_BINARY, file.string(), "-o", out.string()});
      const ChildRun diff = run_child({ARCPRESS_BINARY, "diff", file.string(), out.string(), "-j1"});
      auto ratio = [&](const ChildRun& now, const ChildRun& before, bool time) {
        if (k == 0) return std::string("");
        if (time && now.seconds < kNoiseSeconds && before.seconds < kNoiseSeconds) return std::string("-");
        const double r = time ? now.seconds / before.seconds : now.peak_mib / before.peak_mib;
        if (r > kMaxRatio) over = true;
        return fmt::format("{:.2f}{}", r, r > kMaxRatio ? "!" : "");
      };
      fmt::print("{:<24}{:>8}{:>14g}  {:>10.3f}{:>10.1f}{:>8}{:>8}  {:>10.3f}{:>10.1f}{:>8}{:>8}{}\n", k == 0 ? c.name : "",
                 k == 0 ? c.grows : "", size, compress.seconds, compress.peak_mib, ratio(compress, last_compress, true),
                 ratio(compress, last_compress, false), diff.seconds, diff.peak_mib, ratio(diff, last_diff, true),
                 ratio(diff, last_diff, false),
                 compress.exit_code < 0 || diff.exit_code < 0 ? "  (a run did not finish)" : "");
      last_compress = compress;
      last_diff = diff;
    }
  }
  fs::remove_all(dir);
  if (over) fmt::print("a ratio above {} per doubling: work grows faster than the size ('!')\n", kMaxRatio);
  return over ? 1 : 0;
}
