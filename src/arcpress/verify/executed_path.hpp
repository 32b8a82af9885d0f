#pragma once
// The path a firmware really moves along: each arc of an interpreted program replaced by the
// chords its rule cuts it into (dialect/arc_segmentation.hpp). `arcpress diff --executed`
// and the compressor's check with --band executed measure these paths instead of the
// programmed circles.
#include "arcpress/dialect/arc_segmentation.hpp"
#include "arcpress/model/move.hpp"

namespace arcpress {

/// `in` with every placed arc move replaced by the straight moves the firmware of `rule`
/// makes of it: equal turns about the centre, the normal axis, E and the other axes carried
/// evenly, the last chord ending exactly at the arc's end. Each chord keeps the arc's
/// block, frame, feed and S; the block's entry in move_of_block names the last chord.
/// Unchanged for Rule::None or a program without arcs.
Interpretation executed_path(const Interpretation& in, const ArcSegmentation& rule);

}  // namespace arcpress
