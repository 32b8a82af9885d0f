// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What a LinuxCNC O-word line does to the modal state: a subroutine's definition, return, end
// or call (Subroutines), and the blocks of `if`, `while`, `do` and `repeat` (BlockNesting),
// as rs274 runs them.
#include <string>

#include "arcpress/lex/o_word.hpp"
#include "arcpress/model/modal_state.hpp"

namespace arcpress {

/// What the interpreter does beside the state the line changed.
struct OWordFlow {
  /// A subroutine's body begins: its position, distance mode and motion are its caller's
  /// (not known).
  bool enters_body = false;
  /// A call: the position is where the body ended (one place, not known).
  bool after_call = false;
  /// The line ends blocks (what they may have changed is not known after it), jumps back to a
  /// loop's start, or begins a loop.
  BlockNesting::Join join;
  /// Why a call cannot run the body as it was read (E-FLOW-SUB-MODES), else empty.
  std::string problem;
};

/// A repeat marker (Marlin's M808) at line `line`, read in state `s`: `mark` (M808 L) opens a
/// loop whose first lines follow; without, the innermost such loop goes back to its start
/// (BlockNesting, as LinuxCNC's `do` .. `while`). What the interpreter joins.
BlockNesting::Join follow_repeat_marker(ModalState& s, bool mark, uint32_t line);

/// O-word `w`, line `line`, read in state `s`, whose frame the interpreter sets from `frame`
/// afterwards.
OWordFlow follow_o_word(ModalState& s, const OWord& w, Frame& frame, uint32_t line);

}  // namespace arcpress
