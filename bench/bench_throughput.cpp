// SPDX-License-Identifier: GPL-3.0-or-later
// Throughput of the streaming engine as ratios to a bare tokenizer on the same files in the
// same run: ../shared/tools/parse_ceiling.cpp, which only splits words and parses numbers,
// built beside this bench. Per file (bunny, FreeCAD, ps271 and bunny x 8): the tokenizer's
// MB/s; lexing and interpreting as the engine's reader does, in pieces, in MB/s and as a share of it; compressing
// with verification (the default) through Compressor in 1 MiB pushes on one thread and on
// every hardware thread, in MB/s and as a share of it; and the fit's quality: blocks out and
// the measured maximum deviation. Best of three runs each.
// The cores of a shared machine need not run alike (here one ran the tokenizer at half the
// other's rate, run after run, and which one changed over minutes): per file, a run of the
// tokenizer on each core picks the faster, and there the tokenizer, the reader and the
// one-thread compression run in turns, the best of three rounds each, so that each ratio
// compares like with like; the all-threads compression runs on every core.
// With --stages, where one thread's time goes instead: the reader alone, the pipeline writing
// every move as it is without the check (--method keep --no-verify), fitting without the
// check (--no-verify), and the default, as MB/s and as shares of the default's time.
//   bench_throughput [--markdown] [--stages] [PARSE_CEILING]
// With --markdown, the table alone, as docs/streaming.md shows it (scripts/docs_figures.sh).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <sched.h>

#include "arcpress/api/compressor.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"
#include "timed_compress.hpp"

namespace fs = std::filesystem;
using namespace arcpress;
using clk = std::chrono::steady_clock;

namespace {

constexpr int kRepeats = 3;

/// The cores this process may run on.
std::vector<int> allowed_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  std::vector<int> cores;
  if (sched_getaffinity(0, sizeof set, &set) != 0) return cores;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &set)) cores.push_back(c);
  return cores;
}

/// Runs this process (and what it starts) on `cores` only.
void pin(const std::vector<int>& cores) {
  cpu_set_t set;
  CPU_ZERO(&set);
  for (int c : cores) CPU_SET(c, &set);
  sched_setaffinity(0, sizeof set, &set);
}

/// The tokenizer's MB/s on `file`, as it prints it; none when it could not run.
std::optional<double> ceiling_once(const std::string& exe, const fs::path& file) {
  const std::string cmd = fmt::format("'{}' '{}'", exe, file.string());
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return std::nullopt;
  char line[512] = {};
  std::string out;
  while (std::fgets(line, sizeof line, p)) out += line;
  if (::pclose(p) != 0) return std::nullopt;
  double mb_s = 0;
  if (std::sscanf(out.c_str(), "parse ceiling: %lf MB/s", &mb_s) != 1) return std::nullopt;
  return mb_s;
}

template <class F>
double best_seconds(F&& f) {
  double best = 1e9;
  for (int k = 0; k < kRepeats; ++k) {
    const auto t0 = clk::now();
    f();
    best = std::min(best, std::chrono::duration<double>(clk::now() - t0).count());
  }
  return best;
}

struct Streamed {
  CompressResult result;
  size_t lines_out = 0;
};

Streamed stream(const std::string& text, unsigned threads, CompressOptions opt = {}) {
  opt.threads = threads;
  DiagnosticSink sink;
  Compressor c("bench", opt, sink);
  std::string out;
  Streamed s;
  for (size_t at = 0; at < text.size(); at += size_t(1) << 20) {
    c.push(std::string_view(text).substr(at, size_t(1) << 20));
    out.clear();
    c.take(out);
    s.lines_out += size_t(std::count(out.begin(), out.end(), '\n'));
  }
  c.finish();
  out.clear();
  c.take(out);
  s.lines_out += size_t(std::count(out.begin(), out.end(), '\n'));
  s.result = c.result();
  return s;
}

/// Seconds to read `text` once as the engine's reader does: line by line into pieces of
/// kPieceBytes, each read on from the state the last one ended in.
double read_seconds(const std::string& text) {
  const auto t0 = clk::now();
  {
    DiagnosticSink sink;
    const Dialect dialect;
    ModalInterpreter reader(dialect, sink, initial_state(dialect));
    uint32_t line = 0;
    size_t moves = 0;
    Program p;
    Interpretation in;
    for (size_t at = 0; at < text.size();) {
      // Each piece read into the last one's buffers, emptied, as the engine reads it.
      p.text.clear();
      p.blocks.clear();
      p.words.clear();
      in.moves.clear();
      in.move_of_block.clear();
      in.unplaced.clear();
      reserve_piece(p, in);
      reader.begin(p, in);
      while (at < text.size() && p.text.size() < kPieceBytes) {
        const size_t nl = text.find('\n', at);
        const size_t end = nl == std::string::npos ? text.size() : nl + 1;
        const size_t begin = p.text.size();
        p.text.append(text, at, end - at);
        lex_line(p, begin, p.text.size(), ++line, sink);
        reader.step(uint32_t(p.blocks.size() - 1));
        at = end;
      }
      moves += in.moves.size();
    }
    if (moves == 0) std::puts("");
  }
  return std::chrono::duration<double>(clk::now() - t0).count();
}

/// Seconds that one call of `f` took.
template <class F>
double seconds_of(F&& f) {
  const auto t0 = clk::now();
  f();
  return std::chrono::duration<double>(clk::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  const bool markdown = argc > 1 && std::string(argv[1]) == "--markdown";
  if (markdown) --argc, ++argv;
  const bool stages = argc > 1 && std::string(argv[1]) == "--stages";
  if (stages) --argc, ++argv;
  const std::string ceiling = argc > 1 ? argv[1] : ARCPRESS_PARSE_CEILING;
  const fs::path corpus = ARCPRESS_CORPUS_DIR;
  const fs::path bunny = corpus / "printer" / "prusaslicer-2.5_bunny_marlin.gcode";
  if (!fs::exists(bunny) || !fs::exists(ceiling)) {
    fmt::print("no corpus at {} or no tokenizer at {}\n", corpus.string(), ceiling);
    return 0;
  }
  const fs::path dir = fs::temp_directory_path() / fmt::format("arcpress-bench-throughput-{}", getpid());
  fs::create_directories(dir);
  const fs::path bunny8 = dir / "bunny-x8.gcode";
  {
    const std::string text = file_text(bunny);
    std::string eight;
    for (int k = 0; k < 8; ++k) eight += text;
    std::ofstream(bunny8, std::ios::binary) << eight;
  }
  const std::array<std::pair<const char*, fs::path>, 4> files = {{
      {"bunny", bunny},
      {"FreeCAD", corpus / "cnc" / "freecad-script_BackFastening_2_OutCut.nc"},
      {"ps271", corpus / "printer" / "ps271_benchy.gcode"},
      {"bunny x 8", bunny8},
  }};
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const std::vector<int> every = allowed_cores();
  if (stages && markdown) {
    fmt::print("| file | MB | tokenizer MB/s | read MB/s | keep, unchecked | fit, unchecked | default | read | rest of "
               "the pipeline | fit | check |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
  } else if (stages) {
    fmt::print("one thread's time by stage (MB/s, then shares of the default's time), best of {}\n", kRepeats);
    fmt::print("{:<10} {:>6} {:>9} | {:>7} {:>7} {:>7} {:>7} | {:>6} {:>6} {:>6} {:>6}\n", "file", "MB", "tokenizer", "read",
               "keep", "fit", "default", "read", "rest", "fit", "check");
  } else if (markdown) {
    fmt::print("| file | MB | tokenizer MB/s | read MB/s | ratio | compress, 1 thread | ratio | {} threads | ratio | gain | "
               "lines out | max deviation mm |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
               cores);
  } else {
    fmt::print("throughput against the bare tokenizer ({}), best of {}; {} hardware threads\n", ceiling, kRepeats, cores);
    fmt::print("{:<10} {:>6} {:>9} | {:>9} {:>6} | {:>9} {:>6} {:>9} {:>6} {:>6} | {:>9} {:>10}\n", "file", "MB",
               "tokenizer", "read", "ratio", "1 thread", "ratio", fmt::format("{} thr.", cores), "ratio", "gain",
               "lines out", "max dev mm");
  }
  bool all_ok = true;
  for (const auto& [name, file] : files) {
    const std::string text = file_text(file);
    const double mb = double(text.size()) / 1e6;
    // The fastest core for this file, by a run of the tokenizer on each; the tokenizer, the
    // reader and the one-thread compression then run there, in turns (one run of each per
    // round, the best of kRepeats rounds), so that a core slowing down over the minutes
    // slows all alike.
    int core = -1;
    double probe = 0;
    for (int c : every) {
      pin({c});
      if (const auto r = ceiling_once(ceiling, file); r && *r > probe) probe = *r, core = c;
    }
    if (core >= 0) pin({core});
    std::optional<double> tok;
    double read_s = 1e9;
    auto tokenizer_and_reader = [&] {
      if (const auto r = ceiling_once(ceiling, file)) tok = std::max(tok.value_or(0.0), *r);
      read_s = std::min(read_s, read_seconds(text));
    };
    if (stages) {
      // One thread, the stages added one at a time: the reader alone; the whole pipeline
      // writing every move as it is, unchecked; fitting, unchecked; and checking (the default).
      CompressOptions keep, unchecked;
      keep.fit.method = FitOptions::Method::Keep;
      keep.verify = unchecked.verify = false;
      Streamed r;
      double keep_s = 1e9, fit_s = 1e9, full_s = 1e9;
      for (int k = 0; k < kRepeats; ++k) {
        tokenizer_and_reader();
        keep_s = std::min(keep_s, seconds_of([&] { r = stream(text, 1, keep); }));
        fit_s = std::min(fit_s, seconds_of([&] { r = stream(text, 1, unchecked); }));
        full_s = std::min(full_s, seconds_of([&] { r = stream(text, 1); }));
      }
      auto share = [&](double s) { return fmt::format("{:.0f} %", 100 * s / full_s); };
      fmt::print(fmt::runtime(markdown ? "| {} | {:.1f} | {} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {} | {} | {} | {} |\n"
                                       : "{:<10} {:>6.1f} {:>9} | {:>7.1f} {:>7.1f} {:>7.1f} {:>7.1f} | {:>6} {:>6} {:>6} {:>6}\n"),
                 name, mb, tok ? fmt::format("{:.0f}", *tok) : "-", mb / read_s, mb / keep_s, mb / fit_s, mb / full_s,
                 share(read_s), share(keep_s - read_s), share(fit_s - keep_s), share(full_s - fit_s));
      std::fflush(stdout);
      continue;
    }
    Streamed one, many;
    double one_s = 1e9;
    for (int k = 0; k < kRepeats; ++k) {
      tokenizer_and_reader();
      one_s = std::min(one_s, seconds_of([&] { one = stream(text, 1); }));
    }
    if (!every.empty()) pin(every);
    const double many_s = best_seconds([&] { many = stream(text, 0); });
    const bool same = one.lines_out == many.lines_out && one.result.check.max_deviation_mm == many.result.check.max_deviation_mm;
    all_ok = all_ok && same && many.result.within_band();
    auto ratio = [&](double mb_s) { return tok ? fmt::format("{:.3f}", mb_s / *tok) : std::string("-"); };
    const std::string row_format = markdown ? "| {} | {:.1f} | {} | {:.1f} | {} | {:.1f} | {} | {:.1f} | {} | {:.2f}× | {} | {:.6f}{} |\n"
                                            : "{:<10} {:>6.1f} {:>9} | {:>9.1f} {:>6} | {:>9.1f} {:>6} {:>9.1f} {:>6} "
                                              "{:>5.2f}x | {:>9} {:>10.6f}{}\n";
    fmt::print(fmt::runtime(row_format), name, mb, tok ? fmt::format("{:.0f}", *tok) : "-", mb / read_s,
               ratio(mb / read_s), mb / one_s, ratio(mb / one_s), mb / many_s, ratio(mb / many_s), one_s / many_s,
               many.lines_out, many.result.check.max_deviation_mm, same ? "" : "  (threads differ!)");
    std::fflush(stdout);
  }
  fs::remove_all(dir);
  if (!markdown && !stages)
    fmt::print("MB/s; ratio: of the tokenizer's MB/s on the same file; gain: 1 thread's time over all threads'\n");
  return all_ok ? 0 : 1;
}
