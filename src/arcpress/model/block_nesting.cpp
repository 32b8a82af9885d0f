// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/model/block_nesting.hpp"

#include <algorithm>

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

BlockNesting::Join BlockNesting::line(std::string_view line, bool opens) {
  const int32_t indent = indent_of(line);
  if (indent < 0) return {};
  const uint16_t d = uint16_t(indent);
  Join j;
  if (d < last_indent) {
    uint8_t closed = 0;
    while (depth > 0 && levels[depth - 1].indent > d) {
      if (!levels[depth - 1].plain) closed |= levels[depth - 1].changed;  // (an outer level's holds the inner's)
      levels[--depth] = Level{};
    }
    j.position = (closed & kMoved) != 0;
    j.distance = (closed & kDistance) != 0;
  }
  if (d > (depth > 0 ? levels[depth - 1].indent : 0)) {
    if (depth < kMostLevels)
      levels[depth++] = Level{d, 0, false, 0, !last_opens};
    else  // merged: it keeps what changed since the outer block began, and is a block where either is
      levels[depth - 1].indent = d, levels[depth - 1].plain = levels[depth - 1].plain && !last_opens;
  }
  last_indent = d;
  last_opens = opens;
  return j;
}

void BlockNesting::open(uint32_t label, bool do_loop) {
  if (depth < kMostLevels)
    levels[depth++] = Level{0, 0, do_loop, label};
  else
    levels[depth - 1].label = label, levels[depth - 1].do_loop = do_loop;  // merged, as in line()
}

BlockNesting::Join BlockNesting::close(uint32_t label) {
  uint32_t k = depth;
  while (k > 0 && levels[k - 1].label != label) --k;
  if (k == 0) {
    // Not open (a block past kMostLevels, merged): whatever the innermost block changed.
    if (depth == 0) return {};
    k = depth;
  }
  const uint8_t closed = levels[k - 1].changed;  // (the outer level's holds the inner's)
  while (depth >= k) levels[--depth] = Level{};
  return {(closed & kMoved) != 0, (closed & kDistance) != 0};
}

}  // namespace arcpress
