// SPDX-License-Identifier: GPL-3.0-or-later
// The compression of every corpus file by one method, the pipeline without verification as
// bench_curves times it, in one process: for timing one change against another, and for
// counting instructions under callgrind (one repeat), where a figure does not move.
// Usage: bench_fit [METHOD] [REPEATS] [THREADS] [MATCH]
//   METHOD: keep, arcs (default), global, greedy, stream or lowe; REPEATS: best of (3);
//   THREADS: workers (1; 0: one per hardware thread); MATCH: only the files whose path
//   holds it (one file's share of the time, e.g. freecad).
// The fitter's own instructions are those of a method less those of keep, e.g.
//   valgrind --tool=callgrind ./build/bench/bench_fit arcs 1 1   (and keep 1 1)
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "corpus_files.hpp"
#include "timed_compress.hpp"
#include "arcpress/api/arcpress.hpp"

namespace fs = std::filesystem;
using arcpress::FitOptions;

int main(int argc, char** argv) {
  const std::string_view name = argc > 1 ? argv[1] : "arcs";
  const std::pair<std::string_view, FitOptions::Method> methods[] = {
      {"keep", FitOptions::Method::Keep},     {"arcs", FitOptions::Method::Arcs},
      {"global", FitOptions::Method::Global}, {"greedy", FitOptions::Method::Greedy},
      {"stream", FitOptions::Method::Stream}, {"lowe", FitOptions::Method::Lowe}};
  const auto* method = std::find_if(std::begin(methods), std::end(methods), [&](const auto& m) { return m.first == name; });
  if (method == std::end(methods)) {
    fmt::print(stderr, "bench_fit: unknown method '{}' (keep, arcs, global, greedy, stream, lowe)\n", name);
    return 2;
  }
  const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
  const unsigned threads = argc > 3 ? unsigned(std::max(0, std::atoi(argv[3]))) : 1;
  std::vector<fs::path> files = corpus_files();
  if (argc > 4)
    std::erase_if(files, [&](const fs::path& f) { return f.string().find(argv[4]) == std::string::npos; });
  if (files.empty()) {
    fmt::print("no corpus at {}\n", ARCPRESS_CORPUS_DIR);
    return 0;
  }
  double seconds = 0;
  size_t points = 0, blocks = 0;
  for (const auto& f : files) {
    arcpress::CompressOptions opt;
    opt.verify = false;
    opt.fit.method = method->second;
    opt.threads = threads;
    const auto [best, r] = timed_compress(f, file_text(f), opt, repeats);
    seconds += best;
    points += r.stats.moves_in;
    blocks += r.stats.lines_out + r.stats.arcs_out;
  }
  fmt::print("{}: {} files, {} run points, {} blocks out, {:.4f} s (best of {}, {} thread(s)), {:.2f} M run points/s through the pipeline\n",
             name, files.size(), points, blocks, seconds, repeats, threads == 0 ? std::string("all") : std::to_string(threads),
             double(points) / seconds / 1e6);
  return 0;
}
