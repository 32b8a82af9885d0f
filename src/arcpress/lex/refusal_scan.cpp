#include "arcpress/lex/refusal_scan.hpp"

#include <fmt/format.h>

#include <cmath>

namespace arcpress {
namespace {

/// "G90.1" for a G word of value 90.1; "O" for any O word.
bool matches(const Word& w, std::string_view code) {
  if (code.empty() || w.is_expr || std::toupper(static_cast<unsigned char>(code[0])) != w.letter) return false;
  if (code.size() == 1) return true;
  double v = 0;
  try {
    v = std::stod(std::string(code.substr(1)));
  } catch (...) {
    return false;
  }
  return std::abs(w.value - v) < 1e-6;
}

}  // namespace

void scan_refusals(const Program& program, const Dialect& dialect, DiagnosticSink& sink) {
  const bool percent = dialect.refuses("%");
  for (const Block& b : program.blocks) {
    if (b.kind == BlockKind::Percent && percent)
      sink.warning({b.line, 1}, "W-DIALECT-REFUSED",
                   fmt::format("'%' is refused by {}; the line is passed through unchanged", dialect.name));
    for (const Word* w = program.words_begin(b); w != program.words_end(b); ++w)
      for (const auto& code : dialect.refused)
        if (code != "%" && matches(*w, code))
          sink.warning({b.line, w->col}, "W-DIALECT-REFUSED",
                       fmt::format("'{}' is refused by {}; the block is passed through unchanged",
                                   program.raw(b, *w), dialect.name));
    if (b.has_comment) {
      std::string_view raw = program.raw(b);
      size_t paren = raw.find('('), semi = raw.find(';');
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
