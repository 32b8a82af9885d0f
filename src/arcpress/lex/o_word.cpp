// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/lex/o_word.hpp"

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
  if (is("SUB")) w.kind = OWord::Kind::Sub;
  else if (is("ENDSUB")) w.kind = OWord::Kind::EndSub;
  else if (is("RETURN")) w.kind = OWord::Kind::Return;
  else if (is("CALL")) w.kind = OWord::Kind::Call;
  else if (is("IF")) w.kind = OWord::Kind::If;
  else if (is("ELSEIF")) w.kind = OWord::Kind::ElseIf;
  else if (is("ELSE")) w.kind = OWord::Kind::Else;
  else if (is("ENDIF")) w.kind = OWord::Kind::EndIf;
  else if (is("WHILE")) w.kind = OWord::Kind::While;
  else if (is("ENDWHILE")) w.kind = OWord::Kind::EndWhile;
  else if (is("DO")) w.kind = OWord::Kind::Do;
  else if (is("REPEAT")) w.kind = OWord::Kind::Repeat;
  else if (is("ENDREPEAT")) w.kind = OWord::Kind::EndRepeat;
  return w;
}

}  // namespace arcpress
