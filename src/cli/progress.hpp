// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Progress of a long run on a terminal: bytes read, share of the input, rate and time left,
// on one line of standard error rewritten a few times a second and erased at the end.
#include <chrono>
#include <cstddef>
#include <optional>

namespace arcpress::cli {

class Progress {
 public:
  /// Shown when `forced`, or when standard error is a terminal and not `quiet`; then only
  /// once the input proves bigger than kShownFromBytes (`total`, where known, says so at once).
  Progress(std::optional<size_t> total, bool quiet, bool forced);
  ~Progress();
  /// The input read so far.
  void update(size_t bytes);
  /// Erases the line, if one was drawn.
  void clear();

  /// Inputs smaller than this finish too fast for a progress line to help.
  static constexpr size_t kShownFromBytes = size_t(4) << 20;

 private:
  using Clock = std::chrono::steady_clock;
  std::optional<size_t> total_;
  bool enabled_ = false;
  bool drawn_ = false;
  Clock::time_point start_, last_;
};

}  // namespace arcpress::cli
