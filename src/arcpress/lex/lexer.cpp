// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/lex/lexer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>

#include "arcpress/core/decimal.hpp"
#include "arcpress/lex/characters.hpp"

namespace arcpress {
namespace {

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

/// M-codes whose argument is free text (firmware messages and SD-card file names).
bool is_text_mcode(double v) {
  return v == 117 || v == 118 || v == 23 || v == 28 || v == 32 || v == 928;
}

class LineLexer {
 public:
  LineLexer(Program& prog, Block& blk, DiagnosticSink& sink)
      : p_(prog), b_(blk), sink_(sink), s_(prog.text.data() + blk.begin), n_(blk.length) {}

  void run() {
    size_t i = 0;
    if (b_.line == 1 && n_ >= 3 && s_[0] == '\xEF' && s_[1] == '\xBB' && s_[2] == '\xBF') i = 3;  // UTF-8 BOM
    i = skip_space(i);
    if (i < n_ && s_[i] == '%') {
      if (!program_name(i)) {
        b_.kind = BlockKind::Percent;
        return;
      }
      i = after_;
    }
    if (i < n_ && s_[i] == '/') {
      b_.block_delete = true;
      ++i;
      while (i < n_ && is_digit(s_[i])) ++i;  // Fanuc /1 ... /9
    }
    bool first_token = true;
    while (true) {
      i = skip_space(i);
      if (i >= n_) break;
      char c = s_[i];
      if (c == '(') {
        size_t close = i + 1;
        while (close < n_ && s_[close] != ')') ++close;
        b_.has_comment = true;
        if (close >= n_) {
          opaque(i, "E-LEX-COMMENT", "comment '(' is not closed on this line");
          return;
        }
        i = close + 1;
        continue;
      }
      if (c == ';') {
        b_.has_comment = true;
        break;
      }
      if (c == '*') {
        // `*NN` is a host's checksum (Marlin, RepRapFirmware); a `*` with no number is
        // Heidenhain ISO's end of block.
        ++i;
        if (i < n_ && is_digit(s_[i]))
          b_.has_checksum = true;
        else
          b_.block_end = true;
        while (i < n_ && is_digit(s_[i])) ++i;
        continue;
      }
      // (After a block number only: the last block's `N99999999 %NAME G71 *`.)
      if (c == '%' && b_.word_count == 1 && p_.words.back().letter == 'N' && program_name(i)) {
        i = after_;
        continue;
      }
      if (c == '#') {
        set_kind(BlockKind::Macro);
        return;
      }
      if (first_token && (c == '$' || c == '?' || c == '!' || c == '~')) {
        set_kind(BlockKind::HostCommand);
        return;
      }
      if (!is_alpha(c)) {
        if (const int read = unexpected(i); read > 0) {
          first_token = false;
          i = after_;
          continue;
        } else if (read < 0) {
          return;
        }
        opaque(i, "E-LEX-CHAR", fmt::format("unexpected character '{}' (byte 0x{:02X})", printable(c), uint8_t(c)));
        return;
      }
      // A letter: an address word, or the start of a multi-letter keyword.
      size_t j = skip_space(i + 1);
      if (i + 1 < n_ && (is_alpha(s_[i + 1]) || s_[i + 1] == '_')) {
        if (!keyword(i, first_token)) return;
        first_token = false;
        i = after_;
        continue;
      }
      if (upper(c) == 'O' && j < n_ && s_[j] == '<') {  // o<name> ...
        set_kind(BlockKind::Control);
        return;
      }
      if (!word(i, j)) return;
      first_token = false;
      const Word& w = p_.words.back();
      if (w.letter == 'M' && !w.is_expr && (is_text_mcode(w.value) || w.value == 486 || (w.value >= 862 && w.value < 863))) {
        set_kind(BlockKind::HostCommand);
        return;
      }
      i = after_;
      if (w.letter == 'O') {
        // `O100 sub`, `O100 if [...]`: flow control follows the number.
        size_t k = skip_space(i);
        if (k < n_ && is_alpha(s_[k])) {
          set_kind(BlockKind::Control);
          return;
        }
      }
    }
    if (b_.word_count > 0 && b_.kind == BlockKind::Empty) b_.kind = BlockKind::Code;
    if (p_.rules.numbered_labels && b_.kind == BlockKind::Code) numbered_label();
  }

 private:
  static char printable(char c) { return (uint8_t(c) >= 32 && uint8_t(c) < 127) ? c : '?'; }

  size_t skip_space(size_t i) const {
    while (i < n_ && is_space(s_[i])) ++i;
    return i;
  }

  void set_kind(BlockKind k) { b_.kind = k; }

  /// Whether the `%` at `i` names a program (`%NAME G71 *` and `N99999999 %NAME G71 *`,
  /// Heidenhain ISO's first and last blocks): a name follows it at once. The name is stepped
  /// over (after_ is set past it) and the words after it are read; a `%` alone is a tape mark.
  bool program_name(size_t i) {
    size_t e = i + 1;
    while (e < n_ && (is_alpha(s_[e]) || is_digit(s_[e]) || s_[e] == '_' || s_[e] == '-' || s_[e] == '.')) ++e;
    if (e == i + 1) return false;
    after_ = e;
    return true;
  }

  void opaque(size_t i, std::string_view code, std::string msg) {
    b_.kind = BlockKind::Opaque;
    sink_.problem({b_.line, uint32_t(i + 1)}, code, std::move(msg));
  }

  /// The multi-letter word at `i`: one of the dialect's keywords is read as a word (true:
  /// lexing goes on at after_); flow control makes the line a Macro, a first word an extended
  /// command, and any other keyword leaves the line unread.
  bool keyword(size_t i, bool first_token) {
    size_t e = i;
    while (e < n_ && (is_alpha(s_[e]) || is_digit(s_[e]) || s_[e] == '_')) ++e;
    if (p_.rules.labels && e < n_ && s_[e] == ':' && label(i)) return true;
    std::string kw;
    for (size_t k = i; k < e; ++k) kw += upper(s_[k]);
    for (const KeywordSpelling& k : p_.rules.keywords)
      if (k.name == kw) return dialect_keyword(i, e, k);
    if (kw == "IF" || kw == "WHILE" || kw == "GOTO" || kw == "GOTOB" || kw == "GOTOF" || kw == "GOTOC" ||
        kw.rfind("END", 0) == 0 || kw.rfind("DO", 0) == 0 || kw == "THEN" || kw == "ELSE" || kw == "LOOP" ||
        kw == "FOR" || kw == "REPEAT" || kw == "UNTIL") {
      set_kind(BlockKind::Macro);
      return false;
    }
    if (first_token && (e >= n_ || is_space(s_[e]) || s_[e] == '=' || s_[e] == ';')) {
      set_kind(BlockKind::HostCommand);  // Klipper/RepRap style extended command
      return false;
    }
    opaque(i, "E-LEX-KEYWORD", fmt::format("unknown keyword '{}'", kw));
    return false;
  }

  /// The dialect's keyword `k`, written from `i` to `e`: bare, with a number after `=`, with
  /// its arguments in parentheses (`CYCLE832(0.01,_FINISH,1)`, `MSG("...")`), or, where it
  /// makes a call, with the call after it; arguments and a call end the block's words.
  bool dialect_keyword(size_t i, size_t e, const KeywordSpelling& k) {
    auto ends_word = [&](size_t q) { return q >= n_ || is_space(s_[q]) || s_[q] == ';'; };
    const size_t next = skip_space(e);
    if (k.takes_call || (next < n_ && s_[next] == '(')) {
      const bool alone = next >= n_ || s_[next] == ';';
      if (!push(i, e, kKeywordLetter, 0, false, 0, false, alone)) return false;
      b_.has_comment = b_.has_comment || (alone && next < n_);
      set_kind(BlockKind::Code);
      return false;
    }
    if (next < n_ && s_[next] == '=') {
      size_t q = skip_space(next + 1);
      bool negative = false;
      if (q < n_ && (s_[q] == '-' || s_[q] == '+')) negative = s_[q++] == '-';
      const size_t start = q;
      const Number n = scan_plain_number(q);
      if (n.digits > 0 && !n.rescan && ends_word(q)) {
        const double v = value_of(n, start, q);
        return push(i, q, kKeywordLetter, negative ? -v : v, false, n.decimals, n.point, false);
      }
      opaque(start, "E-LEX-KEYWORD-VALUE", fmt::format("the value of '{}' is not a number", k.name));
      return false;
    }
    if (ends_word(e)) return push(i, e, kKeywordLetter, 0, false, 0, false, true);
    opaque(e, "E-LEX-KEYWORD", fmt::format("'{}' followed by '{}' is not read", k.name, printable(s_[e])));
    return false;
  }

  /// What the dialect reads at `i` where RS274 has no word (an unexpected character): a label
  /// that begins with `_` (LexRules::labels), the `=` after an address and its number or
  /// brackets (`R1=5`, `R[R1]=4`, `X1=10`: assignment()), the comma of Heidenhain's `L1,2`
  /// (LexRules::numbered_labels, a Control line). As assignment(): 0 where it is none of them.
  int unexpected(size_t i) {
    const char c = s_[i];
    if (c == '_' && p_.rules.labels) return label(i) ? 1 : 0;
    if (b_.word_count == 0) return 0;
    const Word last = p_.words.back();
    if (c == ',' && p_.rules.numbered_labels && last.letter == 'L' && i + 1 < n_ && is_digit(s_[i + 1])) {
      set_kind(BlockKind::Control);  // L1,2: a repeat or call of the lines after label 1
      return -1;
    }
    if (c != '=' || !p_.rules.assignments || skip_space(last.col - 1 + last.length) != i) return 0;
    p_.words.pop_back();  // read again as an assignment
    --b_.word_count;
    if (const int read = assignment(last.col - 1)) return read;
    p_.words.push_back(last);
    ++b_.word_count;
    return 0;
  }

  /// The assignment at `i` where the dialect writes them (LexRules::assignments): 0 where the
  /// address there is not followed by `=`; 1 where it was read as a word (lexing goes on at
  /// after_); -1 where the line is done: a parameter's assignment (`R1=5`, `R[R2]=5`) after
  /// nothing but a block number makes a Macro line, and after other words leaves it unread.
  int assignment(size_t i) {
    const char letter = upper(s_[i]);
    size_t k = i + 1;
    if (k < n_ && s_[k] == '[') {
      for (int depth = 0; k < n_; ++k) {
        if (s_[k] == '[') ++depth;
        if (s_[k] == ']' && --depth == 0) break;
      }
      if (k < n_) ++k;
    } else {
      while (k < n_ && is_digit(s_[k])) ++k;
    }
    const bool extension = k > i + 1;  // R1=, X1=, M2=: the address's number before the `=`
    k = skip_space(k);
    if (k >= n_ || s_[k] != '=') return 0;
    if (letter == 'R' && extension) {
      if (!numbered_only()) {
        opaque(i, "E-LEX-ASSIGN", "a parameter's assignment after other words is not read");
        return -1;
      }
      set_kind(BlockKind::Macro);
      return -1;
    }
    size_t q = skip_space(k + 1);
    if (!extension) {  // X=10, X=-2.5: the word X10, X-2.5
      size_t v = q;
      const bool negative = v < n_ && s_[v] == '-';
      if (v < n_ && (s_[v] == '-' || s_[v] == '+')) ++v;
      const size_t start = v;
      const Number n = scan_plain_number(v);
      if (n.digits > 0 && !n.rescan && (v >= n_ || is_space(s_[v]) || s_[v] == ';')) {
        const double value = value_of(n, start, v);
        return push(i, v, letter, negative ? -value : value, false, n.decimals, n.point, false) ? 1 : -1;
      }
    }
    // An expression (R1*2, IC(5), AC(R3), "DRILL"): up to the first blank outside its
    // brackets and quotes.
    int depth = 0;
    for (bool quoted = false; q < n_; ++q) {
      const char c = s_[q];
      if (c == '"') quoted = !quoted;
      if (quoted) continue;
      if (c == '(' || c == '[') ++depth;
      if (c == ')' || c == ']') --depth;
      if (depth <= 0 && (is_space(c) || c == ';')) break;
    }
    b_.has_expr = true;
    return push(i, q, letter, 0, true, 0, false, false) ? 1 : -1;
  }

  /// The label at `i` where the dialect writes them (LexRules::labels): a name of two
  /// characters or more and a colon, after nothing but a block number, is read as a word of
  /// kLabelLetter (true: lexing goes on at after_).
  bool label(size_t i) {
    size_t e = i;
    while (e < n_ && (is_alpha(s_[e]) || is_digit(s_[e]) || s_[e] == '_')) ++e;
    if (e >= n_ || s_[e] != ':' || e - i < 2 || !numbered_only()) return false;
    return push(i, e + 1, kLabelLetter, double(label_hash(std::string_view(s_ + i, e - i))), false, 0, false, false);
  }

  /// Where the block sets a numbered label (`G98 L1`, LexRules::numbered_labels), its L word
  /// becomes a label word.
  void numbered_label() {
    Word* const first = p_.words.data() + b_.first_word;
    Word* const end = first + b_.word_count;
    const bool g98 = std::any_of(first, end, [](const Word& w) { return w.letter == 'G' && !w.is_expr && w.value == 98; });
    for (Word* w = first; g98 && w != end; ++w)
      if (w->letter == 'L' && !w->is_expr && w->value >= 1 && w->value == std::floor(w->value) && w->value < 1e12) {
        w->letter = kLabelLetter;
        w->value = double(numbered_label_hash(uint64_t(w->value)));
      }
  }

  /// Whether the block's words so far are block numbers only.
  bool numbered_only() const {
    for (uint32_t w = 0; w < b_.word_count; ++w)
      if (p_.words[b_.first_word + w].letter != 'N') return false;
    return true;
  }

  /// Lexes the word whose letter is at `i`; `j` is the first non-space after the letter.
  bool word(size_t i, size_t j) {
    const char letter = upper(s_[i]);
    size_t k = j;
    bool negative = false;
    const bool plus = k < n_ && s_[k] == '+';
    if (k < n_ && (s_[k] == '-' || s_[k] == '+')) {
      negative = s_[k] == '-';
      k = skip_space(k + 1);
    }
    if (k < n_ && (s_[k] == '[' || s_[k] == '#')) {
      b_.has_expr = true;
      if (s_[k] == '[') {
        int depth = 0;
        for (; k < n_; ++k) {
          if (s_[k] == '[') ++depth;
          if (s_[k] == ']' && --depth == 0) break;
        }
        if (k >= n_) {
          opaque(i, "E-LEX-EXPR", fmt::format("expression after '{}' has no closing ']'", letter));
          return false;
        }
        ++k;
      } else {
        while (k < n_ && s_[k] == '#') ++k;
        if (k < n_ && s_[k] == '<') {
          while (k < n_ && s_[k] != '>') ++k;
          if (k < n_) ++k;
        } else {
          while (k < n_ && (is_digit(s_[k]) || s_[k] == '.')) ++k;
        }
      }
      return push(i, k, letter, 0, true, 0, false, false);
    }
    const size_t start = k;
    Number n = scan_plain_number(k);
    if (n.rescan) {
      k = start;
      n = scan_number(k);
    }
    if (n.digits == 0 && k < n_ && s_[k] == '"') {
      set_kind(BlockKind::HostCommand);  // firmware string argument: M862.3 P "MINI"
      return false;
    }
    if (n.digits == 0 && k < n_ && s_[k] == '=' && p_.rules.assignments) return assignment(i) > 0;  // X=R1
    if (n.digits == 0 && (i + 1 >= n_ || is_space(s_[i + 1]) || s_[i + 1] == ';') && allows_flags())
      return push(i, k, letter, 0, false, 0, false, true);  // Marlin-style axis flag: M84 X Y E, G28 X Y
    if (n.digits == 0) {
      std::string found = k < n_ ? fmt::format("'{}'", printable(s_[k])) : std::string("end of line");
      opaque(i, "E-LEX-NUMBER", fmt::format("word '{}' has no number (found {})", letter, found));
      return false;
    }
    const double value = value_of(n, start, k);
    if (!push(i, k, letter, negative ? -value : value, false, n.decimals, n.point, false)) return false;
    p_.words.back().plus = plus;
    return true;
  }

  /// The digits of a number: its first 18 as an integer, how many follow the point.
  struct Number {
    uint64_t mant = 0;
    int digits = 0, decimals = 0;
    bool point = false;
    bool slow = false;          ///< more digits than `mant` holds: read by strtod
    /// scan_number() must read it: blanks with more of the number after them, or more
    /// digits than `mant` holds.
    bool rescan = false;
  };

  /// A number written without blanks (what nearly every program writes), from `k`, which
  /// is left after it.
  Number scan_plain_number(size_t& k) const {
    Number n;
    auto digits = [&](bool after_point) {
      for (; k < n_ && is_digit(s_[k]); ++k, ++n.digits) {
        n.mant = n.mant * 10 + uint64_t(s_[k] - '0');
        n.decimals += after_point;
      }
    };
    digits(false);
    if (k < n_ && s_[k] == '.') {
      n.point = true;
      ++k;
      digits(true);
    }
    if (n.digits >= 18) n.rescan = true;
    if (k < n_ && (s_[k] == ' ' || s_[k] == '\t')) {
      size_t q = k;
      while (q < n_ && (s_[q] == ' ' || s_[q] == '\t')) ++q;
      if (q < n_ && (is_digit(s_[q]) || (s_[q] == '.' && !n.point))) n.rescan = true;
    }
    return n;
  }

  /// A number as RS274 allows it, with blanks between its characters, from `k`, which is
  /// left after its last character.
  Number scan_number(size_t& k) const {
    Number n;
    const size_t start = k;
    while (k < n_) {
      char c = s_[k];
      if (is_digit(c)) {
        if (n.digits < 18) {
          n.mant = n.mant * 10 + uint64_t(c - '0');
          if (n.point) ++n.decimals;
        } else {
          n.slow = true;
        }
        ++n.digits;
      } else if (c == '.' && !n.point) {
        n.point = true;
      } else if (!(c == ' ' || c == '\t')) {
        break;
      }
      ++k;
    }
    while (k > start && (s_[k - 1] == ' ' || s_[k - 1] == '\t')) --k;  // trailing blanks are not the number's
    return n;
  }

  /// The value of number `n`, written at [start, k).
  double value_of(const Number& n, size_t start, size_t k) const {
    if (!n.slow && n.decimals <= kExactPow10Max) return double(n.mant) / kPow10[n.decimals];
    std::string buf;
    for (size_t q = start; q < k; ++q)
      if (s_[q] != ' ' && s_[q] != '\t') buf += s_[q];
    return std::strtod(buf.c_str(), nullptr);
  }

  /// Letters without numbers are flags after an M-code or G28/G29/G61 (firmware syntax).
  bool allows_flags() const {
    for (uint32_t k = 0; k < b_.word_count; ++k) {
      const Word& w = p_.words[b_.first_word + k];
      if (w.letter == 'M' || (w.letter == 'G' && (w.value == 28 || w.value == 29 || w.value == 61))) return true;
    }
    return false;
  }

  /// Adds the word whose letter is at `i` and whose text ends at `after` to the block; false
  /// (and the block kept as it is) for a word too long for Word::length, which a rewritten
  /// block could not copy whole, or one past the most Block::word_count can count. The word is built where it is stored (built aside and
  /// copied, its narrow fields' stores stall the copy's wide loads).
  bool push(size_t i, size_t after, char letter, double value, bool is_expr, int decimals, bool point, bool flag) {
    const size_t length = after - i;
    if (length > UINT16_MAX) {
      opaque(i, "E-LEX-WORD-LENGTH",
             fmt::format("word '{}' is {} bytes long; at most {} are read", letter, length, UINT16_MAX));
      return false;
    }
    if (b_.word_count == UINT16_MAX) {
      opaque(i, "E-LEX-WORD-COUNT",
             fmt::format("block has more than {} words; it is passed through unread", UINT16_MAX));
      return false;
    }
    if (b_.word_count == 0) b_.first_word = uint32_t(p_.words.size());
    Word& w = p_.words.emplace_back();
    w.value = value;
    w.col = uint32_t(i + 1);
    w.length = uint16_t(length);
    w.letter = letter;
    w.is_expr = is_expr;
    w.decimals = uint8_t(decimals > 255 ? 255 : decimals);
    w.has_point = point;
    w.flag = flag;
    ++b_.word_count;
    after_ = after;
    return true;
  }

  Program& p_;
  Block& b_;
  DiagnosticSink& sink_;
  const char* s_;
  size_t n_;
  size_t after_ = 0;
};

}  // namespace

namespace {

/// The block of the line at [begin, end) of `t` (its "\n" or "\r\n" apart), no words yet.
Block line_block(const std::string& t, size_t begin, size_t end, uint32_t line, uint32_t first_word) {
  Block b;
  b.line = line;
  b.begin = uint32_t(begin);
  size_t content_end = end;
  if (end > begin && t[end - 1] == '\n') {
    content_end = end - 1;
    b.eol_length = 1;
    if (content_end > begin && t[content_end - 1] == '\r') {
      --content_end;
      b.eol_length = 2;
    }
  }
  b.length = uint32_t(content_end - begin);
  b.first_word = first_word;
  return b;
}

/// Adds the line at [begin, end) as a copy of `from`, a block of `source`, if its bytes are
/// that block's and lexing it again could differ in nothing: false where it must be lexed.
bool take_copy(Program& p, size_t begin, size_t end, uint32_t line, const Program& source, const Block& from) {
  if (line == 1 || from.line == 1 || from.kind == BlockKind::Opaque) return false;
  Block b = line_block(p.text, begin, end, line, uint32_t(p.words.size()));
  if (b.length != from.length || std::string_view(p.text).substr(begin, b.length) != source.raw(from)) return false;
  b.word_count = from.word_count;
  b.kind = from.kind;
  b.block_delete = from.block_delete;
  b.has_comment = from.has_comment;
  b.has_checksum = from.has_checksum;
  b.block_end = from.block_end;
  b.has_expr = from.has_expr;
  p.words.insert(p.words.end(), source.words_begin(from), source.words_end(from));
  p.blocks.push_back(b);
  return true;
}

}  // namespace

void lex_line(Program& p, size_t begin, size_t end, uint32_t line, DiagnosticSink& sink) {
  p.blocks.push_back(line_block(p.text, begin, end, line, uint32_t(p.words.size())));
  LineLexer(p, p.blocks.back(), sink).run();
}

Program lex(std::string name, std::string text, DiagnosticSink& sink, LexRules rules) {
  Program source;
  source.rules = std::move(rules);
  return lex(std::move(name), std::move(text), sink, source, {});
}

Program lex(std::string name, std::string text, DiagnosticSink& sink, const Program& source,
            std::span<const CopiedLine> copies) {
  Program p;
  p.name = std::move(name);
  p.text = std::move(text);
  p.rules = source.rules;
  p.jumps = source.jumps;
  p.blocks.reserve(p.text.size() / 24 + 1);
  p.words.reserve(p.text.size() / 6 + 1);
  uint32_t line = 0;
  size_t c = 0;  // the next copy at or after the line
  for (size_t pos = 0; pos < p.text.size();) {
    const size_t nl = p.text.find('\n', pos);
    const size_t end = nl == std::string::npos ? p.text.size() : nl + 1;
    ++line;
    while (c < copies.size() && copies[c].offset < pos) ++c;
    const bool copied = c < copies.size() && copies[c].offset == pos && copies[c].block < source.blocks.size() &&
                        take_copy(p, pos, end, line, source, source.blocks[copies[c].block]);
    if (!copied) lex_line(p, pos, end, line, sink);
    pos = end;
  }
  return p;
}

bool is_arcpress_header(std::string_view line) {
  size_t i = line.find_first_not_of(" \t");
  if (i == std::string_view::npos || (line[i] != ';' && line[i] != '(')) return false;
  i = line.find_first_not_of(" \t", i + 1);
  constexpr std::string_view kMark = "arcpress ";
  return i != std::string_view::npos && line.substr(i, kMark.size()) == kMark && i + kMark.size() < line.size() &&
         line[i + kMark.size()] >= '0' && line[i + kMark.size()] <= '9';
}

}  // namespace arcpress
