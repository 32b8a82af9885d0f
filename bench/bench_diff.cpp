// arcpress diff speed: a synthetic program of N feed moves (a long spiral of short G1
// moves, 1 million by default) against its compressed version, and each corpus file
// against its compressed version. Prints moves compared per second.
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
    }
}
