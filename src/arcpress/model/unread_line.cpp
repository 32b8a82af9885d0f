// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/model/unread_line.hpp"

#include "arcpress/lex/characters.hpp"
#include "arcpress/model/subroutines.hpp"

namespace arcpress {
namespace {

/// The modes G-code `code10` (the code times ten) sets, read as `dialect` reads it.
uint8_t modes_of(int code10, const Dialect& dialect) {
  if (const CodeMeaning* m = dialect.meaning_of('G', code10))
    return *m == CodeMeaning::Inch || *m == CodeMeaning::Mm ? kStatesUnits : 0;
  if (dialect.turn_reading(code10)) return kStatesMotion;
  switch (code10) {
    case 170: case 180: case 190: return kStatesPlane;
    case 200: case 210: return kStatesUnits;
    case 900: case 910: return kStatesDistance;
    case 0: case 10: case 20: case 30: case 50: case 51: case 52: case 53: case 330: case 331:
    case 382: case 383: case 384: case 385: case 730: case 760:
      return kStatesMotion;
    default: return code10 >= 800 && code10 <= 890 ? kStatesMotion : 0;  // canned cycles
  }
}

}  // namespace

uint8_t modes_named(std::string_view raw, const Dialect& dialect) {
  uint8_t out = 0;
  const size_t n = raw.size();
  for (size_t i = 0; i < n; ++i) {
    const char c = raw[i];
    if (c == ';' && dialect.semicolon_comments) break;
    if (c == '(' && dialect.paren_comments) {
      while (i < n && raw[i] != ')') ++i;
      continue;
    }
    if (upper(c) != 'G' || (i > 0 && (is_alpha(raw[i - 1]) || is_digit(raw[i - 1]) || raw[i - 1] == '_'))) continue;
    size_t k = i + 1;
    while (k < n && (raw[k] == ' ' || raw[k] == '\t')) ++k;
    if (k < n && (is_alpha(raw[k]) || raw[k] == '_')) continue;  // a name: GOTOF, G_VAR
    int code10 = 0, digits = 0;
    for (; k < n && is_digit(raw[k]) && digits < 6; ++k, ++digits) code10 = code10 * 10 + (raw[k] - '0');
    code10 *= 10;
    if (k + 1 < n && raw[k] == '.' && is_digit(raw[k + 1])) code10 += raw[k + 1] - '0';
    out |= digits == 0 ? kStatesAll : modes_of(code10, dialect);
  }
  return out;
}

}  // namespace arcpress
