// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// One program's feed path as the verifier measures it: its feed moves cut into segments and
// pieces of flat arcs, by sections between rapids, with what could not be measured.
#include <array>
#include <cstdint>
#include <vector>

#include "arcpress/model/move.hpp"
#include "arcpress/verify/move_geometry.hpp"

namespace arcpress {

/// One program's feed path as segments: segment s runs from points[first[s]] to the point
/// after it, belongs to move move_of[s] and section section_of[s]; within a section the
/// segments follow each other along the path, each starting where the one before ends. A
/// flat arc is kept as pieces of itself (arc_of[s] names its arc) and measured exactly; other
/// arcs (helices, several turns) as chords.
struct FeedPath {
  static constexpr int32_t kStraight = -1, kClosingStep = -2;
  std::vector<Vec3> points;
  std::vector<uint32_t> first, move_of, section_of;
  /// Per segment: the arc it is a piece of, or kStraight, or kClosingStep: the step from a
  /// flat arc's last piece to its end point as read, where rounding left that off the circle
  /// (far shorter than the band, and of no direction of its own).
  std::vector<int32_t> arc_of;
  std::vector<FlatArc> arcs;
  double max_sagitta_mm = 0;    ///< the farthest any piece lies from its chord
  std::vector<double> section_length_mm, section_e;  ///< per section
  /// Per section, how far floating rounding can carry its E sum (mm): E is a running
  /// position, so each move's E is the difference of two numbers as large as that.
  std::vector<double> section_e_rounding_mm;
  /// Arcs whose chords lie farther than kRoughShare of the band from them (too big to follow
  /// within the measure's precision): not measured. The first one's move.
  size_t rough_arcs = 0;
  uint32_t first_rough_move = 0;
  /// Feed moves too far from the origin to measure (farthest_measurable_mm()): not measured. The first one.
  size_t far_moves = 0;
  uint32_t first_far_move = 0;
  /// How much farther than the measure's precision the chords of any other arc lie, mm.
  double chord_excess_mm = 0;
  /// The moves not measured (far from the origin, or arcs too big), as exact keys: where the
  /// other program has the very same moves, they are the same path and need no measure.
  std::vector<std::array<double, 12>> unmeasured;
  std::vector<uint32_t> rapids;                      ///< move indices of rapids whose end is known
  /// Move indices of feed moves from an unknown position to a known one.
  std::vector<uint32_t> entries;
  size_t feed_moves = 0;

  size_t size() const { return move_of.size(); }
  Vec3 a(size_t s) const { return points[first[s]]; }
  Vec3 b(size_t s) const { return points[first[s] + 1]; }
  bool curved(size_t s) const { return arc_of[s] >= 0; }
  const FlatArc& arc(size_t s) const { return arcs[size_t(arc_of[s])]; }
  /// The point of segment (or piece) s nearest p.
  Vec3 nearest(size_t s, const Vec3& p) const {
    return curved(s) ? nearest_on_piece(arc(s), a(s), b(s), p) : nearest_on_segment(p, a(s), b(s));
  }
  /// The middle of segment (or piece) s.
  Vec3 middle(size_t s) const { return curved(s) ? point_on_piece(arc(s), a(s), b(s), 0.5) : Vec3((a(s) + b(s)) / 2); }
  /// How far piece s lies from its chord (0 for a segment).
  double sagitta(size_t s) const { return curved(s) ? piece_sagitta_mm(arc(s), a(s), b(s)) : 0.0; }
  /// The segments that repeat no earlier one exactly (same ends, and the same arc or none),
  /// ascending: a path traced again adds none. One pass over an open-addressed table of the
  /// segments kept so far, by a hash of their key.
  std::vector<uint32_t> distinct_segments() const;

};


/// An arc whose chords (kMaxChordsPerMove of them) lie farther than this share of the band
/// from it is not measured: its own distance could not be told within the band.
constexpr double kRoughShare = 0.1;
/// Longest piece of a path put into the index, mm.
constexpr double kPieceMm = 10.0;
/// Most pieces one straight segment is cut into: past this a segment's pieces grow longer
/// than kPieceMm, so that its length never sets how much there is to measure.
constexpr int kMaxPiecesPerSegment = 64;
/// Most pieces (beyond those its sweep needs) one flat arc is cut into: past this its pieces
/// lie farther from their chords than the sagitta share, and the index reaches as much further.
constexpr size_t kMaxPiecesPerArc = 4096;
/// Largest sweep of a flat arc's piece: its chord runs within half of it of the arc's
/// direction, as the feed pairing's direction tests read it.
constexpr double kPieceSweepRad = 5 * kPi / 180;
/// How far a piece may lie from its chord, as a share of the band: the spatial index finds
/// pieces by their chords, so its searches reach this much further.
constexpr double kPieceSagittaShare = 0.5;

/// The feed path of `in`: arcs followed by chords within `chord_mm` of them or as pieces of
/// themselves, moves too far from the origin to measure for `tolerance_mm` left out and keyed.
/// Without `segments`, only what is not the path's points: sections, their lengths and E,
/// rapids, entries, the moves not measured (the whole-path measure's segments are not made).
FeedPath feed_path(const Interpretation& in, double chord_mm, double tolerance_mm, bool segments = true);

}  // namespace arcpress
