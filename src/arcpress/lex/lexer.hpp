// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Lexer stage: bytes -> blocks. Never drops a byte: every line becomes a Block whose raw
// text is kept; what is not understood is marked Opaque and reported once per code.
#include <span>
#include <string_view>
#include <vector>

#include "arcpress/core/diagnostic.hpp"
#include "arcpress/lex/block.hpp"

namespace arcpress {

/// Lexes `text` (any line endings: LF, CRLF, none at the end) into a Program.
/// Diagnostics (codes E-LEX-*) go to `sink`; lexing always completes. `rules`: what the
/// program's dialect's lines hold (lex_rules()), kept as Program::rules.
Program lex(std::string name, std::string text, DiagnosticSink& sink, LexRules rules = {});

/// lex(), where the lines `copies` names (in order of their offsets) are said to be byte
/// copies of blocks of `source`: each such line whose bytes are that block's takes over its
/// words, kind and flags instead of being lexed again. Lexing reads nothing but a line's own
/// bytes, so the program is the one lex() makes; the lines not copied, those whose bytes
/// differ, blocks whose lexing reported a problem (so that every diagnostic is reported
/// again) and first lines (a byte-order mark) are lexed. It reads `source`'s rules, and takes its jumps.
Program lex(std::string name, std::string text, DiagnosticSink& sink, const Program& source,
            std::span<const CopiedLine> copies);

/// Lexes the one line of `program.text` at offsets [begin, end) (with its "\n", unless it is
/// the program's last line and has none) into a new block numbered `line`, for a program
/// that is read as it arrives.
void lex_line(Program& program, size_t begin, size_t end, uint32_t line, DiagnosticSink& sink);

/// Whether `line` is the comment arcpress writes after a slicer's first line to name itself,
/// its version and options ("; arcpress 0.1.0 --tolerance ..." or "(arcpress 0.1.0 ...)"):
/// no part of the program, which `arcpress diff` passes over and a second run does not repeat.
bool is_arcpress_header(std::string_view line);

}  // namespace arcpress
