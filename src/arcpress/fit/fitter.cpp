#include "arcpress/fit/fitter.hpp"

namespace arcpress {

FitResult fit_run(const Interpretation&, const Run& run, const FitOptions&) {
  FitResult r;
  r.prims.reserve(run.move_count);
  for (uint32_t v = 1; v <= run.move_count; ++v) r.prims.push_back({v, Primitive::Kind::Line});
  return r;
}

}  // namespace arcpress
