#pragma once
// The path of one interpreted move, shared by the verifiers and the plot: an arc as an
// ArcGeom in its plane, and any move as points along it.
#include <vector>

#include "arcpress/core/deviation.hpp"
#include "arcpress/model/move.hpp"

namespace arcpress {

/// Move i (an arc) in its plane's coordinates (first, second, normal). End points that
/// coincide in the plane make a full turn; a P word adds turns.
ArcGeom arc_of_move(const Interpretation& in, size_t i);

/// Appends the points of move i after its start, in XYZ: the end point for lines, chords of
/// sagitta at most `chord_mm` for arcs (an even count, so the arc's middle is a point).
void move_path(const Interpretation& in, size_t i, double chord_mm, std::vector<Vec3>& out);

}  // namespace arcpress
