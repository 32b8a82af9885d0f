// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The blocks a program's leading blanks open and close, where they have a meaning
// (Dialect::indented_blocks: RepRapFirmware 3's conditional G-code, whose `if`, `elif`,
// `else` and `while` run the lines indented below them). A line indented less than the
// line before it ends those blocks, and is entered both from where they end and from where
// they began: an `if` not taken, an `else` skipped, a `while` run no more or not at all, a
// `break`. What any line between may have changed is not known there.
#include <array>
#include <cstdint>
#include <string_view>

namespace arcpress {

struct BlockNesting {
  /// What may differ at a line entered from both ends of the blocks it closes.
  struct Join {
    bool position = false;  ///< a move, or a change of the known axes, frame or offsets
    bool distance = false;  ///< G90 or G91 (or whether it is known)
  };

  /// Reads the leading blanks of `line` (a block's raw text) before the block is read:
  /// what may differ at it where it closes blocks. Blank lines and indented comment lines
  /// open and close nothing (the firmware skips them); a line's tab moves its indent to the
  /// next multiple of 4, as the firmware counts.
  Join line(std::string_view line);
  /// After a block: what it changed, for every block open around it.
  void changed(bool position, bool distance) {
    const uint8_t bits = uint8_t((position ? kMoved : 0) | (distance ? kDistance : 0));
    for (uint32_t k = 0; k < depth; ++k) levels[k].changed |= bits;
  }

  bool operator==(const BlockNesting&) const = default;

  static constexpr uint8_t kMoved = 1, kDistance = 2;
  /// Blocks open more deeply than this are merged into the deepest one kept, which
  /// joins at least where they would.
  static constexpr uint32_t kMostLevels = 24;
  struct Level {
    uint16_t indent = 0;
    uint8_t changed = 0;  ///< kMoved | kDistance since the level's first line
    bool operator==(const Level&) const = default;
  };
  std::array<Level, kMostLevels> levels{};
  uint32_t depth = 0;        ///< levels open (indented past 0)
  uint16_t last_indent = 0;  ///< of the last line read that counts
};

}  // namespace arcpress
