// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/lex/jump_targets.hpp"

#include <algorithm>
#include <cmath>
#include <charconv>
#include <cstring>

#include "arcpress/lex/characters.hpp"

namespace arcpress {

namespace {

bool is_letter(char c) { return is_alpha(c) || c == '_'; }

/// The name at text[i, end) after blanks (a letter or `_`, then letters, digits and `_`), or empty.
std::string_view name_at(std::string_view text, size_t i, size_t end) {
  while (i < end && (text[i] == ' ' || text[i] == '\t')) ++i;
  size_t e = i;
  if (e < end && is_letter(text[e]))
    while (e < end && (is_letter(text[e]) || is_digit(text[e]))) ++e;
  return text.substr(i, e - i);
}

/// What a jump names, read from `i` on: a block number (N100, or 100), a number the program
/// computes (#1, [#1+10]), or neither (a label's name, nothing).
struct Named {
  enum Kind { Nothing, Number, Computed } kind = Nothing;
  uint64_t number = 0;
};

Named named_at(std::string_view s, size_t i, bool n_allowed) {
  while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
  if (i >= s.size()) return {};
  if (s[i] == '#' || s[i] == '[') return {Named::Computed, 0};
  if (n_allowed && upper(s[i]) == 'N' && i + 1 < s.size() && is_digit(s[i + 1])) ++i;
  if (!is_digit(s[i])) return {};
  uint64_t n = 0;
  for (; i < s.size() && is_digit(s[i]); ++i) {
    if (n > (uint64_t(1) << 50)) return {};
    n = n * 10 + uint64_t(s[i] - '0');
  }
  if (i < s.size() && s[i] == '.') {  // P100. is 100; P100.5 names no block
    for (++i; i < s.size() && is_digit(s[i]); ++i)
      if (s[i] != '0') return {};
  }
  return {Named::Number, n};
}

/// Heidenhain's `Ln,m` at text[i, end) (i at the L): label n and the count m, else none.
std::optional<std::pair<uint64_t, uint64_t>> label_repeat_at(std::string_view text, size_t i, size_t end) {
  size_t j = i + 1;
  uint64_t n = 0, m = 0;
  for (; j < end && is_digit(text[j]) && n < (uint64_t(1) << 40); ++j) n = n * 10 + uint64_t(text[j] - '0');
  if (j == i + 1 || j + 1 >= end || text[j] != ',' || !is_digit(text[j + 1])) return std::nullopt;
  for (++j; j < end && is_digit(text[j]) && m < (uint64_t(1) << 40); ++j) m = m * 10 + uint64_t(text[j] - '0');
  return std::pair(n, m);
}

/// Whether M-code text[j, end) is `code` (M2, M02, M2.0; not M20).
bool m_code_is(std::string_view text, size_t j, size_t end, unsigned code) {
  while (j < end && text[j] == '0') ++j;
  unsigned v = 0;
  for (; j < end && is_digit(text[j]) && v < 1000; ++j) v = v * 10 + unsigned(text[j] - '0');
  if (j < end && text[j] == '.')
    for (++j; j < end && is_digit(text[j]); ++j)
      if (text[j] != '0') return false;
  return v == code && (j >= end || !is_digit(text[j]));
}

/// Whether text[i, end) begins with keyword `word` (upper case), in any case, not followed by
/// a letter.
bool keyword_at(std::string_view text, size_t i, size_t end, std::string_view word) {
  if (end - i < word.size()) return false;
  for (size_t j = 0; j < word.size(); ++j)
    if (upper(text[i + j]) != word[j]) return false;
  return i + word.size() == end || !is_letter(text[i + word.size()]);
}

/// The jumps in the line text[start, end): `add(number, at, call)` for a block number named
/// (`call`: by a call, which returns), `add_computed(at)` for a computed one; `loops` set where
/// it opens or ends a loop of blocks (`do`, `DO1`, `while`, `repeat`, `LOOP`, `FOR`, `UNTIL`, M808).
/// Returns whether the line ends a program (M2, M30, M99).
template <class Add, class AddComputed>
bool read_line(std::string_view text, size_t start, size_t end, Add& add, AddComputed& add_computed, bool& loops) {
  char jump_m = 0;      // M97 ('7') or M99 ('9')
  bool call_m = false;  // M98
  bool ends = false;
  Named p, q;           // the line's P and Q words
  for (size_t i = start; i < end; ++i) {
    const char c = text[i];
    const bool starts = i == start || !is_letter(text[i - 1]);
    switch (c) {
      case '(':
        while (i + 1 < end && text[i + 1] != ')') ++i;
        break;
      case '"':
        while (i + 1 < end && text[i + 1] != '"') ++i;
        ++i;
        break;
      case ';':
        i = end;
        break;
      case 'G': case 'g': {
        if (!starts || i + 3 >= end || upper(text[i + 1]) != 'O' || upper(text[i + 2]) != 'T' || upper(text[i + 3]) != 'O')
          break;
        size_t j = i + 4;
        if (j < end && (upper(text[j]) == 'F' || upper(text[j]) == 'B' || upper(text[j]) == 'C')) ++j;
        if (j < end && is_letter(text[j])) break;  // another word (a name beginning GOTO)
        const Named t = named_at(text.substr(0, end), j, true);
        if (t.kind == Named::Number) add(t.number, i, false);
        if (t.kind == Named::Computed) add_computed(i);
        if (const std::string_view label = name_at(text, j, end); t.kind == Named::Nothing && !label.empty())
          add(kLabelKey | label_hash(label), i, false);
        i = j - 1;
        break;
      }
      case 'D': case 'd':  // `do`, `DO1`
        loops = loops || (starts && i + 1 < end && upper(text[i + 1]) == 'O' &&
                          (i + 2 == end || is_digit(text[i + 2]) || text[i + 2] == ' ' || text[i + 2] == '\t' || text[i + 2] == '\r'));
        break;
      case 'W': case 'w': loops = loops || (starts && keyword_at(text, i, end, "WHILE")); break;
      case 'R': case 'r': loops = loops || (starts && keyword_at(text, i, end, "REPEAT")); break;
      case 'L': case 'l':
        loops = loops || (starts && keyword_at(text, i, end, "LOOP"));  // (Sinumerik's)
        if (const auto r = starts ? label_repeat_at(text, i, end) : std::nullopt)  // (Heidenhain's L1,2)
          add(kLabelKey | numbered_label_hash(r->first), i, false);
        break;
      case 'F': case 'f': loops = loops || (starts && keyword_at(text, i, end, "FOR")); break;
      case 'U': loops = loops || (starts && keyword_at(text, i, end, "UNTIL")); break;
      case 'M': case 'm': {
        if (!starts) break;
        size_t j = i + 1;
        while (j < end && (text[j] == ' ' || text[j] == '\t')) ++j;
        ends = ends || m_code_is(text, j, end, 2) || m_code_is(text, j, end, 30) || m_code_is(text, j, end, 99);
        loops = loops || m_code_is(text, j, end, 808);  // (Marlin's repeat marker)
        while (j + 2 < end && text[j] == '0' && is_digit(text[j + 1]) && is_digit(text[j + 2])) ++j;
        if (j + 1 < end && text[j] == '9' && (text[j + 1] == '7' || text[j + 1] == '8' || text[j + 1] == '9') &&
            (j + 2 >= end || (!is_digit(text[j + 2]) && text[j + 2] != '.')))
          text[j + 1] == '8' ? void(call_m = true) : void(jump_m = text[j + 1]);
        break;
      }
      case 'P': case 'p': case 'Q': case 'q': {
        if (!starts) break;
        size_t j = i + 1;
        while (j < end && (text[j] == ' ' || text[j] == '\t')) ++j;
        if (j < end && (is_digit(text[j]) || text[j] == '#' || text[j] == '['))
          (upper(c) == 'P' ? p : q) = named_at(text.substr(0, end), j, false);
        break;
      }
      default:
        break;
    }
  }
  // M97 Pn and M99 Pn name block n; M98 P.. Qn starts the program it calls at block n.
  const Named& named = jump_m ? p : call_m ? q : Named{};
  if (named.kind == Named::Number) add(named.number, start, jump_m != '9');
  if (named.kind == Named::Computed) add_computed(start);
  return ends;
}

}  // namespace

uint64_t label_hash(std::string_view name) {
  uint64_t h = 14695981039346656037ull;  // FNV-1a
  for (const char c : name) h = (h ^ uint8_t(upper(c))) * 1099511628211ull;
  return h & ((uint64_t(1) << 52) - 1);
}

uint64_t numbered_label_hash(uint64_t n) {
  char name[24] = {'L'};
  const std::to_chars_result r = std::to_chars(name + 1, name + sizeof name, n);
  return label_hash(std::string_view(name, size_t(r.ptr - name)));
}

bool calls_label(std::string_view line) {
  for (size_t i = 0; i < line.size(); ++i)
    if (upper(line[i]) == 'L' && (i == 0 || !is_letter(line[i - 1])))
      if (const auto r = label_repeat_at(line, i, line.size())) return r->second == 0;
  return false;
}

std::optional<uint64_t> number_key(double n) {
  if (!(n >= 0) || n != std::floor(n) || n >= 1e15) return std::nullopt;
  return uint64_t(n);
}

std::optional<uint64_t> jump_named(std::string_view line) {
  std::optional<uint64_t> named;
  auto add = [&](uint64_t number, size_t, bool call) {
    if (!call && !named) named = number;
  };
  auto add_computed = [](size_t) {};
  bool loops = false;
  read_line(line, 0, line.size(), add, add_computed, loops);
  return named;
}

bool jump_computed(std::string_view line) {
  bool computed = false, loops = false;
  auto add = [](uint64_t, size_t, bool) {};
  auto add_computed = [&](size_t) { computed = true; };
  read_line(line, 0, line.size(), add, add_computed, loops);
  return computed;
}

size_t JumpTargets::read(std::string_view text, uint32_t first_line, const PassedNumbers* passed) {
  size_t ended = std::string_view::npos;
  const size_t before = numbers_.size();
  // The line of a jump, counted only where one is found (most programs have none).
  size_t counted = 0;
  uint32_t counted_line = first_line;
  // (A line's jumps come in any order, `GOTO 10 .. M99 P20` noting M99's at the line's start:
  // a place before the one counted to is in the same line.)
  auto line_at = [&](size_t pos) {
    if (pos > counted) counted_line += uint32_t(std::count(text.begin() + long(counted), text.begin() + long(pos), '\n'));
    counted = std::max(counted, pos);
    return counted_line;
  };
  const size_t jumped_before = jumped_.size();
  auto add = [&](uint64_t number, size_t at, bool call) {
    const uint32_t line = line_at(at);
    if (!late_ && passed && passed->passed(number)) late_ = Late{line, number, false};
    numbers_.push_back(number);
    if (!call) jumped_.push_back(number);
  };
  auto add_computed = [&](size_t at) {
    const uint32_t line = line_at(at);
    if (!late_ && !computed_ && passed && passed->any()) late_ = Late{line, 0, true};
    computed_ = true;
  };
  // Only a line with an M or an O (of GOTO), either case, or a comma (Heidenhain's L1,2) can
  // hold a jump, and a loop only one with an O (LinuxCNC's O-words, Fanuc's DO1, Sinumerik's
  // LOOP and FOR), a `while` or Sinumerik's UNTIL: those are found by memchr, a byte at a time
  // only in such lines.
  constexpr int kKeyCount = 8;
  constexpr char kKeys[kKeyCount] = {'M', 'm', 'O', 'o', 'w', 'W', 'U', ','};
  size_t next[kKeyCount];
  const size_t n = text.size();
  auto find = [&](int k, size_t from) {
    const void* hit = from < n ? std::memchr(text.data() + from, kKeys[k], n - from) : nullptr;
    next[k] = hit ? size_t(static_cast<const char*>(hit) - text.data()) : n;
  };
  for (int k = 0; k < kKeyCount; ++k) find(k, 0);
  for (size_t from = 0;;) {
    const size_t at = *std::min_element(next, next + kKeyCount);
    if (at >= n) break;
    const size_t start = at == 0 ? 0 : text.rfind('\n', at - 1) + 1;  // (npos + 1 is 0)
    size_t end = text.find('\n', at);
    if (end == std::string_view::npos) end = n;
    if (start >= from && read_line(text, start, end, add, add_computed, loops_) && ended == std::string_view::npos)
      ended = std::min(end + 1, n);
    from = end + 1;
    for (int k = 0; k < kKeyCount; ++k)
      if (next[k] < from) find(k, from);
  }
  for (auto [list, size] : {std::pair{&numbers_, before}, std::pair{&jumped_, jumped_before}})
    if (list->size() != size) {
      std::sort(list->begin(), list->end());
      list->erase(std::unique(list->begin(), list->end()), list->end());
    }
  return ended;
}

void JumpTargets::merge(const JumpTargets& other) {
  if (!late_) late_ = other.late_;
  computed_ = computed_ || other.computed_;
  loops_ = loops_ || other.loops_;
  for (auto [to, from] : {std::pair{&numbers_, &other.numbers_}, std::pair{&jumped_, &other.jumped_}}) {
    if (from->empty()) continue;
    to->insert(to->end(), from->begin(), from->end());
    std::sort(to->begin(), to->end());
    to->erase(std::unique(to->begin(), to->end()), to->end());
  }
}

bool JumpTargets::only_called(uint64_t key) const {
  return !computed_ && enters(key) && !std::binary_search(jumped_.begin(), jumped_.end(), key);
}

bool JumpTargets::enters(uint64_t key) const {
  if (computed_ && !(key & kLabelKey)) return true;  // (a computed jump names a number)
  return std::binary_search(numbers_.begin(), numbers_.end(), key);
}

void PassedNumbers::pass(uint64_t key) {
  if (!(key & kLabelKey)) any_ = true;  // (what a computed jump may name)
  if (key >= kBits) {
    high_ = true;
    return;
  }
  if (bits_.size() <= key / 64) bits_.resize(key / 64 + 1);
  bits_[key / 64] |= uint64_t(1) << (key % 64);
}

bool PassedNumbers::passed(uint64_t key) const {
  if (key >= kBits) return high_;
  return key / 64 < bits_.size() && (bits_[key / 64] >> (key % 64)) & 1u;
}

}  // namespace arcpress
