// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The feed check of arcpress diff: each piece of B's feed path paired with the piece of A's
// it stands for, in program order, and the two moves' feed and S handed on to compare.
#include <cstdint>
#include <functional>

#include "arcpress/model/move.hpp"
#include "arcpress/verify/feed_path.hpp"
#include "arcpress/verify/segment_index.hpp"

namespace arcpress {

/// What the feed check compared of B's feed path.
struct FeedCompared {
  double share = 1;           ///< by length, the share whose feed was compared
  double unpaired_mm = 0;     ///< the length within the band of A with no counterpart on it
  uint32_t unpaired_move = UINT32_MAX;  ///< the first B move with such a piece
};

/// Called with A's move, B's move and the point of B where their feed is compared.
using FeedVisit = std::function<void(const Move& a, const Move& b, const Vec3& at)>;

/// Pairs each of B's segments with its counterpart on A for the feed check, in program
/// order, at the middle of the B segment (away from the joints, where two moves meet). Both
/// paths are counted along from where they were last at the same place: a B move that starts
/// on a vertex of A, or else the last pair. The counterpart is, of the A segments within the
/// band of that middle and printing as it does: of those within a band's width along A of
/// where the piece lies along B, the one nearest that place that does not run against the
/// piece, else the nearest; else the one paired last or the next, where it runs roughly the
/// same way, or, for a piece of an arc that lies over one of them, that one while the piece
/// does not run against it; else the first ahead within a window that runs roughly the same way, or the
/// nearest anywhere if it lies ahead and runs the same way; else the nearest in the stretch
/// of A, from the last pair on, that lies within the band of the piece's whole move. Travel
/// that retraces a printed line elsewhere in the program, or a line printed a layer later
/// within a wide band, is thus not taken for it. A B segment with no counterpart is not
/// compared, and is counted where it lies within the band of A's path (beyond it, the path
/// measure finds B different); nor is one whose counterpart's point lies within a band's
/// width, along A's path, of a joint where A's feed changes. `visit(a_move, b_move, point)`.
FeedCompared compare_feed(const FeedPath& pa, const Interpretation& ia, const FeedPath& pb, const Interpretation& ib,
                          const SegmentIndex& index_a, double tolerance_mm, const FeedVisit& visit);

}  // namespace arcpress
