// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/emit/flow_point.hpp"

#include "arcpress/model/block_nesting.hpp"

namespace arcpress {

bool jumps_elsewhere(const Program& p, const Block& b, const Dialect& dialect) {
  if (dialect.indented_blocks && b.kind == BlockKind::HostCommand && BlockNesting::leaves_block(p.raw(b))) return true;
  for (auto* w = p.words_begin(b); w != p.words_end(b); ++w)
    if (w->letter == 'M' && !w->is_expr) {
      const int m = w->code10();
      const CodeMeaning* own = dialect.meaning_of('M', m);
      if (own ? *own == CodeMeaning::Loop : m == 970 || m == 980 || m == 990) return true;
    }
  return false;
}

const Block* closes_indented(const Program& p, const Block& b) {
  const int32_t indent = BlockNesting::indent_of(p.raw(b));
  if (indent < 0) return nullptr;
  for (const Block* k = &b; k-- > p.blocks.data();)
    if (const int32_t before = BlockNesting::indent_of(p.raw(*k)); before >= 0) return before > indent ? k : nullptr;
  return nullptr;
}

}  // namespace arcpress
