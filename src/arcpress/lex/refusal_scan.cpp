// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/lex/refusal_scan.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <string_view>
#include <utility>
#include <vector>

namespace arcpress {
namespace {

/// A refused word as the dialect names it: a letter alone ("O": any O word) or a letter
/// with a value ("G90.1").
struct RefusedWord {
  char letter = 0;
  bool any_value = true;
  double value = 0;
};

std::vector<RefusedWord> parse_refused(const Dialect& d) {
  std::vector<RefusedWord> out;
  for (const auto& code : d.refused) {
    if (code.empty() || code == "%") continue;
    RefusedWord r{char(std::toupper(static_cast<unsigned char>(code[0]))), code.size() == 1, 0};
    if (!r.any_value) {
      char* end = nullptr;
      r.value = std::strtod(code.c_str() + 1, &end);
      if (*end != '\0') continue;  // not a word: nothing in a program can match it
    }
    out.push_back(r);
  }
  return out;
}

/// Where a line's first '(' comment and its ';' comment open, as the lexer reads them: a
/// '(' inside a ';' comment, or a ';' inside '( )', opens nothing. npos where none opens.
std::pair<size_t, size_t> comment_openers(std::string_view raw) {
  size_t paren = std::string_view::npos;
  bool in_paren = false;
  for (size_t k = 0; k < raw.size(); ++k) {
    const char c = raw[k];
    if (in_paren) {
      in_paren = c != ')';
    } else if (c == '(') {
      in_paren = true;
      if (paren == std::string_view::npos) paren = k;
    } else if (c == ';') {
      return {paren, k};
    }
  }
  return {paren, std::string_view::npos};
}

}  // namespace

void scan_refusals(const Program& program, const Dialect& dialect, DiagnosticSink& sink) {
  const bool percent = dialect.refuses("%");
  const std::vector<RefusedWord> refused = parse_refused(dialect);
  for (const Block& b : program.blocks) {
    if (b.kind == BlockKind::Percent && percent)
      sink.warning({b.line, 1}, "W-DIALECT-REFUSED",
                   fmt::format("'%' is refused by {}; the line is passed through unchanged", dialect.name));
    for (const Word* w = program.words_begin(b); w != program.words_end(b); ++w)
      for (const auto& r : refused)
        if (!w->is_expr && w->letter == r.letter && (r.any_value || std::abs(w->value - r.value) < 1e-6))
          sink.warning({b.line, w->col}, "W-DIALECT-REFUSED",
                       fmt::format("'{}' is refused by {}; the block is passed through unchanged",
                                   program.raw(b, *w), dialect.name));
    if (b.has_comment) {
      const auto [paren, semi] = comment_openers(program.raw(b));
      if (paren != std::string_view::npos && !dialect.paren_comments)
        sink.warning({b.line, uint32_t(paren + 1)}, "W-DIALECT-COMMENT",
                     fmt::format("{} does not read '( )' as a comment", dialect.name));
      if (semi != std::string_view::npos && !dialect.semicolon_comments)
        sink.warning({b.line, uint32_t(semi + 1)}, "W-DIALECT-COMMENT",
                     fmt::format("{} does not read ';' as a comment (it ends the block there)", dialect.name));
    }
  }
}

}  // namespace arcpress
