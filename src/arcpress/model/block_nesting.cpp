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

namespace {

/// Whether `line`, after its blanks, is RepRapFirmware's `while`.
bool is_while(std::string_view line) {
  const size_t at = line.find_first_not_of(" \t");
  if (at == std::string_view::npos || line.substr(at, 5) != "while") return false;
  return at + 5 == line.size() || line[at + 5] == ' ' || line[at + 5] == '\t' || line[at + 5] == '\r';
}

}  // namespace

BlockNesting::Join BlockNesting::line(std::string_view line, bool opens, uint8_t mode) {
  const int32_t indent = indent_of(line);
  if (indent < 0) return {};
  const uint16_t d = uint16_t(indent);
  Join j;
  if (d < last_indent) {
    uint8_t closed = 0;
    while (depth > 0 && levels[depth - 1].indent > d) {
      if (!levels[depth - 1].plain) closed |= levels[depth - 1].changed;  // (an outer level's holds the inner's)
      j.loop_modes = j.loop_modes || runs_again_otherwise(levels[depth - 1], mode);
      levels[--depth] = Level{};
    }
    j.position = (closed & kMoved) != 0;
    j.distance = (closed & kDistance) != 0;
  }
  if (d > (depth > 0 ? levels[depth - 1].indent : 0)) {
    if (depth < kMostLevels)
      levels[depth++] = Level{d, 0, false, 0, !last_opens, uint8_t(last_loops ? 1 + mode : 0)};
    else  // merged: it keeps what changed since the outer block began, and is a block where either is
      levels[depth - 1].indent = d, levels[depth - 1].plain = levels[depth - 1].plain && !last_opens;
  }
  last_indent = d;
  last_opens = opens;
  last_loops = opens && is_while(line);
  return j;
}

void BlockNesting::open(uint32_t label, bool do_loop, bool loop, uint8_t mode) {
  if (depth < kMostLevels)
    levels[depth++] = Level{0, 0, do_loop, label, false, uint8_t(loop ? 1 + mode : 0)};
  else
    levels[depth - 1].label = label, levels[depth - 1].do_loop = do_loop;  // merged, as in line()
}

BlockNesting::Join BlockNesting::close(uint32_t label, uint8_t mode) {
  uint32_t k = depth;
  while (k > 0 && levels[k - 1].label != label) --k;
  if (k == 0) {
    // Not open (a block past kMostLevels, merged): whatever the innermost block changed.
    if (depth == 0) return {};
    k = depth;
  }
  const uint8_t closed = levels[k - 1].changed;  // (the outer level's holds the inner's)
  bool loop_modes = false;
  for (uint32_t at = k - 1; at < depth; ++at) loop_modes = loop_modes || runs_again_otherwise(levels[at], mode);
  while (depth >= k) levels[--depth] = Level{};
  return {(closed & kMoved) != 0, (closed & kDistance) != 0, loop_modes};
}

bool BlockNesting::runs_again_otherwise(const Level& l, uint8_t mode) {
  return l.loop != 0 && (l.changed & kEarly) && (mode != l.loop - 1 || mode == kUnknownMode);
}

const char* BlockNesting::loop_modes_problem() {
  return "a loop ends here in another distance mode (G90 or G91) than the one the moves at its start, before its "
         "first G90 or G91, were read in: run again, they read their words otherwise; state G90 or G91 at the "
         "loop's start";
}

}  // namespace arcpress
