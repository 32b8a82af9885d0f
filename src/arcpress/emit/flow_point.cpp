// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/emit/flow_point.hpp"

#include "arcpress/emit/output_habits.hpp"

namespace arcpress {

bool jumps_elsewhere(const Program& p, const Block& b, const Dialect& dialect) {
  for (auto* w = p.words_begin(b); w != p.words_end(b); ++w)
    if (w->letter == 'M' && !w->is_expr) {
      const int m = w->code10();
      const CodeMeaning* own = dialect.meaning_of('M', m);
      if (own ? *own == CodeMeaning::Loop : m == 970 || m == 980 || m == 990) return true;
    }
  return false;
}

const Block* closes_indented(const Program& p, const Block& b) {
  auto width = [&](const Block& x) {  // (as RepRapFirmware counts: a tab to the next multiple of 4)
    uint32_t w = 0;
    for (char c : block_indent(p, x)) w = c == ' ' ? w + 1 : (w + 4) & ~3u;
    return w;
  };
  for (const Block* k = &b; k-- > p.blocks.data();)
    if (p.raw(*k).find_first_not_of(" \t\r") != std::string_view::npos) return width(*k) > width(b) ? k : nullptr;
  return nullptr;
}

}  // namespace arcpress
