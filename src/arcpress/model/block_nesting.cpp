// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/model/block_nesting.hpp"

#include <algorithm>

#include "arcpress/model/subroutines.hpp"

namespace arcpress {

int32_t BlockNesting::indent_of(std::string_view line) {
  // RepRapFirmware's StringParser::Put(): a space adds 1, a tab moves on to the next multiple
  // of 4; a line with nothing after its blanks is skipped, so is an indented `;` comment.
  uint32_t indent = 0;
  size_t i = 0;
  for (; i < line.size() && (line[i] == ' ' || line[i] == '\t'); ++i) indent = line[i] == ' ' ? indent + 1 : (indent + 4) & ~3u;
  if (i == line.size() || line[i] == '\r' || (indent > 0 && line[i] == ';')) return -1;
  return int32_t(std::min<uint32_t>(indent, UINT16_MAX));
}

namespace {

/// Whether `line`, after its blanks, is RepRapFirmware's keyword `word` (`while`, `continue`).
bool is_keyword(std::string_view line, std::string_view word) {
  const size_t at = line.find_first_not_of(" \t");
  if (at == std::string_view::npos || line.substr(at, word.size()) != word) return false;
  const size_t end = at + word.size();
  return end == line.size() || line[end] == ' ' || line[end] == '\t' || line[end] == '\r';
}

}  // namespace

uint8_t BlockNesting::differing(const Modes& a, const Modes& b) {
  return uint8_t((a.plane != b.plane ? kStatesPlane : 0) | (a.units != b.units ? kStatesUnits : 0) |
                 (a.distance != b.distance ? kStatesDistance : 0) | (a.motion != b.motion ? kStatesMotion : 0) |
                 (a.extrusion != b.extrusion ? kStatesExtrusion : 0) |
                 ((a.unstated ^ b.unstated) & (kStatesPlane | kStatesUnits)));
}

bool BlockNesting::leaves_block(std::string_view line) { return is_keyword(line, "break") || is_keyword(line, "continue"); }

BlockNesting::Join BlockNesting::line(std::string_view line, bool opens, uint32_t line_number, const Modes& now) {
  const int32_t indent = indent_of(line);
  if (indent < 0) return {};
  const uint16_t d = uint16_t(indent);
  Join j;
  if (d < last_indent) {
    uint8_t closed = 0;
    while (depth > 0 && levels[depth - 1].indent > d) {
      if (!levels[depth - 1].plain)
        closed |= uint8_t(levels[depth - 1].changed | differing(levels[depth - 1].at_open, now) << 1);
      j.back_to(levels[depth - 1].loop);
      levels[--depth] = Level{};
    }
    j.position = (closed & kMoved) != 0;
    j.modes = uint8_t(closed >> 1);
  }
  if (d > (depth > 0 ? levels[depth - 1].indent : 0)) {
    if (depth < kMostLevels) {
      const uint32_t loop = last_loop ? ++loops : 0;
      levels[depth++] = Level{d, 0, false, 0, !last_opens, loop, now};
      j.loop_entered = loop, j.loop_line = last_loop;
    } else {  // merged: it keeps what changed since the outer block began, and is a block where either is
      levels[depth - 1].indent = d, levels[depth - 1].plain = levels[depth - 1].plain && !last_opens;
      j.loop_unfollowed = last_loop != 0;
    }
  }
  if (opens && is_keyword(line, "continue")) j.back_to(loop_of(0));
  last_indent = d;
  last_opens = opens;
  last_loop = opens && is_keyword(line, "while") ? line_number : 0;
  return j;
}

uint32_t BlockNesting::open(uint32_t label, bool do_loop, bool loop, const Modes& now) {
  if (depth == kMostLevels) {
    levels[depth - 1].label = label, levels[depth - 1].do_loop = do_loop;  // merged, as in line()
    return loop ? kUnfollowed : 0;
  }
  const uint32_t number = loop ? ++loops : 0;
  levels[depth++] = Level{0, 0, do_loop, label, false, number, now};
  return number;
}

BlockNesting::Join BlockNesting::close(uint32_t label, const Modes& now) {
  uint32_t k = depth;
  while (k > 0 && levels[k - 1].label != label) --k;
  if (k == 0) {
    // Not open (a block past kMostLevels, merged): whatever the innermost block changed.
    if (depth == 0) return {};
    k = depth;
  }
  Join j;
  uint8_t closed = 0;
  for (uint32_t at = k - 1; at < depth; ++at) closed |= uint8_t(levels[at].changed | differing(levels[at].at_open, now) << 1);
  j.position = (closed & kMoved) != 0;
  j.modes = uint8_t(closed >> 1);
  for (uint32_t at = depth; at-- > k - 1;) j.back_to(levels[at].loop);
  while (depth >= k) levels[--depth] = Level{};
  return j;
}

uint32_t BlockNesting::loop_of(uint32_t label) const {
  for (uint32_t k = depth; k-- > 0;)
    if (levels[k].loop != 0 && (label == 0 || levels[k].label == label)) return levels[k].loop;
  return 0;
}

}  // namespace arcpress
