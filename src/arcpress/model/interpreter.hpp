#pragma once
// Modal interpreter stage: blocks -> moves in absolute millimetres, tracking every modal
// group that changes how words are read. What it cannot evaluate (expressions, flow
// control, canned cycles, machine-coordinate moves) makes the position unknown and is a
// barrier that later stages never fit across.
#include "arcpress/core/diagnostic.hpp"
#include "arcpress/dialect/dialect.hpp"
#include "arcpress/lex/block.hpp"
#include "arcpress/model/move.hpp"

namespace arcpress {

/// Reads `program` as `dialect`'s controller would (centre form, G18 direction, numbers
/// without a decimal point); the default is generic RS274.
Interpretation interpret(const Program& program, DiagnosticSink& sink, const Dialect& dialect = Dialect{});

}  // namespace arcpress
