// SPDX-License-Identifier: GPL-3.0-or-later
// arcpress diff speed: a synthetic program of N feed moves (a long spiral of short G1
// moves, 1 million by default) against its compressed version, and each corpus file
// against its compressed version. Prints moves compared per second by the path measure
// (diff_programs()), then the whole command as a user runs it (`arcpress diff A B`: reading,
// lexing, interpreting and measuring both files; best of three): seconds and the pages the
// kernel mapped in for it. (Not its peak resident set: a child spawned from this process
// inherits this process's peak in that count.)
//   bench_diff [N]
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "arcpress/api/arcpress.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"
#include "arcpress/verify/program_diff.hpp"
#include "child_process.hpp"

using namespace arcpress;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

void measure(const std::string& name, const std::string& a_text) {
  DiagnosticSink sink(name);
  CompressOptions opt;
  opt.verify = false;
  CompressResult r = compress(name, a_text, opt, sink);
  DiagnosticSink sa("a"), sb("b");
  Program pa = lex("a", a_text, sa), pb = lex("b", r.output, sb);
  Interpretation ia = interpret(pa, sa), ib = interpret(pb, sb);
  DiffOptions d;
  auto t0 = Clock::now();
  ProgramDiff diff = diff_programs(pa, ia, pb, ib, d);
  double s = seconds_since(t0);
  size_t moves = ia.moves.size() + ib.moves.size();
  fmt::print("{:<48} {:>9} + {:>8} moves  {:>7.3f} s  {:>6.2f} M moves/s  max {:.6f} mm\n", name, ia.moves.size(),
             ib.moves.size(), s, double(moves) / s / 1e6, diff.max_deviation_mm);
}

/// `arcpress diff` of `a_text` against its compressed output, as a command: the best of three
/// runs. With `band_mm`, both at that band (else the defaults).
void measure_command(const std::string& name, const std::string& a_text, double band_mm = 0) {
  DiagnosticSink sink(name);
  CompressOptions opt;
  opt.verify = false;
  if (band_mm > 0) opt.fit.tolerance_mm = band_mm;
  const CompressResult r = compress(name, a_text, opt, sink);
  const auto dir = std::filesystem::temp_directory_path() / fmt::format("arcpress-bench-diff-{}", ::getpid());
  std::filesystem::create_directories(dir);
  const auto a = dir / "a.nc", b = dir / "b.nc";
  std::ofstream(a, std::ios::binary) << a_text;
  std::ofstream(b, std::ios::binary) << r.output;
  bench::ChildRun best;
  for (int k = 0; k < 3; ++k) {
    std::vector<std::string> args = {ARCPRESS_BINARY, "diff", a.string(), b.string()};
    if (band_mm > 0) args.insert(args.end(), {"--tolerance", fmt::format("{}", band_mm)});
    const bench::ChildRun run = bench::run_child(args);
    if (k == 0 || run.seconds < best.seconds) best = run;
  }
  std::filesystem::remove_all(dir);
  const std::string command = band_mm > 0 ? fmt::format("arcpress diff, both at {} mm", band_mm) : "arcpress diff";
  fmt::print("{:<48} {}  {:>7.3f} s  {:>7} page faults  exit {}\n", name, command, best.seconds, best.minor_faults,
             best.exit_code);
}

}  // namespace

int main(int argc, char** argv) {
  size_t n = argc > 1 ? std::stoul(argv[1]) : 1000000;
  std::string t = "G21 G90\nG0 X0 Y0 Z0\nG1 F1000\n";
  t.reserve(n * 32);
  for (size_t k = 1; k <= n; ++k) {
    double a = double(k) * 0.002, r = 5 + 0.0005 * double(k) / 50;  // 0.01-0.1 mm moves
    t += fmt::format("X{:.4f} Y{:.4f}\n", r * std::cos(a), r * std::sin(a));
  }
  measure(fmt::format("synthetic spiral, {} moves", n), t);
  std::filesystem::path corpus = ARCPRESS_CORPUS_DIR;
  if (!std::filesystem::exists(corpus)) return 0;
  for (const auto& sub : {"cnc", "printer"})
    for (const auto& e : std::filesystem::directory_iterator(corpus / sub)) {
      if (std::filesystem::file_size(e.path()) < 1000000) continue;
      std::ifstream f(e.path(), std::ios::binary);
      std::stringstream ss;
      ss << f.rdbuf();
      measure(e.path().filename().string(), ss.str());
      measure_command(e.path().filename().string(), ss.str());
      // A band as wide as several printed lines: most of the path lies within the band of
      // other passes, and the feed's pairing searches further for each piece.
      measure_command(e.path().filename().string(), ss.str(), 1.0);
    }
}
