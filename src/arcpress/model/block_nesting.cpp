// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/model/block_nesting.hpp"

#include <algorithm>

namespace arcpress {

BlockNesting::Join BlockNesting::line(std::string_view line) {
  // RepRapFirmware's StringParser::Put(): a space adds 1, a tab moves on to the next multiple
  // of 4; a line with nothing after its blanks is skipped, so is an indented `;` comment.
  uint32_t indent = 0;
  size_t i = 0;
  for (; i < line.size() && (line[i] == ' ' || line[i] == '\t'); ++i) indent = line[i] == ' ' ? indent + 1 : (indent + 4) & ~3u;
  if (i == line.size() || line[i] == '\r' || (indent > 0 && line[i] == ';')) return {};
  const uint16_t d = uint16_t(std::min<uint32_t>(indent, UINT16_MAX));
  Join j;
  if (d < last_indent) {
    uint8_t closed = 0;
    while (depth > 0 && levels[depth - 1].indent > d) {
      closed |= levels[depth - 1].changed;  // (the outer level's holds the inner's)
      levels[--depth] = Level{};
    }
    j.position = (closed & kMoved) != 0;
    j.distance = (closed & kDistance) != 0;
  }
  if (d > (depth > 0 ? levels[depth - 1].indent : 0)) {
    if (depth < kMostLevels)
      levels[depth++] = Level{d, 0};
    else
      levels[depth - 1].indent = d;  // merged: it keeps what changed since the outer block began
  }
  last_indent = d;
  return j;
}

}  // namespace arcpress
