// SPDX-License-Identifier: GPL-3.0-or-later
// arcpress against ArcWelder, the tool printer users pick instead, side by side on this
// machine: every corpus file of at least 100 KB at ±0.025 and ±0.01 mm. arcpress runs its
// default (check on, every hardware thread, the dialect the file names); ArcWelder its
// console's default at the same band (-r twice the tolerance: its resolution is the band's
// width). The two take turns, PAIRS pairs per file and band, and the median of each is
// printed: CPU seconds (user and system, all threads), wall seconds, MB/s, the median of
// the pairs' ratios arcpress / ArcWelder, the motion blocks each wrote (G0-G3 blocks and
// blocks of bare axis words, one counter for both tools' files), and how far each output's
// path lies from the input's, as `arcpress diff` measures both (both ways, on the
// programmed path: arcs as circles).
// ArcWelder rewrites only extruding moves: on a CNC program (corpus/cnc), whose feed moves
// carry no E, its default writes every move back. Such a program also gets a row of
// ArcWelder with --allow-travel-arcs (-y), its way to fit moves that do not extrude.
//   bench_vs_arcwelder ARCWELDER [PAIRS]   ARCWELDER: the path of ArcWelder's console program
//   bench_vs_arcwelder ARCWELDER --instructions
//   bench_vs_arcwelder ARCWELDER --printers
// With --instructions, each runs once under valgrind's callgrind (on PATH), which counts the
// instructions every thread executes: a figure that a busy machine does not move, where
// times move by tens of per cent from run to run. It counts work, not time: a division or
// a cache miss costs more than an addition.
// With --printers, the band each tool holds on the printer files (all sizes, both bands, read
// as Marlin reads them): ArcWelder with the options of bench_printers' reference figures
// (-r twice the tolerance, -y), its blocks and the largest distance of its path from the
// input's on the programmed path and on the chords Marlin cuts its arcs into (arcpress diff,
// and with --executed); then the largest resolution, in twentieths of -r from -r down to
// half of it, at which its executed path keeps the band, and its blocks there; beside
// arcpress's blocks and executed distance at its default with --dialect marlin.
// ArcWelder is no Debian package: build it from its source (FormerLurker/ArcWelderLib,
// target ArcWelderConsole) in a folder of your own.
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "corpus_files.hpp"

namespace fs = std::filesystem;
using arcpress::bench::ChildRun;
using arcpress::bench::run_child;

namespace {

/// Motion blocks in a program: lines that begin with G0..G3 (not G38, G30, ...) or with an
/// axis, E or F word.
size_t motion_blocks(const fs::path& file) {
  std::ifstream in(file);
  size_t n = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    const char c = char(std::toupper(static_cast<unsigned char>(line[0])));
    if (c == 'X' || c == 'Y' || c == 'Z' || c == 'E' || c == 'F') {
      ++n;
    } else if (c == 'G' && line.size() >= 2 && line[1] >= '0' && line[1] <= '3' &&
               (line.size() == 2 || !std::isdigit(static_cast<unsigned char>(line[2])))) {
      ++n;
    }
  }
  return n;
}

/// `name` found on PATH, or empty.
std::string on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  for (std::string dirs = path ? path : ""; !dirs.empty();) {
    const size_t colon = dirs.find(':');
    const fs::path candidate = fs::path(dirs.substr(0, colon)) / name;
    if (fs::exists(candidate)) return candidate.string();
    dirs = colon == std::string::npos ? "" : dirs.substr(colon + 1);
  }
  return {};
}

/// The instructions `words` executes under callgrind, all threads; 0 where it fails.
double instructions(const std::vector<std::string>& words, const fs::path& log) {
  static const std::string valgrind = on_path("valgrind");
  if (valgrind.empty()) return 0;
  std::vector<std::string> all = {valgrind, "--tool=callgrind", "--callgrind-out-file=/dev/null",
                                  "--log-file=" + log.string()};
  all.insert(all.end(), words.begin(), words.end());
  const ChildRun r = run_child(all);
  std::ifstream in(log);
  double n = 0;
  for (std::string line; std::getline(in, line);)
    if (const auto at = line.find("Collected : "); at != std::string::npos) n = std::atof(line.c_str() + at + 12);
  return r.exit_code == 0 ? n : 0;
}

/// The largest distance between the paths of programs `in` and `out` that `arcpress diff`
/// measures at `band` (mm), with `options` (a dialect, --executed), or a negative number
/// where it printed none; `report` holds what it printed.
double measured_deviation_mm(const fs::path& in, const fs::path& out, double band, const fs::path& report,
                             const std::vector<std::string>& options = {}) {
  std::vector<std::string> words = {ARCPRESS_BINARY, "diff", in.string(), out.string(), "--tolerance",
                                    fmt::format("{}", band)};
  words.insert(words.end(), options.begin(), options.end());
  run_child(words, report.string());
  std::ifstream text(report);
  for (std::string line; std::getline(text, line);)
    if (const auto at = line.find("max deviation "); at != std::string::npos) return std::atof(line.c_str() + at + 14);
  return -1;
}

/// A distance for the tables: "-" where none was measured, in bold above the band.
std::string deviation_cell(double d_mm, double band) {
  if (d_mm < 0) return "-";
  return d_mm > band ? fmt::format("**{:.4f}**", d_mm) : fmt::format("{:.4f}", d_mm);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    fmt::print(stderr, "usage: bench_vs_arcwelder ARCWELDER [PAIRS | --instructions | --printers]\n");
    return 2;
  }
  const std::string arcwelder = argv[1];
  const bool count = argc > 2 && std::string(argv[2]) == "--instructions";
  const bool printers = argc > 2 && std::string(argv[2]) == "--printers";
  const int pairs = argc > 2 && !count && !printers ? std::max(1, std::atoi(argv[2])) : 3;
  if (!fs::exists(arcwelder)) {
    fmt::print(stderr, "bench_vs_arcwelder: no ArcWelder at '{}'\n", arcwelder);
    return 2;
  }
  const fs::path dir = fs::temp_directory_path() / fmt::format("arcpress-vs-arcwelder-{}", ::getpid());
  fs::create_directories(dir);
  const fs::path out_a = dir / "arcpress.gcode", out_b = dir / "arcwelder.gcode";
  // Every corpus file of at least 100 KB at both bands, with the two commands that run it
  // and the name of its row (a CNC program's second row says ArcWelder's option).
  struct Case {
    fs::path file;
    std::string name;
    double mb, band;
    std::vector<std::string> a, b;
  };
  std::vector<Case> cases;
  for (const fs::path& f : corpus_files()) {
    const double mb = double(fs::file_size(f)) / 1e6;
    if (mb < 0.1) continue;
    const bool cnc = f.parent_path().filename() == "cnc";
    for (const double band : {0.025, 0.01}) {
      const std::vector<std::string> a = {ARCPRESS_BINARY, f.string(), "-o", out_a.string(),
                                          "--tolerance", fmt::format("{}", band), "-q"};
      const std::vector<std::string> b = {arcwelder, f.string(), out_b.string(), fmt::format("-r={}", 2 * band)};
      cases.push_back({f, f.filename().string(), mb, band, a, b});
      if (cnc) {
        std::vector<std::string> travel = b;
        travel.push_back("-y");
        cases.push_back({f, f.filename().string() + ", ArcWelder -y", mb, band, a, travel});
      }
    }
  }
  bool failed = false;
  if (printers) {
    fmt::print("| file | band mm | ArcWelder blocks | ArcWelder dev. program mm | ArcWelder dev. executed mm | "
               "largest -r holding the band executed | ArcWelder blocks there | arcpress blocks | arcpress dev. "
               "executed mm |\n");
    fmt::print("|---|---|---|---|---|---|---|---|---|\n");
    const std::vector<std::string> marlin = {"--dialect", "marlin"}, executed = {"--dialect", "marlin", "--executed"};
    const fs::path report = dir / "diff.txt";
    for (const fs::path& f : corpus_files()) {
      if (f.parent_path().filename() != "printer") continue;
      for (const double band : {0.025, 0.01}) {
        auto arcwelder_at = [&](double r) {
          return run_child({arcwelder, f.string(), out_b.string(), fmt::format("-r={}", r), "-y"}).exit_code == 0;
        };
        auto shown = [&](double d) { return deviation_cell(d, band); };
        const bool ran = run_child({ARCPRESS_BINARY, f.string(), "-o", out_a.string(), "--tolerance",
                                    fmt::format("{}", band), "-q", "--dialect", "marlin"})
                             .exit_code == 0;
        if (!ran || !arcwelder_at(2 * band)) {
          fmt::print(stderr, "bench_vs_arcwelder: {} at {} mm: a run failed\n", f.filename().string(), band);
          failed = true;
          continue;
        }
        const size_t blocks_b = motion_blocks(out_b);
        const double program_b = measured_deviation_mm(f, out_b, band, report, marlin);
        const double executed_b = measured_deviation_mm(f, out_b, band, report, executed);
        std::string held = "none", held_blocks = "-";
        for (int k = 20; k >= 10; --k) {
          const double r = 2 * band * k / 20;
          if (k < 20 && !arcwelder_at(r)) break;
          const double d = k == 20 ? executed_b : measured_deviation_mm(f, out_b, band, report, executed);
          if (d >= 0 && d <= band) {
            held = fmt::format("{:.4g}", r);
            held_blocks = std::to_string(motion_blocks(out_b));
            break;
          }
        }
        fmt::print("| {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", f.filename().string(), band, blocks_b,
                   shown(program_b), shown(executed_b), held, held_blocks, motion_blocks(out_a),
                   shown(measured_deviation_mm(f, out_a, band, report, executed)));
      }
    }
    fs::remove_all(dir);
    return failed ? 1 : 0;
  }
  if (count) {
    fmt::print("| file | MB | band mm | arcpress instructions | ArcWelder instructions | A/B |\n");
    fmt::print("|---|---|---|---|---|---|\n");
    for (const Case& c : cases) {
      const double a = instructions(c.a, dir / "a.log"), b = instructions(c.b, dir / "b.log");
      if (a == 0 || b == 0) {
        fmt::print(stderr, "bench_vs_arcwelder: {} at {} mm: no count (is valgrind on PATH?)\n", c.name, c.band);
        failed = true;
        continue;
      }
      fmt::print("| {} | {:.2f} | {} | {:.3f} G | {:.3f} G | {:.2f} |\n", c.name, c.mb, c.band, a / 1e9, b / 1e9, a / b);
    }
    fs::remove_all(dir);
    return failed ? 1 : 0;
  }
  fmt::print("| file | MB | band mm | arcpress CPU s | ArcWelder CPU s | CPU A/B | wall A/B | arcpress MB/s | "
             "ArcWelder MB/s | arcpress blocks | ArcWelder blocks | arcpress deviation mm | ArcWelder deviation mm |\n");
  fmt::print("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Case& c : cases) {
    const fs::path& f = c.file;
    const double band = c.band, mb = c.mb;
    std::vector<double> cpu_a, cpu_b, wall_a, wall_b, cpu_ratio, wall_ratio;
    for (int k = 0; k < pairs; ++k) {
      const ChildRun a = run_child(c.a);
      const ChildRun b = run_child(c.b);
      if (a.exit_code != 0 || b.exit_code != 0) {
        fmt::print(stderr, "bench_vs_arcwelder: {} at {} mm: arcpress exit {}, ArcWelder exit {}\n", c.name, band,
                   a.exit_code, b.exit_code);
        failed = true;
      }
      // The two of a pair run back to back, under the same load: their ratio drifts less
      // than the ratio of the medians on a machine whose load comes and goes.
      if (b.cpu_seconds > 0) cpu_ratio.push_back(a.cpu_seconds / b.cpu_seconds);
      if (b.seconds > 0) wall_ratio.push_back(a.seconds / b.seconds);
      cpu_a.push_back(a.cpu_seconds);
      cpu_b.push_back(b.cpu_seconds);
      wall_a.push_back(a.seconds);
      wall_b.push_back(b.seconds);
    }
    const double ca = median(cpu_a), cb = median(cpu_b), wa = median(wall_a), wb = median(wall_b);
    // Each output against the input, by the same measure.
    auto deviation = [&](const fs::path& out) {
      return deviation_cell(measured_deviation_mm(f, out, band, dir / "diff.txt"), band);
    };
    fmt::print("| {} | {:.2f} | {} | {:.3f} | {:.3f} | {:.2f} | {:.2f} | {:.1f} | {:.1f} | {} | {} | {} | {} |\n", c.name,
               mb, band, ca, cb, median(cpu_ratio), median(wall_ratio), mb / wa, mb / wb, motion_blocks(out_a),
               motion_blocks(out_b), deviation(out_a), deviation(out_b));
  }
  fs::remove_all(dir);
  return failed ? 1 : 0;
}
