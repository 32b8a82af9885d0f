// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Blocks: one per input line, holding the parsed words and the exact raw bytes so that a
// block that is not rewritten is written back byte for byte.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "arcpress/core/diagnostic.hpp"
#include "arcpress/lex/jump_targets.hpp"

namespace arcpress {

/// The letter of a word that is a keyword the program's dialect reads (Program::keywords):
/// Sinumerik's `SOFT`, `TRANS`, `ADIS=0.05`. Its value is the number after `=`, else 0.
inline constexpr char kKeywordLetter = '&';

/// The letter of a word that is a label, where the dialect writes them ([lines] labels):
/// Sinumerik's `LOOP1:` at a block's start. Its value is label_hash() of its name.
inline constexpr char kLabelLetter = ':';

/// One address word: a letter and its value. `letter` is upper case (or kKeywordLetter, kLabelLetter).
struct Word {
  double value = 0;      ///< meaningless when is_expr
  uint32_t col = 0;      ///< 1-based column of the letter
  uint16_t length = 0;   ///< raw bytes from the letter to the end of the value
  char letter = 0;
  bool is_expr = false;  ///< value is `[expression]` or `#parameter`: not evaluable here
  uint8_t decimals = 0;  ///< digits written after the decimal point
  bool has_point = false;
  bool flag = false;     ///< a letter without a number (firmware flags: `M84 X Y E`), or a keyword with
                         ///< nothing after it on its line (`MCALL`); value 0
  bool plus = false;     ///< written with a '+' sign (`X+10.5`, Heidenhain's habit)

  /// The value as a code number times ten, rounded half away from zero: G90.1 is 901, G1 is
  /// 10, M83 is 830 (inline: std::lround is a library call, and every block asks).
  int code10() const { return code10_of(value); }
  static int code10_of(double v) {
    const double t = v * 10.0;
    constexpr double kLimit = 1e9;  // far past any code, inside int
    return t >= kLimit ? int(kLimit) : t <= -kLimit ? -int(kLimit) : int(t < 0 ? t - 0.5 : t + 0.5);
  }
  /// The key by which jumps name the block this word numbers or labels (JumpTargets): an N
  /// word's number_key(), a label's kLabelKey and hash; none for any other word.
  std::optional<uint64_t> target_key() const {
    if (letter == kLabelLetter) return kLabelKey | uint64_t(value);
    return letter == 'N' && !is_expr ? number_key(value) : std::nullopt;
  }
};

/// What kind of line a block is. Everything but Code is passed through untouched and is a
/// barrier for fitting.
enum class BlockKind : uint8_t {
  Empty,        ///< only white space and/or comments
  Code,         ///< ordinary words
  Percent,      ///< a `%` tape mark line
  Control,      ///< LinuxCNC O-word flow control: `O100 sub`, `o<x> if [...]`, ...
  Macro,        ///< parameter assignment `#1=...` or Fanuc macro line (IF/GOTO/WHILE/END)
  HostCommand,  ///< sender/firmware commands: `$H`, `?`, `M117 text`, Klipper `SET_FAN ...`
  Opaque,       ///< not understood; kept verbatim, reported once per kind
};

struct Block {
  uint32_t begin = 0;       ///< offset of the raw text (line without its end-of-line)
  uint32_t length = 0;
  uint32_t line = 0;        ///< 1-based
  uint32_t first_word = 0;  ///< index into Program::words
  uint16_t word_count = 0;
  uint8_t eol_length = 0;   ///< 0 (last line, no newline), 1 ("\n") or 2 ("\r\n")
  BlockKind kind = BlockKind::Empty;
  bool block_delete = false;  ///< starts with `/`
  bool has_comment = false;   ///< `( )` or `;` comment anywhere on the line
  bool has_checksum = false;  ///< `*NN`
  bool block_end = false;     ///< ends with a `*` and no number: the end-of-block mark (Heidenhain ISO)
  bool has_expr = false;      ///< a word value is an expression or parameter
};

/// A line of one program's text that is a byte copy of a block of another program (an
/// output's line copied from its input): where the line starts in the text, and the block.
struct CopiedLine {
  size_t offset = 0;
  uint32_t block = 0;
};

/// A word of two letters or more that a dialect reads within a block, beside the address
/// words (Sinumerik's `G17 G90 G71 G642 SOFT`): lexed as a word of kKeywordLetter, bare, with
/// a number after `=` (`ADIS=0.05`), or with its arguments in parentheses after it, which
/// end the block (`CYCLE832(0.01,_FINISH,1)`). Any other such word leaves its line unread (Opaque).
struct KeywordSpelling {
  std::string name;        ///< upper case; programs may write it in any case
  bool takes_call = false; ///< the rest of its line is a call it makes (`MCALL CYCLE81(10,0,2,-5)`), not words
};

/// What a dialect's lines hold beyond RS274's words (Program::rules).
struct LexRules {
  /// The keywords the dialect reads (none: a multi-letter word leaves its line unread).
  std::vector<KeywordSpelling> keywords;
  /// Sinumerik's assignments: `R1=5` (and `R[R2]=5`) sets a parameter, and a line of them is a
  /// Macro line; `X=10` is X10; `X=R1*2`, `X=IC(5)` give an address an expression's value and
  /// `M2=3`, `X1=10` an address with an extension, both read as expression words. Elsewhere
  /// an `=` after an address leaves its line unread.
  bool assignments = false;
  /// Sinumerik's labels: a name and a colon at a block's start, after its number at most
  /// (`LOOP1:`, `N10 _START: G1 X0`), are a word of kLabelLetter, the target of the jumps
  /// that name it (`GOTOB LOOP1`). Elsewhere such a line is not read.
  bool labels = false;
  /// Heidenhain ISO's numbered labels: `G98 L1` sets label 1, its L word read as a label word
  /// (`G98 L0`, a subprogram's end, sets none); `L1,2` repeats the lines after label 1 twice
  /// and `L1,0` calls them, each a Control line. Elsewhere a comma leaves its line unread.
  bool numbered_labels = false;
};

/// A lexed program: the bytes, the blocks and all words (blocks index into `words`).
struct Program {
  std::string name;  ///< file name for diagnostics
  std::string text;
  std::vector<Block> blocks;
  std::vector<Word> words;
  /// How its dialect's lines are lexed.
  LexRules rules;
  /// The blocks its jumps may enter (null: none known), read from its whole text before its
  /// blocks are read: a block a jump enters goes on from where the jump was made.
  std::shared_ptr<const JumpTargets> jumps;

  std::string_view raw(const Block& b) const { return std::string_view(text).substr(b.begin, b.length); }
  std::string_view eol(const Block& b) const {
    return std::string_view(text).substr(b.begin + b.length, b.eol_length);
  }
  const Word* words_begin(const Block& b) const { return words.data() + b.first_word; }
  const Word* words_end(const Block& b) const { return words.data() + b.first_word + b.word_count; }
  /// First word with `letter` in the block, or nullptr.
  std::string_view raw(const Block& b, const Word& w) const { return raw(b).substr(w.col - 1, w.length); }
  /// The name of keyword word `w` as written (`SOFT`, `ADIS` of `ADIS=0.05`).
  std::string_view keyword_name(const Block& b, const Word& w) const {
    const std::string_view r = raw(b, w);
    return r.substr(0, std::min(r.find_first_of("= \t"), r.size()));
  }
  const Word* find(const Block& b, char letter) const {
    for (auto* w = words_begin(b); w != words_end(b); ++w)
      if (w->letter == letter) return w;
    return nullptr;
  }
};

}  // namespace arcpress
