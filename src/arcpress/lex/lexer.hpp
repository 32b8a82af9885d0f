#pragma once
// Lexer stage: bytes -> blocks. Never drops a byte: every line becomes a Block whose raw
// text is kept; what is not understood is marked Opaque and reported once per code.
#include "arcpress/core/diagnostic.hpp"
#include "arcpress/lex/block.hpp"

namespace arcpress {

/// Lexes `text` (any line endings: LF, CRLF, none at the end) into a Program.
/// Diagnostics (codes E-LEX-*) go to `sink`; lexing always completes.
Program lex(std::string name, std::string text, DiagnosticSink& sink);

/// Lexes the one line of `program.text` that starts at offset `begin` (up to and with its
/// "\n", or to the end of the text) into a new block numbered `line`, for a program that is
/// read as it arrives. Returns the offset after the line.
size_t lex_line(Program& program, size_t begin, uint32_t line, DiagnosticSink& sink);

}  // namespace arcpress
