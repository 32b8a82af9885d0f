#pragma once
// Fitting stage: a run of G1 moves becomes the fewest lines and arcs inside the band.
// Never fails and never throws: where no arc fits, the input's own lines are the answer.
#include "arcpress/extract/run.hpp"
#include "arcpress/fit/primitive.hpp"

namespace arcpress {

FitResult fit_run(const Interpretation& in, const Run& run, const FitOptions& opt);

}  // namespace arcpress
