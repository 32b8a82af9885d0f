// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// `arcpress diff --plot FILE.svg`: both feed paths projected on one plane, A thin and grey,
// B coloured by its local deviation from A, arcs drawn as SVG arcs, the worst place marked
// with its line numbers, and a legend with the band. Drawing is decimated (points closer
// than half a pixel are merged), never the measurement.
#include <string>

#include "arcpress/verify/diff_report.hpp"

namespace arcpress {

std::string diff_svg(const Interpretation& ia, const Interpretation& ib, const ProgramDiff& d, Plane plane,
                     double tolerance_mm, const DiffNames& names);

}  // namespace arcpress
