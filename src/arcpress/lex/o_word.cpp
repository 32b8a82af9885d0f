// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/lex/o_word.hpp"

#include <utility>

#include "arcpress/lex/characters.hpp"

namespace arcpress {

namespace {

/// Fanuc's and Haas's macro loops: `WHILE [condition] DO1` .. `END1`, and `DO1` .. `END1`, a loop
/// a GOTO leaves (after blanks, a block delete and a block number, from `i`).
OWord read_macro_loop(std::string_view line, size_t i) {
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

OWord read_o_word(std::string_view line) {
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
  if (upper(line[i]) != 'O') return read_macro_loop(line, i);
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
