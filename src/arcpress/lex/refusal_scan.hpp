// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What in a program the target controller will not read: words its dialect refuses ("%",
// "O", "G90.1") and comments in a form it does not treat as comments. arcpress passes such
// blocks through unchanged (they are the user's), so each finding is a warning with its place.
#include "arcpress/core/diagnostic.hpp"
#include "arcpress/dialect/dialect.hpp"
#include "arcpress/lex/block.hpp"

namespace arcpress {

/// Warns (W-DIALECT-REFUSED, W-DIALECT-COMMENT) about what `dialect` refuses in `program`.
void scan_refusals(const Program& program, const Dialect& dialect, DiagnosticSink& sink);

}  // namespace arcpress
