// SPDX-License-Identifier: GPL-3.0-or-later
#include "batch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <system_error>

#include "arcpress/core/error.hpp"
#include "arcpress/core/utf8_path.hpp"
#include "arcpress/core/workers.hpp"
#include "arcpress/verify/diff_report.hpp"
#include "file_io.hpp"
#include "progress.hpp"

namespace arcpress::cli {
namespace {

namespace fs = std::filesystem;

/// The extensions a folder's G-code files have (compared without case) where no --glob is given.
constexpr const char* kGcodeExtensions[] = {".gcode", ".gco", ".gc", ".g", ".nc", ".ngc", ".tap", ".cnc",
                                            ".ncc",   ".mpf", ".eia", ".iso", ".ptp", ".min"};

/// Whether `name` matches `pattern`, where * stands for any run of characters and ? for one.
bool glob_matches(std::string_view pattern, std::string_view name) {
  size_t p = 0, n = 0, star = std::string_view::npos, from = 0;
  while (n < name.size()) {
    if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == name[n])) {
      ++p, ++n;
    } else if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      from = n;
    } else if (star != std::string_view::npos) {
      p = star + 1;
      n = ++from;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

bool is_gcode_name(const fs::path& p, const std::string& glob) {
  const std::string name = utf8_string(p.filename());
  if (!glob.empty()) return glob_matches(glob, name);
  std::string ext = utf8_string(p.extension());
  std::transform(ext.begin(), ext.end(), ext.begin(), [](char c) { return char(c >= 'A' && c <= 'Z' ? c + 32 : c); });
  return std::find(std::begin(kGcodeExtensions), std::end(kGcodeExtensions), ext) != std::end(kGcodeExtensions);
}

bool is_folder(const std::string& path) {
  std::error_code ec;
  return fs::is_directory(utf8_path(path), ec);
}

/// One program of the batch: where it is read and written, and its name relative to the
/// folder it was found in (its file name where it was named itself).
struct Job {
  std::string input, output, relative;
  size_t size = 0;
};

/// The batch's programs, in order: each named file, and each folder's G-code files, found
/// recursively, sorted by relative name.
std::vector<Job> jobs_of(const CompressArgs& a, const BatchArgs& b) {
  std::vector<Job> jobs;
  for (const std::string& in : b.inputs) {
    if (in == "-") throw Error(kExitInput, "standard input ('-') cannot be one of several programs");
    if (!is_folder(in)) {
      jobs.push_back({in, "", utf8_string(utf8_path(in).filename()), 0});
      continue;
    }
    std::vector<Job> found;
    std::error_code ec;
    const fs::path root = utf8_path(in);
    for (fs::recursive_directory_iterator it(root, fs::directory_options::skip_permission_denied, ec), end;
         !ec && it != end; it.increment(ec)) {
      if (!it->is_regular_file(ec) || !is_gcode_name(it->path(), b.glob)) continue;
      found.push_back({utf8_string(it->path()), "", utf8_string(it->path().lexically_relative(root)), 0});
    }
    if (ec) throw Error(kExitIo, fmt::format("cannot read the folder '{}': {}", in, ec.message()));
    if (found.empty())
      throw Error(kExitInput, fmt::format("no G-code files in '{}' ({})", in,
                                          b.glob.empty() ? "by extension: .gcode, .nc, .ngc, .tap, ...; see --glob"
                                                         : "none matches --glob " + b.glob));
    std::sort(found.begin(), found.end(), [](const Job& x, const Job& y) { return x.relative < y.relative; });
    jobs.insert(jobs.end(), found.begin(), found.end());
  }
  // Where each goes: over itself, or under the output folder by its relative name.
  std::map<std::string, std::string> taken;  // output -> input
  for (Job& j : jobs) {
    j.output = a.in_place ? j.input : utf8_string(utf8_path(a.output) / utf8_path(j.relative));
    if (auto [at, fresh] = taken.emplace(j.output, j.input); !fresh)
      throw Error(kExitInput, fmt::format("'{}' and '{}' would both be written to '{}'", at->second, j.input, j.output));
    std::error_code ec;
    j.size = size_t(fs::file_size(utf8_path(j.input), ec));
    if (ec) j.size = 0;
  }
  return jobs;
}

std::string status_of(const FileReport& r) {
  switch (r.exit_code) {
    case kExitOk: return "ok";
    case kExitVerifyFailed: return "failed its check, not written";
    case kExitInput: return "cannot be read, not written";
    default: return "file error, not written";
  }
}

std::string summary_text(const std::vector<FileReport>& reports) {
  size_t width = 4;
  for (const FileReport& r : reports) width = std::max(width, r.input.size());
  std::string out = fmt::format("{:<{}}  {:>12}  {:>12}  {:>10}  {:>10}  {:>12}  {}\n", "file", width, "bytes in",
                                "bytes out", "blocks in", "blocks out", "max dev mm", "status");
  size_t in = 0, out_bytes = 0, ok = 0;
  for (const FileReport& r : reports) {
    const bool written = r.exit_code == kExitOk;
    out += fmt::format("{:<{}}  {:>12}  {:>12}  {:>10}  {:>10}  {:>12}  {}\n", r.input, width, r.bytes_in,
                       written ? fmt::format("{}", r.bytes_out) : "-", r.blocks_in,
                       written ? fmt::format("{}", r.blocks_out) : "-",
                       r.max_deviation_mm >= 0 ? fmt::format("{:.6f}", r.max_deviation_mm) : "-", status_of(r));
    in += r.bytes_in;
    if (written) out_bytes += r.bytes_out, ++ok;
  }
  out += fmt::format("{} of {} programs written; {} bytes in, {} bytes out of those written\n", ok, reports.size(), in,
                     out_bytes);
  return out;
}

std::string summary_json(const std::vector<FileReport>& reports, int exit_code) {
  std::string files;
  for (const FileReport& r : reports) {
    const bool written = r.exit_code == kExitOk;
    files += fmt::format(
        "{}\n    {{\"input\": {}, \"output\": {}, \"bytes_in\": {}, \"bytes_out\": {}, \"blocks_in\": {}, "
        "\"blocks_out\": {}, \"max_deviation_mm\": {}, \"written\": {}, \"exit_code\": {}, \"status\": {}}}",
        files.empty() ? "" : ",", json_string(r.input), json_string(r.output), r.bytes_in,
        written ? fmt::format("{}", r.bytes_out) : "null", r.blocks_in,
        written ? fmt::format("{}", r.blocks_out) : "null",
        r.max_deviation_mm >= 0 ? fmt::format("{:.6f}", r.max_deviation_mm) : "null", written, r.exit_code,
        json_string(status_of(r)));
  }
  return fmt::format("{{\n  \"files\": [{}\n  ],\n  \"exit_code\": {}\n}}\n", files, exit_code);
}

}  // namespace

bool is_batch(const std::vector<std::string>& inputs) {
  return inputs.size() > 1 || (inputs.size() == 1 && inputs[0] != "-" && is_folder(inputs[0]));
}

int run_batch(const CompressArgs& a, const BatchArgs& b) {
  // `arcpress in.nc out.nc`: a second name that is no program was meant for -o. (Elsewhere a
  // program that cannot be opened fails on its own, as any other.)
  std::error_code ec;
  if (b.inputs.size() == 2 && a.output.empty() && !a.in_place && !fs::exists(utf8_path(b.inputs[1]), ec))
    throw Error(kExitInput, fmt::format("no program '{}' to read; to write a file, use -o {}", b.inputs[1], b.inputs[1]));
  if (!a.in_place && a.output.empty())
    throw Error(kExitInput, "several programs, or a folder, are written with --in-place or -o FOLDER");
  if (a.in_place && !a.output.empty()) throw Error(kExitInput, "--in-place and -o cannot be used together");
  if (!a.in_place && !is_folder(a.output) && fs::exists(utf8_path(a.output)))
    throw Error(kExitInput, fmt::format("-o '{}' is a file: several programs are written into a folder", a.output));
  const std::vector<Job> jobs = jobs_of(a, b);
  std::vector<FileReport> reports(jobs.size());
  size_t total = 0;
  for (const Job& j : jobs) total += j.size;

  // Workers take the next program as each is done; the caller draws the one progress line
  // and prints each program's messages whole once it is done, so that none interleave.
  std::atomic<size_t> next{0}, read{0};
  std::mutex m;
  std::condition_variable cv;
  std::vector<size_t> finished;  // done, messages not yet printed
  auto work = [&] {
    for (size_t k; (k = next++) < jobs.size();) {
      const Job& j = jobs[k];
      FileReport& r = reports[k];
      CompressArgs one = a;
      one.input = j.input;
      one.output = a.in_place ? std::string() : j.output;
      one.opt.threads = 1;  // N programs at once take N threads, and N times one program's memory
      try {
        if (!a.in_place) {
          std::error_code made;
          fs::create_directories(utf8_path(j.output).parent_path(), made);
          if (made) throw Error(kExitIo, fmt::format("cannot make the folder for '{}': {}", j.output, made.message()));
        }
        r.exit_code = compress_file(one, r, &read);
      } catch (const Error& e) {
        r.log += fmt::format("arcpress: {}: {}\n", j.input, e.what());
        r.exit_code = e.exit_code();
      } catch (const std::exception& e) {
        r.log += fmt::format("arcpress: {}: internal error: {}\n", j.input, e.what());
        r.exit_code = kExitIo;
      }
      r.input = j.input;
      r.output = j.output;
      if (r.bytes_in == 0) r.bytes_in = j.size;  // (refused before it was read)
      {
        std::lock_guard lk(m);
        finished.push_back(k);
      }
      cv.notify_all();
    }
  };
  const size_t workers = worker_count(b.jobs, jobs.size());
  std::vector<PooledThread> pool;
  for (size_t w = 0; w < workers; ++w) pool.emplace_back(work);
  Progress progress(total, a.quiet, a.progress);
  for (size_t printed = 0; printed < jobs.size();) {
    std::vector<size_t> done;
    {
      std::unique_lock lk(m);
      cv.wait_for(lk, std::chrono::milliseconds(250), [&] { return !finished.empty(); });
      done.swap(finished);
    }
    for (size_t k : done) {
      const FileReport& r = reports[k];
      if (r.log.empty()) continue;
      progress.clear();
      std::fputs(r.exit_code == kExitOk ? r.log.c_str() : (r.log + fmt::format("arcpress: {}: {}\n", r.input, status_of(r))).c_str(),
                 stderr);
    }
    printed += done.size();
    progress.update(read);
  }
  for (auto& t : pool) t.join();
  progress.clear();
  int code = kExitOk;
  for (const FileReport& r : reports) code = std::max(code, r.exit_code);
  write_stdout(b.json ? summary_json(reports, code) : summary_text(reports));
  return code;
}

}  // namespace arcpress::cli
