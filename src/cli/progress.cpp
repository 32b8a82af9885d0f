// SPDX-License-Identifier: GPL-3.0-or-later
#include "progress.hpp"

#include "console.hpp"

#include <cstdio>
#include <string>

#include <fmt/format.h>

namespace arcpress::cli {
namespace {

/// Time between two redraws.
constexpr std::chrono::milliseconds kRedraw{250};

std::string megabytes(size_t bytes) { return fmt::format("{:.1f} MB", double(bytes) / 1e6); }

}  // namespace

Progress::Progress(std::optional<size_t> total, bool quiet, bool forced)
    : total_(total), enabled_(forced || (!quiet && is_terminal(2))), start_(Clock::now()),
      last_(start_ - kRedraw) {}  // the first line is drawn as soon as the input is big enough

Progress::~Progress() { clear(); }

void Progress::update(size_t bytes) {
  if (!enabled_) return;
  const auto now = Clock::now();
  if (now - last_ < kRedraw) return;
  if (bytes < kShownFromBytes && !(total_ && *total_ >= kShownFromBytes)) return;
  last_ = now;
  const double seconds = std::chrono::duration<double>(now - start_).count();
  const double rate = seconds > 0 ? double(bytes) / seconds : 0;
  std::string line = fmt::format("arcpress: {}", megabytes(bytes));
  if (total_ && *total_ > 0) {
    line += fmt::format(" of {} ({:.0f} %)", megabytes(*total_), 100.0 * double(bytes) / double(*total_));
  }
  line += fmt::format(", {:.1f} MB/s", rate / 1e6);
  if (total_ && rate > 0 && *total_ > bytes) line += fmt::format(", {:.0f} s left", double(*total_ - bytes) / rate);
  std::fprintf(stderr, "\r\033[K%s", line.c_str());
  std::fflush(stderr);
  drawn_ = true;
}

void Progress::clear() {
  if (!drawn_) return;
  std::fputs("\r\033[K", stderr);
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace arcpress::cli
