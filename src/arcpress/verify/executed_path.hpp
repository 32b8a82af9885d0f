// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The path a firmware really moves along: each arc of an interpreted program replaced by the
// chords its rule cuts it into (dialect/arc_segmentation.hpp). `arcpress diff --executed`
// and the compressor's check with --band executed measure these paths instead of the
// programmed circles.
#include "arcpress/dialect/arc_segmentation.hpp"
#include "arcpress/model/move.hpp"

namespace arcpress {

/// Whether `in` moves otherwise than programmed under `rule`: a placed arc, and a rule.
bool has_executed_chords(const Interpretation& in, const ArcSegmentation& rule);

/// `in` with every placed arc move replaced by the straight moves the firmware of `rule`
/// makes of it: equal turns about the centre, the normal axis, E and the other axes carried
/// evenly, the last chord ending exactly at the arc's end. Each chord keeps the arc's
/// block, frame, feed and S; the block's entry in move_of_block names the last chord.
/// A copy of `in` where has_executed_chords() is false.
Interpretation executed_path(const Interpretation& in, const ArcSegmentation& rule);

/// The path `in` executes under `rule`: `in` itself where that is the programmed path, else
/// executed_path() made into `storage`.
const Interpretation& executed_path(const Interpretation& in, const ArcSegmentation& rule, Interpretation& storage);

}  // namespace arcpress
