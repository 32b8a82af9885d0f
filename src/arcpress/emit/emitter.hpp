#pragma once
// Emission stage: the program text again, with each run replaced by its primitives.
// Blocks outside runs, and single-move lines the fitter kept, are copied byte for byte;
// new blocks copy the look of the blocks they replace (case, spacing, G1 vs G01, the
// input's own number text for every coordinate that comes from the input).
#include <string>
#include <vector>

#include "arcpress/extract/run.hpp"
#include "arcpress/fit/primitive.hpp"
#include "arcpress/lex/block.hpp"

namespace arcpress {

struct EmitStats {
  size_t runs = 0;
  size_t moves_in = 0;    ///< G1 moves inside runs
  size_t lines_out = 0;   ///< G1 blocks written for runs (copied or new)
  size_t arcs_out = 0;    ///< G2/G3 blocks written
  size_t motion_words_added = 0;  ///< copied blocks that needed their motion word restated
};

/// `band_mm` is the tolerance the fit was made for: arc centres are printed with enough
/// digits that rounding them moves the arc by at most 1.5 % of it (the fitter keeps 3 % back).
std::string emit_program(const Program& program, const Interpretation& in, const std::vector<Run>& runs,
                         const std::vector<FitResult>& fits, double band_mm = 0.01, EmitStats* stats = nullptr);

}  // namespace arcpress
