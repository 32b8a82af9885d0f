// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/lex/o_word.hpp"

#include <algorithm>
#include <utility>

#include "arcpress/lex/characters.hpp"

namespace arcpress {

namespace {

/// Labels of Sinumerik's blocks, which nest by their keywords (`WHILE` .. `ENDWHILE`): one per
/// kind, kept apart from Fanuc's numbers and LinuxCNC's hashes.
constexpr uint32_t kSinumerikWhile = 0x53570001, kSinumerikLoop = 0x53570002, kSinumerikFor = 0x53570003,
                   kSinumerikRepeat = 0x53570004, kSinumerikIf = 0x53570005;

/// Whether `line` holds `name` (upper case) in any case.
bool holds(std::string_view line, std::string_view name) {
  for (size_t at = 0; at + name.size() <= line.size(); ++at) {
    size_t j = 0;
    while (j < name.size() && upper(line[at + j]) == name[j]) ++j;
    if (j == name.size()) return true;
  }
  return false;
}

/// Fanuc's and Haas's macro loops: `WHILE [condition] DO1` .. `END1`, and `DO1` .. `END1`, a loop
/// a GOTO leaves; Sinumerik's blocks: `WHILE condition` .. `ENDWHILE`, `LOOP` .. `ENDLOOP`,
/// `FOR R1=0 TO 5` .. `ENDFOR`, `REPEAT` .. `UNTIL condition`, and `IF condition` .. `ELSE` ..
/// `ENDIF` (an `IF` with a `GOTO` or a `THEN` is a line of its own). After blanks, a block
/// delete and a block number, from `i`.
/// Sinumerik's block line at `i` of `line`, else Kind::Other.
OWord read_keyword_block(std::string_view line, size_t i) {
  using K = OWord::Kind;
  auto is = [&](std::string_view name) {  // `name` at i, a word of its own
    if (line.size() - i < name.size()) return false;
    for (size_t j = 0; j < name.size(); ++j)
      if (upper(line[i + j]) != name[j]) return false;
    const size_t end = i + name.size();
    return end == line.size() || !(is_alpha(line[end]) || is_digit(line[end]) || line[end] == '_');
  };
  static constexpr struct {
    std::string_view name;
    K kind;
    uint32_t label;
  } kKeywords[] = {{"ENDWHILE", K::EndWhile, kSinumerikWhile}, {"ENDLOOP", K::EndWhile, kSinumerikLoop},
               {"ENDFOR", K::EndWhile, kSinumerikFor},     {"UNTIL", K::EndRepeat, kSinumerikRepeat},
               {"ENDIF", K::EndIf, kSinumerikIf},          {"ELSE", K::Else, kSinumerikIf},
               {"LOOP", K::Repeat, kSinumerikLoop},        {"FOR", K::Repeat, kSinumerikFor}};
  for (const auto& k : kKeywords)
    if (is(k.name)) return {k.kind, k.label};
  const size_t after = line.find_first_not_of(" \t\r", std::min(line.size(), i + 6));
  if (is("REPEAT") && (after == std::string_view::npos || line[after] == ';'))  // (`REPEAT LABEL1 P=2`: a section)
    return {K::Repeat, kSinumerikRepeat};
  if (is("IF") && !holds(line, "GOTO") && !holds(line, "THEN")) return {K::If, kSinumerikIf};
  const size_t c = line.find_first_not_of(" \t", std::min(line.size(), i + 5));
  if (is("WHILE") && c < line.size() && line[c] != '[') return {K::While, kSinumerikWhile};  // (Fanuc's: `WHILE [..] DO1`)
  return {};
}

OWord read_macro_loop(std::string_view line, size_t i, bool keyword_blocks) {
  if (keyword_blocks)
    if (const OWord k = read_keyword_block(line, i); k.kind != OWord::Kind::Other) return k;
  OWord w;
  auto skip_blanks = [&] {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
  };
  auto word = [&](std::string_view name) {  // `name` (upper case) at i, in any case
    if (line.size() - i < name.size()) return false;
    for (size_t j = 0; j < name.size(); ++j)
      if (upper(line[i + j]) != name[j]) return false;
    i += name.size();
    return true;
  };
  auto number = [&](OWord::Kind kind) {  // the loop's number after DO or END: its label
    skip_blanks();
    uint32_t n = 0;
    const size_t from = i;
    for (; i < line.size() && is_digit(line[i]) && n < 1000; ++i) n = n * 10 + uint32_t(line[i] - '0');
    if (i > from) w = {kind, 0x9E3779B9u ^ n};
  };
  if (word("WHILE")) {
    skip_blanks();
    if (i == line.size() || line[i] != '[') return w;
    for (int depth = 0; i < line.size(); ++i) {
      depth += line[i] == '[' ? 1 : line[i] == ']' ? -1 : 0;
      if (depth == 0) break;
    }
    ++i;
    skip_blanks();
    if (word("DO")) number(OWord::Kind::While);
  } else if (word("DO")) {
    number(OWord::Kind::Do);
  } else if (word("END")) {
    number(OWord::Kind::EndWhile);
  }
  return w;
}

}  // namespace

OWord read_o_word(std::string_view line, bool keyword_blocks) {
  OWord w;
  size_t i = 0;
  auto skip_blanks = [&] {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
  };
  skip_blanks();
  if (i < line.size() && line[i] == '/') ++i, skip_blanks();
  if (i < line.size() && upper(line[i]) == 'N')
    for (++i; i < line.size() && (is_digit(line[i]) || line[i] == ' ' || line[i] == '\t');) ++i;
  if (i == line.size()) return w;
  if (upper(line[i]) != 'O') return read_macro_loop(line, i, keyword_blocks);
  ++i;
  skip_blanks();
  // The label: digits (leading zeros and blanks do not count: `o0100` is `o100`), or a name
  // in angle brackets (case and blanks do not count, as LinuxCNC reads it).
  uint32_t h = 2166136261u;
  auto mix = [&](char c) { h = (h ^ uint8_t(c)) * 16777619u; };
  if (i < line.size() && line[i] == '<') {
    mix('<');
    for (++i; i < line.size() && line[i] != '>'; ++i)
      if (line[i] != ' ' && line[i] != '\t') mix(char(upper(line[i])));
    if (i == line.size()) return w;
    ++i;
  } else {
    bool leading = true;
    for (; i < line.size() && (is_digit(line[i]) || line[i] == ' ' || line[i] == '\t'); ++i) {
      if (!is_digit(line[i]) || (leading && line[i] == '0')) continue;
      leading = false;
      mix(line[i]);
    }
  }
  w.label = h;
  skip_blanks();
  size_t e = i;
  while (e < line.size() && is_alpha(line[e])) ++e;
  std::string_view k = line.substr(i, e - i);
  auto is = [&](std::string_view name) {
    if (k.size() != name.size()) return false;
    for (size_t j = 0; j < k.size(); ++j)
      if (upper(k[j]) != name[j]) return false;
    return true;
  };
  using K = OWord::Kind;
  static constexpr std::pair<std::string_view, K> kKeywords[] = {
      {"SUB", K::Sub},        {"ENDSUB", K::EndSub}, {"RETURN", K::Return}, {"CALL", K::Call},
      {"IF", K::If},          {"ELSEIF", K::ElseIf}, {"ELSE", K::Else},     {"ENDIF", K::EndIf},
      {"WHILE", K::While},    {"ENDWHILE", K::EndWhile}, {"DO", K::Do},     {"REPEAT", K::Repeat},
      {"ENDREPEAT", K::EndRepeat}, {"CONTINUE", K::Continue}};
  for (const auto& [name, kind] : kKeywords)
    if (is(name)) w.kind = kind;
  return w;
}

}  // namespace arcpress
