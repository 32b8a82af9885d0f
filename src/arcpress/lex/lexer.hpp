#pragma once
// Lexer stage: bytes -> blocks. Never drops a byte: every line becomes a Block whose raw
// text is kept; what is not understood is marked Opaque and reported once per code.
#include "arcpress/core/diagnostic.hpp"
#include "arcpress/lex/block.hpp"

namespace arcpress {

/// Lexes `text` (any line endings: LF, CRLF, none at the end) into a Program.
/// Diagnostics (codes E-LEX-*) go to `sink`; lexing always completes.
Program lex(std::string name, std::string text, DiagnosticSink& sink);

/// Lexes the one line of `program.text` at offsets [begin, end) (with its "\n", unless it is
/// the program's last line and has none) into a new block numbered `line`, for a program
/// that is read as it arrives.
void lex_line(Program& program, size_t begin, size_t end, uint32_t line, DiagnosticSink& sink);

}  // namespace arcpress
