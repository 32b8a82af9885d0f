// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/model/unread_line.hpp"

#include "arcpress/lex/characters.hpp"
#include "arcpress/model/called_programs.hpp"
#include "arcpress/model/subroutines.hpp"

namespace arcpress {

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
    if ((upper(c) != 'G' && upper(c) != 'M') || (i > 0 && (is_alpha(raw[i - 1]) || is_digit(raw[i - 1]) || raw[i - 1] == '_')))
      continue;
    size_t k = i + 1;
    while (k < n && (raw[k] == ' ' || raw[k] == '\t')) ++k;
    if (k < n && (is_alpha(raw[k]) || raw[k] == '_')) continue;  // a name: GOTOF, G_VAR
    int code10 = 0, digits = 0;
    for (; k < n && is_digit(raw[k]) && digits < 6; ++k, ++digits) code10 = code10 * 10 + (raw[k] - '0');
    code10 *= 10;
    if (k + 1 < n && raw[k] == '.' && is_digit(raw[k + 1])) code10 += raw[k + 1] - '0';
    if (upper(c) == 'M') {  // M82, M83: E's mode
      out |= code10 == 820 || code10 == 830 || digits == 0 ? kStatesExtrusion : 0;
      continue;
    }
    out |= digits == 0 ? kStatesAll : modes_set_by(code10, dialect);
    // (G90 and G91 set E's mode too, where the dialect's firmware reads it so)
    if ((out & kStatesDistance) && dialect.extrusion_distance == ExtrusionDistance::WithAxes) out |= kStatesExtrusion;
  }
  return out;
}

}  // namespace arcpress
