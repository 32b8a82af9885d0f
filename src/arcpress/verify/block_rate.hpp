// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The block rate a program demands: how many blocks, and how many bytes of them, a
// controller and the link to it must take per second while it cuts, at the programmed feeds.
//
// Each feed move (G1, G2, G3) whose path is known is one block, lasting its path length
// divided by its feed; acceleration is ignored, so the figures are those of a machine that
// reaches every programmed feed at once: an upper bound on what it really demands. Rapids,
// dwells and the blocks that do not move are not timed. Moves in inverse time (G93) or
// without a feed are left out and counted.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "arcpress/lex/block.hpp"
#include "arcpress/model/move.hpp"

namespace arcpress {

/// One block of cutting: its time at the programmed feed, and its bytes as written (with
/// its end of line).
struct TimedBlock {
  double seconds = 0;
  uint32_t bytes = 0;
};

/// The cutting blocks of `in` (read from `p`) in order, appended to `out`; returns how many
/// feed moves were left out (no feed, inverse time, unknown path).
size_t timed_blocks(const Program& p, const Interpretation& in, std::vector<TimedBlock>& out);

/// What a program demands over any 1 s of cutting. The window starts at every instant t of
/// the cutting timeline and holds the blocks that start in [t, t + 1 s); the peak is its
/// largest content, the 95th percentile the content that 95 % of the window's start times
/// do not exceed. A program that cuts for less than a second is one window.
struct BlockRate {
  double cutting_s = 0;         ///< cutting time at the programmed feeds
  size_t blocks = 0;            ///< timed blocks
  size_t untimed = 0;           ///< feed moves left out (no feed, G93, unknown path)
  double peak_blocks_per_s = 0, p95_blocks_per_s = 0;
  double peak_bytes_per_s = 0, p95_bytes_per_s = 0;
  /// Share of the cutting time (of the window's start times) in which the dialect's
  /// max_blocks_per_s, or link_bytes_per_s, is exceeded; < 0 where it sets none.
  double over_blocks_share = -1, over_link_share = -1;
  double max_blocks_per_s = 0, link_bytes_per_s = 0;  ///< the limits measured against (0: none)
};

/// Measures a program's timed blocks as they come, in order, in memory bounded by the
/// blocks of one second (a streamed program is measured piece by piece).
class BlockRateMeter {
 public:
  /// The dialect's limits (0: none).
  BlockRateMeter(double max_blocks_per_s, double link_bytes_per_s);
  void add(const TimedBlock& b);
  void add_untimed(size_t n) { untimed_ += n; }
  BlockRate finish();

 private:
  /// Moves the window's start to `t`, adding the time it spent at its content.
  void advance(double t);

  double max_blocks_per_s_, link_bytes_per_s_;
  double end_s_ = 0;      ///< the cutting time so far: the next block starts here
  double cursor_s_ = 0;   ///< the window's start, swept so far
  size_t blocks_ = 0, untimed_ = 0;
  uint64_t in_window_bytes_ = 0;
  std::deque<std::pair<double, uint32_t>> window_;  ///< (start, bytes) of the blocks in the window
  /// Time the window held each content: blocks exactly, bytes to three significant digits
  /// (so that the table stays small however long the program).
  std::map<uint64_t, double> blocks_time_, bytes_time_;
  double over_blocks_s_ = 0, over_link_s_ = 0;  ///< time above the limits
};

/// One line: "peak 1480 blocks/s (95 %: 1210), 31400 bytes/s (95 %: 25800) over 812.3 s of
/// cutting", with the shares over the limits where set ("link 11520 bytes/s exceeded 62.1 %
/// of it").
std::string block_rate_text(const BlockRate& r);

/// As a JSON object: cutting_s, blocks, untimed_feed_moves, peak_blocks_per_s,
/// p95_blocks_per_s, peak_bytes_per_s, p95_bytes_per_s, over_max_blocks_share and
/// over_link_share (null where the dialect sets no limit).
std::string block_rate_json(const BlockRate& r);

/// The block rate of a whole program.
BlockRate block_rate(const Program& p, const Interpretation& in, double max_blocks_per_s, double link_bytes_per_s);

}  // namespace arcpress
