// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/emit/output_habits.hpp"

#include <algorithm>

namespace arcpress {

bool is_motion_gcode(double v) {
  int g = Word::code10_of(v);
  return g == 0 || g == 10 || g == 20 || g == 30 || (g >= 50 && g <= 53) || g == 330 || g == 331 ||
         (g >= 382 && g <= 385) || g == 730 || g == 760 || (g >= 800 && g <= 890 && g % 10 == 0);
}

OutputHabits output_habits(const Program& p) {
  OutputHabits h;
  size_t padded = 0, plain = 0, whole_point = 0, whole_bare = 0;
  for (const auto& b : p.blocks) {
    for (auto* w = p.words_begin(b); w != p.words_end(b); ++w)
      if (moves_axis(w->letter) && w->decimals == 0 && !w->is_expr && !w->flag) (w->has_point ? whole_point : whole_bare)++;
  }
  h.keep_point = whole_point > 0 && whole_bare == 0;
  for (const auto& b : p.blocks) {
    for (auto* w = p.words_begin(b); w != p.words_end(b); ++w) {
      if (w->letter != 'G' || w->is_expr || !is_motion_gcode(w->value)) continue;
      auto t = p.raw(b, *w);
      (t.size() >= 3 && t[1] == '0' && t[2] >= '0' && t[2] <= '3') ? ++padded : ++plain;
    }
    if (padded + plain > 200) break;
  }
  h.padded = padded > plain;
  // Signs and block ends as most of the program writes them (Heidenhain ISO: "X+10 *").
  size_t plus = 0, unsigned_positive = 0, ended = 0, open = 0;
  for (const auto& b : p.blocks) {
    if (b.kind != BlockKind::Code) continue;
    (b.block_end ? ended : open)++;
    for (auto* w = p.words_begin(b); w != p.words_end(b); ++w)
      if (moves_axis(w->letter) && !w->is_expr && !w->flag && w->value >= 0) (w->plus ? plus : unsigned_positive)++;
  }
  h.plus_sign = plus > unsigned_positive;
  h.block_end = ended > open;
  return h;
}

BlockStyle block_style(const Program& p, const Block& b, const OutputHabits& habits) {
  BlockStyle s;
  s.padded = habits.padded;
  for (char c : p.raw(b)) {
    if (c >= 'a' && c <= 'z') {
      s.lower = true;
      break;
    }
    if (c >= 'A' && c <= 'Z') break;
  }
  s.spaced = b.word_count < 2 || p.words_begin(b)[1].col - 1 > p.words_begin(b)[0].col - 1 + p.words_begin(b)[0].length;
  s.keep_point = habits.keep_point;
  s.plus = habits.plus_sign;
  for (auto* w = p.words_begin(b); w != p.words_end(b); ++w) {
    if (w->letter == 'G' && !w->is_expr && is_motion_gcode(w->value)) {
      auto t = p.raw(b, *w);
      s.padded = t.size() >= 3 && t[1] == '0';
      break;
    }
  }
  return s;
}

std::string_view block_indent(const Program& p, const Block& b) {
  const std::string_view raw = p.raw(b);
  return raw.substr(0, std::min(raw.find_first_not_of(" \t"), raw.size()));
}

}  // namespace arcpress
