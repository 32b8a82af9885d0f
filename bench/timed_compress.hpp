// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// One corpus file read whole, and the best of several compressions of it: the figures the
// throughput benches print.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>

#include "arcpress/api/arcpress.hpp"

inline std::string file_text(const std::filesystem::path& f) {
  std::ifstream in(f, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// The best of `repeats` compressions of `text` (file `f`) with `opt`, in seconds, and the
/// last result.
inline std::pair<double, arcpress::CompressResult> timed_compress(const std::filesystem::path& f, const std::string& text,
                                                                  const arcpress::CompressOptions& opt, int repeats) {
  using clk = std::chrono::steady_clock;
  double best = 1e9;
  arcpress::CompressResult r;
  for (int k = 0; k < repeats; ++k) {
    arcpress::DiagnosticSink sink;
    const auto t0 = clk::now();
    r = arcpress::compress(f.string(), text, opt, sink);
    best = std::min(best, std::chrono::duration<double>(clk::now() - t0).count());
  }
  return {best, std::move(r)};
}
