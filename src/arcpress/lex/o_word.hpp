// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// LinuxCNC's O-words: the flow-control line `o100 sub`, `o<name> call [1]`, `O100 endsub`,
// `o101 if [...]`, read for what it does and the label it names; and Fanuc's macro loops.
#include <cstdint>
#include <string_view>

namespace arcpress {

struct OWord {
  enum class Kind : uint8_t {
    Other, Sub, EndSub, Return, Call,
    If, ElseIf, Else, EndIf, While, EndWhile, Do, Repeat, EndRepeat, Continue  ///< (a While may end a Do)
  };
  Kind kind = Kind::Other;
  /// The label (`100`, `<name>` in any case), hashed: two lines name one subroutine where
  /// these agree. 0 where the line has none.
  uint32_t label = 0;
};

/// The O-word line `line` (a block of kind Control): its keyword and label. Fanuc's and Haas's
/// macro loops (a block of kind Macro) read as LinuxCNC's: `WHILE [..] DO1` as a `while`, `DO1`
/// as a `do`, `END1` as the end of either; so are Sinumerik's blocks (`WHILE` .. `ENDWHILE`,
/// `LOOP` .. `ENDLOOP`, `FOR` .. `ENDFOR`, `REPEAT` .. `UNTIL`, `IF` .. `ELSE` .. `ENDIF`),
/// where `keyword_blocks` (not where indents make the blocks: RepRapFirmware's `if`, `else`
/// and `while` are not closed by keywords).
OWord read_o_word(std::string_view line, bool keyword_blocks);

}  // namespace arcpress
