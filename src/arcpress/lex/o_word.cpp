// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/lex/o_word.hpp"

#include <utility>

#include "arcpress/lex/characters.hpp"

namespace arcpress {

OWord read_o_word(std::string_view line) {
  OWord w;
  size_t i = 0;
  auto skip_blanks = [&] {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
  };
  skip_blanks();
  if (i == line.size() || upper(line[i]) != 'O') return w;
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
      {"ENDREPEAT", K::EndRepeat}};
  for (const auto& [name, kind] : kKeywords)
    if (is(name)) w.kind = kind;
  return w;
}

}  // namespace arcpress
