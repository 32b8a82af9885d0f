// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Fitting stage: a run of G1 moves becomes the fewest lines and arcs inside the band.
// Never fails and never throws: where no arc fits, the input's own lines are the answer.
#include <functional>
#include <span>
#include <vector>

#include "arcpress/extract/run.hpp"
#include "arcpress/fit/primitive.hpp"

namespace arcpress {

/// The most (mm) a plane's normal axis may spread over a stretch for every primitive fitted
/// there to carry it, linearly along the primitive, inside the normal-axis share of the band:
/// that share with helical motion allowed (`o.helical`), else 0 (a fixed coordinate only).
double normal_axis_spread_mm(const FitOptions& o);

/// Fits the runs of `chain` (out of `runs`, as chain_runs() grouped them) together: one result
/// per run of the chain, in order. Lone moves and input arcs of the chain stay as they are,
/// and the joints with them and between runs are tangent where the path is smooth. Runs in
/// another plane than the chain's are fitted first, together with the others in their
/// plane (tangent to each other across the moves between them, as seen in that plane); then
/// the runs in the chain's plane, tangent to their end lines. `options_for` gives the
/// options for fitting in a run's frame and plane. Where `baseline_for` is given and gives
/// other options, every limit of them as tight as `options_for`'s or tighter (the defaults,
/// where the user loosened one), the chain is fitted under those too and that fit kept where
/// it has fewer forced kinks, or as many and fewer primitives: every chain they allow the
/// looser options allow, so loosening a limit never costs kinks or, with as many, blocks.
std::vector<FitResult> fit_chain(const Interpretation& in, const RunChain& chain, std::span<const Run> runs,
                                 const std::function<FitOptions(const Run&)>& options_for,
                                 const std::function<FitOptions(const Run&)>& baseline_for = {});

}  // namespace arcpress
