#include "arcpress/extract/run.hpp"

namespace arcpress {

std::vector<Run> extract_runs(const Interpretation& in, uint32_t min_moves) {
  std::vector<Run> runs;
  const auto& mv = in.moves;
  size_t i = 0;
  while (i < mv.size()) {
    if (!mv[i].fittable) {
      ++i;
      continue;
    }
    size_t j = i + 1;
    while (j < mv.size() && mv[j].fittable && mv[j].block == mv[j - 1].block + 1 &&
           mv[j].frame == mv[i].frame && mv[j].plane == mv[i].plane && mv[j].feed_mm_min == mv[i].feed_mm_min)
      ++j;
    // The first move must also follow its predecessor directly, or its start is not its block's.
    if (j - i >= min_moves) {
      Run r;
      r.first_move = uint32_t(i);
      r.move_count = uint32_t(j - i);
      r.frame = mv[i].frame;
      r.plane = mv[i].plane;
      r.feed_mm_min = mv[i].feed_mm_min;
      runs.push_back(r);
    }
    i = j;
  }
  return runs;
}

}  // namespace arcpress
