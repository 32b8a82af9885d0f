// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/verify/block_rate.hpp"

#include <fmt/format.h>

#include <cmath>

#include "arcpress/verify/move_geometry.hpp"

namespace arcpress {
namespace {

/// `v` rounded down to three significant digits.
uint64_t three_digits(uint64_t v) {
  uint64_t scale = 1;
  while (v / scale >= 1000) scale *= 10;
  return v / scale * scale;
}

/// The value that `share` of the time does not exceed, from (value -> time).
double percentile(const std::map<uint64_t, double>& time_at, double share) {
  double total = 0;
  for (const auto& [v, t] : time_at) total += t;
  double seen = 0;
  for (const auto& [v, t] : time_at) {
    seen += t;
    if (seen >= share * total) return double(v);
  }
  return time_at.empty() ? 0 : double(time_at.rbegin()->first);
}

}  // namespace

size_t timed_blocks(const Program& p, const Interpretation& in, std::vector<TimedBlock>& out) {
  size_t untimed = 0;
  for (size_t i = 0; i < in.moves.size(); ++i) {
    const Move& m = in.moves[i];
    if (!is_feed(m.kind)) continue;
    if (!m.known || m.feed_mm_min <= 0 || in.frames[m.frame].inverse_time) {
      ++untimed;
      continue;
    }
    double length_mm = 0;
    if (is_arc(m.kind)) {
      const ArcGeom g = arc_of_move(in, i);
      length_mm = std::hypot(g.radius_mm * std::abs(g.sweep), g.h1 - g.h0);
    } else {
      const AxisValues& a = in.from(i);
      length_mm = (m.xyz() - Vec3(a[kX], a[kY], a[kZ])).norm();
    }
    const Block& b = p.blocks[m.block];
    out.push_back({length_mm / (m.feed_mm_min / 60.0), uint32_t(p.raw(b).size() + p.eol(b).size())});
  }
  return untimed;
}

BlockRateMeter::BlockRateMeter(double max_blocks_per_s, double link_bytes_per_s)
    : max_blocks_per_s_(max_blocks_per_s), link_bytes_per_s_(link_bytes_per_s) {}

void BlockRateMeter::advance(double t) {
  if (t <= cursor_s_) return;
  const double dt = t - cursor_s_;
  blocks_time_[window_.size()] += dt;
  bytes_time_[three_digits(in_window_bytes_)] += dt;
  if (max_blocks_per_s_ > 0 && double(window_.size()) > max_blocks_per_s_) over_blocks_s_ += dt;
  if (link_bytes_per_s_ > 0 && double(in_window_bytes_) > link_bytes_per_s_) over_link_s_ += dt;
  cursor_s_ = t;
}

void BlockRateMeter::add(const TimedBlock& b) {
  // The window, starting at t, holds the blocks that start in [t, t + 1 s): this one from
  // t = its start - 1 s on, each before it until t passes its start.
  const double start = end_s_, enters = start - 1;
  while (!window_.empty() && window_.front().first < enters) {
    advance(window_.front().first);
    in_window_bytes_ -= window_.front().second;
    window_.pop_front();
  }
  advance(enters);
  window_.emplace_back(start, b.bytes);
  in_window_bytes_ += b.bytes;
  end_s_ += b.seconds;
  ++blocks_;
}

BlockRate BlockRateMeter::finish() {
  BlockRate r;
  r.max_blocks_per_s = max_blocks_per_s_;
  r.link_bytes_per_s = link_bytes_per_s_;
  r.cutting_s = end_s_;
  r.blocks = blocks_;
  r.untimed = untimed_;
  const double last_start = end_s_ - 1;  // the last window ends with the cutting
  if (last_start <= 0) {
    // Under a second of cutting: one window, holding every block.
    r.peak_blocks_per_s = r.p95_blocks_per_s = double(window_.size());
    r.peak_bytes_per_s = r.p95_bytes_per_s = double(in_window_bytes_);
    if (max_blocks_per_s_ > 0) r.over_blocks_share = r.peak_blocks_per_s > max_blocks_per_s_ ? 1 : 0;
    if (link_bytes_per_s_ > 0) r.over_link_share = r.peak_bytes_per_s > link_bytes_per_s_ ? 1 : 0;
    return r;
  }
  while (!window_.empty() && window_.front().first < last_start) {
    advance(window_.front().first);
    in_window_bytes_ -= window_.front().second;
    window_.pop_front();
  }
  advance(last_start);
  r.peak_blocks_per_s = blocks_time_.empty() ? 0 : double(blocks_time_.rbegin()->first);
  r.peak_bytes_per_s = bytes_time_.empty() ? 0 : double(bytes_time_.rbegin()->first);
  r.p95_blocks_per_s = percentile(blocks_time_, 0.95);
  r.p95_bytes_per_s = percentile(bytes_time_, 0.95);
  if (max_blocks_per_s_ > 0) r.over_blocks_share = over_blocks_s_ / last_start;
  if (link_bytes_per_s_ > 0) r.over_link_share = over_link_s_ / last_start;
  return r;
}

BlockRate block_rate(const Program& p, const Interpretation& in, double max_blocks_per_s, double link_bytes_per_s) {
  std::vector<TimedBlock> timed;
  const size_t untimed = timed_blocks(p, in, timed);
  BlockRateMeter meter(max_blocks_per_s, link_bytes_per_s);
  for (const TimedBlock& b : timed) meter.add(b);
  meter.add_untimed(untimed);
  return meter.finish();
}

std::string block_rate_text(const BlockRate& r) {
  std::string t = fmt::format("peak {:.0f} blocks/s (95 %: {:.0f}), {:.0f} bytes/s (95 %: {:.0f}) over {:.1f} s of cutting",
                              r.peak_blocks_per_s, r.p95_blocks_per_s, r.peak_bytes_per_s, r.p95_bytes_per_s,
                              r.cutting_s);
  if (r.over_blocks_share >= 0)
    t += fmt::format("; {:.0f} blocks/s exceeded {:.1f} % of it", r.max_blocks_per_s, 100 * r.over_blocks_share);
  if (r.over_link_share >= 0)
    t += fmt::format("; link {:.0f} bytes/s exceeded {:.1f} % of it", r.link_bytes_per_s, 100 * r.over_link_share);
  if (r.untimed > 0) t += fmt::format(" ({} feed moves without a feed or in inverse time not timed)", r.untimed);
  return t;
}

std::string block_rate_json(const BlockRate& r) {
  auto share = [](double s) { return s >= 0 ? fmt::format("{:.6f}", s) : std::string("null"); };
  return fmt::format(
      "{{\"cutting_s\": {:.6f}, \"blocks\": {}, \"untimed_feed_moves\": {}, \"peak_blocks_per_s\": {:.0f}, "
      "\"p95_blocks_per_s\": {:.0f}, \"peak_bytes_per_s\": {:.0f}, \"p95_bytes_per_s\": {:.0f}, "
      "\"over_max_blocks_share\": {}, \"over_link_share\": {}}}",
      r.cutting_s, r.blocks, r.untimed, r.peak_blocks_per_s, r.p95_blocks_per_s, r.peak_bytes_per_s,
      r.p95_bytes_per_s, share(r.over_blocks_share), share(r.over_link_share));
}

}  // namespace arcpress
