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
// first lines again in the modes its last leave: its start is an entry, and its end (or a
// `continue`) a jump back to it (model/jump_entries.hpp), both named by the loop's number:
// how many loops the program opened up to it, which an output, whose lines are others' but
// whose flow control is the input's, numbers alike.
// The modes after a block are known where they are the same on every way out of it: where it
// began, where it ends, and at every line of flow control in it (a `break`, a `return`).
#include <array>
#include <cstdint>
#include <string_view>

namespace arcpress {

struct BlockNesting {
  /// Blocks open more deeply than this are merged into the deepest one kept, which
  /// joins at least where they would.
  static constexpr uint32_t kMostLevels = 8;
  /// The modes a block's ways out are compared in (ModalState::modes()).
  struct Modes {
    uint8_t plane = 0;
    uint8_t units = 0;     ///< 1: mm; 2: inch
    uint8_t distance = 0;  ///< 1: G90; 2: G91; 3: not known
    uint8_t unstated = 0;  ///< kStatesPlane, kStatesUnits not known (ModalState::unstated)
    int16_t motion = 0;    ///< ModalState::motion
    uint8_t extrusion = 0;  ///< 1: E words are places (M82); 2: increments (M83); 3: not known
    bool operator==(const Modes&) const = default;
  };
  /// kStates* (model/subroutines.hpp) of the modes that differ between `a` and `b`.
  static uint8_t differing(const Modes& a, const Modes& b);

  /// What may differ at a line entered from both ends of the blocks it closes.
  struct Join {
    bool position = false;  ///< a move, or a change of the known axes, frame or offsets
    /// kStates* (model/subroutines.hpp) of the modes a line in the blocks changed: G90 or G91
    /// (or whether it is known), the plane, the units, the modal motion, E's mode.
    uint8_t modes = 0;
    /// The loops that jump back from here to their start, by their numbers: those that end,
    /// innermost first, or the one a `continue` runs again.
    std::array<uint32_t, kMostLevels> loops_back{};
    uint8_t loops_back_count = 0;
    /// The loop whose first lines begin after this line, by its number (0: none), and the
    /// line that opens it.
    uint32_t loop_entered = 0, loop_line = 0;
    /// A loop begins after this line past kMostLevels, whose end is not followed: its first
    /// lines are read with their modes not known, as a loop found to run them otherwise is.
    bool loop_unfollowed = false;
    /// Adds loop `loop` (a line; 0: none) to those this jumps back to.
    void back_to(uint32_t loop) {
      if (loop != 0 && loops_back_count < loops_back.size()) loops_back[loops_back_count++] = loop;
    }
  };

  /// Reads the leading blanks of `line` (a block's raw text) before the block is read:
  /// what may differ at it where it closes blocks. Blank lines and indented comment lines
  /// open and close nothing (the firmware skips them); a line's tab moves its indent to the
  /// next multiple of 4, as the firmware counts. `opens`: the line is flow control (`if`,
  /// `else`, `while`, or any line the interpreter does not read as code), whose deeper lines
  /// are its block; lines indented deeper after any other line are a plain block, which runs
  /// once, in order, and whose end joins nothing. A `while`'s block is a loop; a `continue`
  /// in one runs it again. `line_number`: the line's; `now`: the modes before it.
  Join line(std::string_view line, bool opens, uint32_t line_number, const Modes& now);
  /// An O-word block labelled `label` opens in modes `now` (`do_loop`: a `do`, which a
  /// `while` ends; `loop`: it is a loop). Returns the loop's number (0: no loop;
  /// kUnfollowed: one past kMostLevels, whose end is not followed).
  uint32_t open(uint32_t label, bool do_loop, bool loop, const Modes& now);
  static constexpr uint32_t kUnfollowed = UINT32_MAX;
  /// The O-word block labelled `label` ends (and those opened in it), in modes `now`: what may
  /// differ after it. Where none is open with that label, nothing is known to end.
  Join close(uint32_t label, const Modes& now);
  /// A line of flow control that may leave the open blocks (a `break`, a `return`, a `GOTO`:
  /// any, to be sure) is read in modes `now`.
  void way_out(const Modes& now) {
    for (uint32_t k = 0; k < depth; ++k)
      if (!levels[k].plain) levels[k].changed |= uint8_t(differing(levels[k].at_open, now) << 1);
  }
  /// The innermost block, an `else` branch, ends where the branch before it ends too, which
  /// `j` (its close) says what differs at: a way out of the whole `if` block.
  void branch_ended(const Join& j) {
    if (depth > 0) levels[depth - 1].changed |= uint8_t((j.position ? kMoved : 0) | j.modes << 1);
  }
  /// Whether `line` is RepRapFirmware's `break` or `continue`, which leave their loop's block
  /// at once (a line of flow control the firmware goes on from elsewhere than the next).
  static bool leaves_block(std::string_view line);
  /// The number of the innermost loop open labelled `label` (any label where `label` is 0),
  /// which a `continue` runs again; 0 where none is open.
  uint32_t loop_of(uint32_t label) const;
  /// Whether the innermost open block is a `do` labelled `label`.
  bool in_do(uint32_t label) const { return depth > 0 && levels[depth - 1].label == label && levels[depth - 1].do_loop; }
  /// The indent of `line` as the firmware counts it (a space 1, a tab to the next multiple of
  /// 4), or -1 where the line counts for nothing (blank, or an indented `;` comment).
  static int32_t indent_of(std::string_view line);
  /// After a block that changed the position (a move, or a change of the known axes, frame
  /// or offsets), for every block open around it.
  void moved() {
    for (uint32_t k = 0; k < depth; ++k) levels[k].changed |= kMoved;
  }

  bool operator==(const BlockNesting&) const = default;

  /// kMoved: the block's lines changed the position; above it, the kStates* of the modes that
  /// differ on a way out (way_out()).
  static constexpr uint8_t kMoved = 1;
  struct Level {
    uint16_t indent = 0;
    uint8_t changed = 0;  ///< kMoved | the modes differing on a way out << 1, since the level's first line
    bool do_loop = false;
    uint32_t label = 0;   ///< an O-word block's (OWord::label); 0 for a block of blanks
    bool plain = false;   ///< deeper blanks after a line that is no flow control (line())
    uint32_t loop = 0;    ///< a loop's number; 0 no loop
    Modes at_open;        ///< the modes it was entered in
    bool operator==(const Level&) const = default;
  };
  std::array<Level, kMostLevels> levels{};
  uint32_t depth = 0;        ///< levels open (indented past 0)
  uint16_t last_indent = 0;  ///< of the last line read that counts
  bool last_opens = false;   ///< that line is flow control
  uint32_t last_loop = 0;    ///< that line is a `while`: its line number
  uint32_t loops = 0;        ///< loops opened so far: the last one's number
};

}  // namespace arcpress
