// Peak memory of the arcpress command: each corpus file of 1 MB or more, and the largest
// repeated `copies` times (10 by default) to show how the peak grows with the input, each
// run as a child process whose peak resident set the kernel reports (wait4). Three runs per
// file: `--method keep --no-verify` (reading and writing back: the floor), `--no-verify`
// (fitting) and the default (fitting, then reading the output back and comparing it with
// the input). Prints megabytes and the ratio to the input's size.
//   bench_memory [copies]
#include <fmt/format.h>

#include <algorithm>
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

void measure(const std::string& name, const fs::path& file) {
  const double in_mib = double(fs::file_size(file)) / (1024.0 * 1024.0);
  auto keep = peak_mib(file, {"--method", "keep", "--no-verify"});
  auto fit = peak_mib(file, {"--no-verify"});
  auto all = peak_mib(file, {});
  auto cell = [&](const std::optional<double>& m) {
    return m ? fmt::format("{:>8.0f} {:>5.0f}x", *m, *m / in_mib) : fmt::format("{:>15}", "failed");
  };
  fmt::print("{:<46} {:>8.1f}  {}  {}  {}\n", name, in_mib, cell(keep), cell(fit), cell(all));
}

}  // namespace

int main(int argc, char** argv) {
  const int copies = argc > 1 ? std::max(1, std::atoi(argv[1])) : 10;
  const fs::path corpus = ARCPRESS_CORPUS_DIR;
  if (!fs::exists(corpus)) {
    fmt::print("no corpus at {}\n", corpus.string());
    return 0;
  }
  std::vector<fs::path> files;
  for (const auto& sub : {"cnc", "printer"})
    for (const auto& e : fs::directory_iterator(corpus / sub))
      if (fs::file_size(e.path()) >= 1000000) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  fmt::print("peak resident set of `arcpress FILE -o -`, MiB and times the input's size\n");
  fmt::print("{:<46} {:>8}  {:>15}  {:>15}  {:>15}\n", "file", "in MiB", "keep,no-verify", "--no-verify",
             "default");
  for (const auto& f : files) measure(f.filename().string(), f);
  if (files.empty()) return 0;
  // The largest file, `copies` times over, in a temporary folder.
  const fs::path largest = *std::max_element(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    return fs::file_size(a) < fs::file_size(b);
  });
  const fs::path dir = fs::temp_directory_path() / fmt::format("arcpress-bench-memory-{}", getpid());
  fs::create_directories(dir);
  const fs::path big = dir / ("x" + std::to_string(copies) + "-" + largest.filename().string());
  {
    std::ifstream in(largest, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream out(big, std::ios::binary);
    for (int k = 0; k < copies; ++k) out << text;
  }
  measure(fmt::format("{} x {}", largest.filename().string(), copies), big);
  fs::remove_all(dir);
  return 0;
}
