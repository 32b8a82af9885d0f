#pragma once
// Lexer stage: bytes -> blocks. Never drops a byte: every line becomes a Block whose raw
// text is kept; what is not understood is marked Opaque and reported once per code.
#include "arcpress/core/diagnostic.hpp"
#include "arcpress/lex/block.hpp"

namespace arcpress {

/// Lexes `text` (any line endings: LF, CRLF, none at the end) into a Program.
/// Diagnostics (codes E-LEX-*) go to `sink`; lexing always completes.
Program lex(std::string name, std::string text, DiagnosticSink& sink);

}  // namespace arcpress
