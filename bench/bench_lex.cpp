// SPDX-License-Identifier: GPL-3.0-or-later
// Lexer + interpreter throughput over the corpus, printed beside a plain read of the same bytes.
// Usage: bench_lex [REPEATS] [FILES...]   (default: every corpus file, best of 5)
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "corpus_files.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"

namespace fs = std::filesystem;
using clk = std::chrono::steady_clock;

int main(int argc, char** argv) {
  int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  std::vector<fs::path> files;
  for (int i = 2; i < argc; ++i) files.emplace_back(argv[i]);
  if (files.empty()) files = corpus_files();
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    fmt::print("no input files (corpus folder {} absent)\n", ARCPRESS_CORPUS_DIR);
    return 0;
  }
  fmt::print("{:<55} {:>10} {:>12} {:>12} {:>8}\n", "file", "MB", "read MB/s", "lex+int MB/s", "ratio");
  double total_mb = 0, total_read = 0, total_lex = 0;
  size_t sink_blocks = 0;
  for (const auto& f : files) {
    double best_read = 1e9, best_lex = 1e9;
    std::string text;
    for (int r = 0; r < repeats; ++r) {
      auto t0 = clk::now();
      std::ifstream in(f, std::ios::binary);
      text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      auto t1 = clk::now();
      arcpress::DiagnosticSink sink(f.string());
      auto prog = arcpress::lex(f.string(), text, sink);
      auto interp = arcpress::interpret(prog, sink);
      auto t2 = clk::now();
      sink_blocks += prog.blocks.size() + interp.moves.size();
      best_read = std::min(best_read, std::chrono::duration<double>(t1 - t0).count());
      best_lex = std::min(best_lex, std::chrono::duration<double>(t2 - t1).count());
    }
    double mb = double(text.size()) / 1e6;
    total_mb += mb;
    total_read += best_read;
    total_lex += best_lex;
    fmt::print("{:<55} {:>10.3f} {:>12.0f} {:>12.0f} {:>8.2f}\n", f.filename().string(), mb, mb / best_read,
               mb / best_lex, best_lex / best_read);
  }
  fmt::print("{:<55} {:>10.3f} {:>12.0f} {:>12.0f} {:>8.2f}\n", "TOTAL (one core)", total_mb, total_mb / total_read,
             total_mb / total_lex, total_lex / total_read);
  fmt::print("(blocks+moves seen: {})\n", sink_blocks);
  return 0;
}
