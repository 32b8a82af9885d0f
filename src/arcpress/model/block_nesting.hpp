// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The blocks a program's leading blanks open and close, where they have a meaning
// (Dialect::indented_blocks: RepRapFirmware 3's conditional G-code, whose `if`, `elif`,
// `else` and `while` run the lines indented below them). A line indented less than the
// line before it ends those blocks, and is entered both from where they end and from where
// they began: an `if` not taken, an `else` skipped, a `while` run no more or not at all, a
// `break`. What any line between may have changed is not known there. LinuxCNC's O-word
// blocks (`o101 if` .. `o101 endif`, `while`, `do`, `repeat`) are such blocks too, opened and
// closed by their lines instead of by blanks. A loop (`while`, `do`, `repeat`) also runs its
// first lines again in the distance mode its last leave.
#include <array>
#include <cstdint>
#include <string_view>

namespace arcpress {

struct BlockNesting {
  /// What may differ at a line entered from both ends of the blocks it closes.
  struct Join {
    bool position = false;  ///< a move, or a change of the known axes, frame or offsets
    bool distance = false;  ///< G90 or G91 (or whether it is known)
    /// A loop closes whose lines before its first G90 or G91 moved, and which leaves another
    /// distance mode than the one they were read in: run again, they read their words otherwise.
    bool loop_modes = false;
  };
  /// The distance mode, as line() and open() take it.
  static constexpr uint8_t kAbsolute = 0, kIncremental = 1, kUnknownMode = 2;
  static uint8_t mode_of(bool absolute, bool unknown) { return unknown ? kUnknownMode : absolute ? kAbsolute : kIncremental; }

  /// Reads the leading blanks of `line` (a block's raw text) before the block is read:
  /// what may differ at it where it closes blocks. Blank lines and indented comment lines
  /// open and close nothing (the firmware skips them); a line's tab moves its indent to the
  /// next multiple of 4, as the firmware counts. `opens`: the line is flow control (`if`,
  /// `else`, `while`, or any line the interpreter does not read as code), whose deeper lines
  /// are its block; lines indented deeper after any other line are a plain block, which runs
  /// once, in order, and whose end joins nothing. A `while`'s block is a loop. `mode`: the
  /// distance mode before the line.
  Join line(std::string_view line, bool opens, uint8_t mode = kAbsolute);
  /// An O-word block labelled `label` opens (`do_loop`: a `do`, which a `while` ends; `loop`: a
  /// loop, entered in distance mode `mode`).
  void open(uint32_t label, bool do_loop, bool loop = false, uint8_t mode = kAbsolute);
  /// The O-word block labelled `label` ends (and those opened in it), in distance mode `mode`:
  /// what may differ after it. Where none is open with that label, nothing is known to end.
  Join close(uint32_t label, uint8_t mode = kAbsolute);
  /// Whether the innermost open block is a `do` labelled `label`.
  bool in_do(uint32_t label) const { return depth > 0 && levels[depth - 1].label == label && levels[depth - 1].do_loop; }
  /// The indent of `line` as the firmware counts it (a space 1, a tab to the next multiple of
  /// 4), or -1 where the line counts for nothing (blank, or an indented `;` comment).
  static int32_t indent_of(std::string_view line);
  /// After a block: what it changed, for every block open around it; whether it moved, and
  /// whether it stated G90 or G91 (which holds for the rest of the innermost block).
  void changed(bool position, bool distance, bool moved = false, bool stated = false) {
    const uint8_t bits = uint8_t((position ? kMoved : 0) | (distance ? kDistance : 0));
    if (stated && depth > 0) levels[depth - 1].changed |= kStated;
    for (uint32_t k = 0; k < depth; ++k)
      levels[k].changed |= uint8_t(bits | (moved && !(levels[k].changed & kStated) ? kEarly : 0));
  }

  bool operator==(const BlockNesting&) const = default;

  /// kMoved, kDistance: what the block's lines changed; kStated: one of its own lines stated
  /// G90 or G91; kEarly: a line moved before that.
  static constexpr uint8_t kMoved = 1, kDistance = 2, kStated = 4, kEarly = 8;
  /// Blocks open more deeply than this are merged into the deepest one kept, which
  /// joins at least where they would.
  static constexpr uint32_t kMostLevels = 8;
  struct Level {
    uint16_t indent = 0;
    uint8_t changed = 0;  ///< kMoved | kDistance | kStated | kEarly since the level's first line
    bool do_loop = false;
    uint32_t label = 0;   ///< an O-word block's (OWord::label); 0 for a block of blanks
    bool plain = false;   ///< deeper blanks after a line that is no flow control (line())
    uint8_t loop = 0;     ///< a loop's: 1 + the distance mode it was entered in; 0 no loop
    bool operator==(const Level&) const = default;
  };
  /// What is said where a loop closes whose lines run again otherwise than read (Join::loop_modes).
  static const char* loop_modes_problem();
  /// Whether loop `l`, ending in distance mode `mode`, runs lines read in another again.
  static bool runs_again_otherwise(const Level& l, uint8_t mode);
  std::array<Level, kMostLevels> levels{};
  uint32_t depth = 0;        ///< levels open (indented past 0)
  uint16_t last_indent = 0;  ///< of the last line read that counts
  bool last_opens = false;   ///< that line is flow control
  bool last_loops = false;   ///< that line is a `while`
};

}  // namespace arcpress
