// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The path of one interpreted move, shared by the verifiers and the plot: an arc as an
// ArcGeom in its plane, any move as points along it, and a flat arc as pieces whose
// distance to a point is measured exactly.
#include <optional>
#include <utility>
#include <vector>

#include "arcpress/core/deviation.hpp"
#include "arcpress/model/move.hpp"

namespace arcpress {

/// Move i (an arc) in its plane's coordinates (first, second, normal). End points that
/// coincide in the plane make a full turn; a P word adds turns.
ArcGeom arc_of_move(const Interpretation& in, size_t i);

/// Where move i of `in` passes nearest `p` (XYZ), to within `slack_mm` (see ProgressWindow):
/// the shares of the move done there, with which the controller carries the move's other axes
/// (line_progress_near(), arc_progress_near(); an arc of more than one turn is read on its first).
ProgressWindow move_progress_near(const Interpretation& in, size_t i, const Vec3& p, double slack_mm);
/// The slack of the check's windows, as a share of the band: the fitter's (kFitNearShare of
/// its own band) and what printing the centre moves an arc (at most 1.5 % of the band) fit
/// inside it.
inline constexpr double kCheckNearShare = 0.1;

/// The length of move i's path (mm): a line's, or an arc's (a helix's climb included, every
/// turn of it).
double move_length_mm(const Interpretation& in, size_t i);

/// Whether any extra axis (A/B/C, U/V/W) moves anywhere in `in`.
bool extra_axes_move(const Interpretation& in);

/// The largest difference between the extra axes (A/B/C, U/V/W) of `x` and `y`, each in its
/// own unit (mm or degrees), and the axis where it is (kAxisLetters; -1 where none differ).
std::pair<double, int> extra_axes_apart(const AxisValues& x, const AxisValues& y);

/// The extra axes (A/B/C, U/V/W) of move i of `in` at `p`, a point of its path, carried from
/// its start to its end with its progress; the other axes as at its end.
AxisValues extra_axes_at(const Interpretation& in, size_t i, const Vec3& p);
/// How near move i of `in` carries its extra axes to `target`'s where it passes nearest `p`
/// (move_progress_near() with `slack_mm`, ProgressWindow::least_gap()): the largest such gap
/// of one axis, each in its own unit, and that axis (kAxisLetters; -1 where none is apart).
std::pair<double, int> extra_axes_gap(const Interpretation& in, size_t i, const Vec3& p, const AxisValues& target,
                                      double slack_mm);

/// An arc that bulges off its chord by no more than this (mm: a floating-point epsilon of
/// lengths, far below any band) is measured as its chord. An arc of a huge radius between
/// two near points is one, and its centre too far off for a double to place its points.
inline constexpr double kFlatArcMm = 1e-9;
/// How far arc `g` bulges off its chord (mm) where that is at most kFlatArcMm (a flat arc,
/// less than half a turn, in its plane), else infinity.
double flat_arc_sagitta_mm(const ArcGeom& g);

/// Most chords one arc is followed by: its radius and turns never set more work than this.
inline constexpr size_t kMaxChordsPerMove = 16384;

/// Appends the points of move i after its start, in XYZ: the end point for lines, chords of
/// sagitta at most `chord_mm` for arcs (an even count, so the arc's middle is a point) where
/// kMaxChordsPerMove allow it. Returns how far the chords lie from the arc at most, mm (0
/// for lines): above `chord_mm` only for an arc that big.
double move_path(const Interpretation& in, size_t i, double chord_mm, std::vector<Vec3>& out);

/// An arc that keeps its plane's normal axis still, for measuring exactly against pieces of
/// it: centre and height in XYZ (the normal axis's coordinate is the height), radius from
/// the start point, turning counter-clockwise about the plane's normal or not.
struct FlatArc {
  Plane plane = Plane::XY;
  Vec3 center{0, 0, 0};
  double radius_mm = 0;
  bool ccw = true;
};

/// Move i as pieces of a flat arc, when it is one (an arc whose normal axis does not move,
/// of one turn at most): appends the points after its start, each on the circle, the pieces
/// between them sweeping at most `max_sweep_rad`, and no longer than `max_piece_mm` and
/// lying no farther than `max_sagitta_mm` from their chords where `max_pieces` pieces allow
/// it (a huge radius gets longer pieces, never more of them), then the end point exactly as
/// read (a last straight step where rounding left it off the circle: `straight_end` is set).
/// Returns the arc, or nothing (and appends nothing) for other moves.
std::optional<FlatArc> arc_pieces(const Interpretation& in, size_t i, double max_sagitta_mm, double max_sweep_rad,
                                  double max_piece_mm, size_t max_pieces, std::vector<Vec3>& out, bool& straight_end);

/// The length of move i (mm) along the path arc_pieces() cuts it into, when it is a flat arc:
/// along the circle, and the last straight step where rounding left the end point off it.
/// Nothing for other moves. (The same sum as the pieces', without cutting them.)
std::optional<double> flat_arc_length_mm(const Interpretation& in, size_t i);

/// The point nearest `p` on the piece of `arc` from `a` to `b` (both on the circle, the
/// piece less than half a turn, in the arc's direction): exact.
Vec3 nearest_on_piece(const FlatArc& arc, const Vec3& a, const Vec3& b, const Vec3& p);

/// Whether `p` lies in the wedge of the piece from `a` to `b` about the arc's centre (seen
/// along the normal), where its nearest point on the circle lies on the piece.
bool in_wedge(const FlatArc& arc, const Vec3& a, const Vec3& b, const Vec3& p);

/// The point of the piece from `a` to `b` a fraction `t` of its sweep from `a`.
Vec3 point_on_piece(const FlatArc& arc, const Vec3& a, const Vec3& b, double t);

/// An upper bound of the distance to the piece from `a` to `b` of every point of the segment
/// from `p0` to `p1`, when both ends lie in the piece's wedge (then so does the segment, the
/// wedge being convex, and each of its points is as far from the piece as from the circle):
/// in the plane |ρ - r|, with ρ the distance from the centre, convex along the segment, so
/// largest at an end and smallest at the foot from the centre; along the normal, largest at
/// an end. Exact for a segment in the arc's plane. Nothing when an end lies outside.
std::optional<double> segment_to_piece_bound(const FlatArc& arc, const Vec3& a, const Vec3& b, const Vec3& p0,
                                             const Vec3& p1);

/// How far the piece from `a` to `b` lies from its chord at most (its sagitta), mm.
double piece_sagitta_mm(const FlatArc& arc, const Vec3& a, const Vec3& b);

}  // namespace arcpress
