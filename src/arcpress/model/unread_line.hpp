// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What a line arcpress does not read may have changed: the interpreter keeps such a line as
// it is and forgets what its words could have set.
#include <cstdint>
#include <string_view>

#include "arcpress/dialect/dialect.hpp"

namespace arcpress {

/// The modes (kStates*: plane, units, G90/G91, modal motion, E's mode) that the G words of
/// `raw`, a line not read (BlockKind::Opaque), name, and its M82 or M83: a controller that
/// reads the line sets them there, so the moves after it are not placed (not fitted where they
/// extrude) until the program states them again. A G word whose
/// code is no plain number (`G#1`, `G[..]`) may name any of them. Words in the dialect's
/// comments, and the G of a longer name (`MSG`, `GOTOF`), are not G words.
uint8_t modes_named(std::string_view raw, const Dialect& dialect);

}  // namespace arcpress
