#pragma once
// Modal interpreter stage: blocks -> moves in absolute millimetres, tracking every modal
// group that changes how words are read. What it cannot evaluate (expressions, flow
// control, canned cycles, machine-coordinate moves) makes the position unknown and is a
// barrier that later stages never fit across.
#include "arcpress/core/diagnostic.hpp"
#include "arcpress/lex/block.hpp"
#include "arcpress/model/move.hpp"

namespace arcpress {

Interpretation interpret(const Program& program, DiagnosticSink& sink);

}  // namespace arcpress
