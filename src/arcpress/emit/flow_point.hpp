// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The blocks after which a program may go on from elsewhere than the next line: where the
// output's modal motion must be the input's again (the emitter states it there).
#include "arcpress/dialect/dialect.hpp"
#include "arcpress/lex/block.hpp"

namespace arcpress {

/// Whether block `b` of `program` calls, returns or jumps (M97, M98, M99; where `dialect`
/// reads an M-code as a loop, M808; where it has indented blocks, RepRapFirmware's `break`
/// and `continue`), after which the program goes on from elsewhere.
bool jumps_elsewhere(const Program& program, const Block& b, const Dialect& dialect);

/// Where block `b` of `program` ends blocks of blanks (Dialect::indented_blocks: it is indented
/// less than the last line before it that counts, BlockNesting::indent_of()), that line, which
/// is in them; else null.
const Block* closes_indented(const Program& program, const Block& b);

}  // namespace arcpress
