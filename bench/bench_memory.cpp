// SPDX-License-Identifier: GPL-3.0-or-later
// Peak memory of the arcpress command: each corpus file of 1 MB or more, then the bunny
// printer program once, 8 times over and repeated to 520 MB (or the megabytes the argument
// gives), and one zigzag path of a million moves that no piece can end at a chain's end, each run as a child process whose peak resident set the kernel reports (wait4).
// Three runs per file: `--method keep --no-verify` (reading and writing back: the floor),
// `--no-verify` (fitting) and the default (fitting, then reading the output back and
// comparing it with the input). Prints megabytes and the ratio to the input's size, and
// fails (exit 1) where any run takes more than 64 MiB or the default's peak on the biggest
// program lies more than 8 MiB above its peak on the bunny alone.
//   bench_memory [--markdown] [MB]
// With --markdown, the table alone, as docs/streaming.md shows it (scripts/docs_figures.sh).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "child_process.hpp"

namespace fs = std::filesystem;

namespace {

/// Peak resident set of `arcpress FILE -o - ARGS...` in MiB, its standard output and
/// error thrown away; none when it could not run or failed.
std::optional<double> peak_mib(const fs::path& file, const std::vector<std::string>& args) {
  std::vector<std::string> words = {ARCPRESS_BINARY, file.string(), "-o", "-"};
  words.insert(words.end(), args.begin(), args.end());
  const arcpress::bench::ChildRun r = arcpress::bench::run_child(words);
  if (r.exit_code != 0) return std::nullopt;
  return r.peak_mib;
}

bool g_markdown = false;  // print Markdown rows

struct Peaks {
  std::string name;
  std::optional<double> keep, fit, all;
};

Peaks measure(const std::string& name, const fs::path& file) {
  const double in_mib = double(fs::file_size(file)) / (1024.0 * 1024.0);
  auto keep = peak_mib(file, {"--method", "keep", "--no-verify"});
  auto fit = peak_mib(file, {"--no-verify"});
  auto all = peak_mib(file, {});
  auto cell = [&](const std::optional<double>& m) {
    return m ? fmt::format("{:>8.0f} {:>5.0f}x", *m, *m / in_mib) : fmt::format("{:>15}", "failed");
  };
  if (g_markdown) {
    auto md = [](const std::optional<double>& m) { return m ? fmt::format("{:.0f}", *m) : std::string("failed"); };
    fmt::print("| {} | {:.1f} | {} | {} | {} |\n", name, in_mib, md(keep), md(fit), md(all));
  } else {
    fmt::print("{:<46} {:>8.1f}  {}  {}  {}\n", name, in_mib, cell(keep), cell(fit), cell(all));
  }
  std::fflush(stdout);
  return {name, keep, fit, all};
}

}  // namespace

/// The most memory arcpress may take with default options on any input, MiB.
constexpr double kLimitMib = 64;
/// How far the peak on the biggest program may lie above the peak on the file it repeats:
/// what threads, pieces and the allocator's moods may add, never a share of the input.
constexpr double kGrowthMib = 8;

int main(int argc, char** argv) {
  g_markdown = argc > 1 && std::string(argv[1]) == "--markdown";
  if (g_markdown) --argc, ++argv;
  // Bytes of the biggest program: 520 MB unless the first argument says otherwise (MB).
  const double big_mb = argc > 1 ? std::max(1.0, std::atof(argv[1])) : 520;
  const fs::path corpus = ARCPRESS_CORPUS_DIR;
  const fs::path bunny = corpus / "printer" / "prusaslicer-2.5_bunny_marlin.gcode";
  if (!fs::exists(bunny)) {
    fmt::print("no corpus at {}\n", corpus.string());
    return 0;
  }
  if (g_markdown) {
    fmt::print("| file | input MiB | keep, no check | no check | default |\n|---|---|---|---|---|\n");
  } else {
    fmt::print("peak resident set of `arcpress FILE -o -`, MiB and times the input's size\n");
    fmt::print("{:<46} {:>8}  {:>15}  {:>15}  {:>15}\n", "file", "in MiB", "keep,no-verify", "--no-verify",
               "default");
  }
  // The corpus files of 1 MB or more, then the biggest repeated 8 times and to `big_mb`.
  std::vector<fs::path> files;
  for (const auto& sub : {"cnc", "printer"})
    for (const auto& e : fs::directory_iterator(corpus / sub))
      if (fs::file_size(e.path()) >= 1000000) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::vector<Peaks> peaks;
  for (const auto& f : files) peaks.push_back(measure(f.filename().string(), f));
  const fs::path dir = fs::temp_directory_path() / fmt::format("arcpress-bench-memory-{}", getpid());
  fs::create_directories(dir);
  std::string text;
  {
    std::ifstream in(bunny, std::ios::binary);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const size_t big_copies = size_t(std::ceil(big_mb * 1e6 / double(text.size())));
  std::optional<double> bunny_peak, biggest_peak;
  for (size_t copies : {size_t(1), size_t(8), big_copies}) {
    const fs::path file = dir / fmt::format("bunny-x{}.gcode", copies);
    {
      std::ofstream out(file, std::ios::binary);
      for (size_t k = 0; k < copies; ++k) out << text;
    }
    const Peaks p = measure(fmt::format("bunny x {} ({:.0f} MB)", copies, double(fs::file_size(file)) / 1e6), file);
    peaks.push_back(p);
    if (copies == 1) bunny_peak = p.all;
    biggest_peak = p.all;
    fs::remove(file);
  }
  // One path no piece can end at a chain's end (every vertex a corner of a zigzag, no move
  // that closes a chain): pieces are cut at vertices, every kMaxPieceBytes.
  {
    const fs::path file = dir / "zigzag.nc";
    {
      std::ofstream out(file, std::ios::binary);
      out << "G21 G90\nG0 X0 Y0 Z1\nG1 Z0 F600\n";
      for (long i = 1; i <= 1000000; ++i) out << fmt::format("G1 X{:.4f} Y{:.4f}\n", double(i) * 0.001, double(i % 2) * 0.001);
      out << "M2\n";
    }
    peaks.push_back(measure(fmt::format("one zigzag path ({:.0f} MB)", double(fs::file_size(file)) / 1e6), file));
    fs::remove(file);
  }
  fs::remove_all(dir);
  // The promise: flat in the input's size, and under the limit on every input.
  bool ok = true;
  for (const Peaks& p : peaks)
    for (const auto& m : {p.keep, p.fit, p.all})
      if (!m || *m > kLimitMib) {
        fmt::print("FAIL: {}: peak {} MiB, limit {} MiB\n", p.name, m ? fmt::format("{:.0f}", *m) : "unknown",
                   kLimitMib);
        ok = false;
      }
  if (bunny_peak && biggest_peak && *biggest_peak > *bunny_peak + kGrowthMib) {
    fmt::print("FAIL: the peak grows with the input: {:.0f} MiB for bunny, {:.0f} MiB for {:.0f} MB of it "
               "(allowed {:.0f} MiB more)\n",
               *bunny_peak, *biggest_peak, big_mb, kGrowthMib);
    ok = false;
  }
  if (!g_markdown || !ok) fmt::print("{}\n", ok ? "memory: flat in the input's size and under the limit" : "memory: FAILED");
  return ok ? 0 : 1;
}
