// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Exact-enough two-sided distance between a polyline and one line or arc: every input
// vertex and every point of every input segment to the primitive, and every point of the
// primitive to the polyline. Used by the fitter to accept a primitive and by the verifier
// to measure a whole program. Points are in plane coordinates: (first, second, normal).
#include <cmath>
#include <optional>
#include <span>

#include "arcpress/core/geometry.hpp"

namespace arcpress {

/// Share of the band by which reading a whole program back may misread a distance: the
/// verifier (and `arcpress diff`) follows each helix by chords within half of it (flat arcs
/// it measures as arcs), and ends its search for the largest distance within the other
/// half. The emitter holds what it prints this much inside the band, so that reading the
/// output back never finds it outside (an R-form arc printed to 3 decimals came out 0.99994
/// of the band, and `arcpress diff` read it at 1.0009).
inline constexpr double kReadingShare = 2e-3;

/// A circular (possibly helical) arc in plane coordinates.
struct ArcGeom {
  Vec2 center{0, 0};
  double radius_mm = 0;
  double start_angle = 0;  ///< radians, of the start point about the centre
  double sweep = 0;        ///< radians, > 0 counter-clockwise; |sweep| <= 2π
  double h0 = 0, h1 = 0;   ///< normal-axis height at start and end (helix)

  Vec3 point_at(double t) const {  ///< t in [0, 1] along the arc
    double a = start_angle + sweep * t;
    return {center.x() + radius_mm * std::cos(a), center.y() + radius_mm * std::sin(a), h0 + (h1 - h0) * t};
  }
  /// Builds the arc from start to end about `center`; `ccw` picks the direction; a start
  /// equal to the end is a full turn.
  static ArcGeom through(const Vec3& start, const Vec3& end, const Vec2& center, bool ccw);
  /// The sweep alone of the arc through() builds (radians, > 0 counter-clockwise).
  static double sweep_of(const Vec3& start, const Vec3& end, const Vec2& center, bool ccw);
};

struct Deviation {
  double max_mm = 0;     ///< the largest distance found, mm
  size_t at_index = 0;   ///< polyline vertex (or segment start) where it occurs
  bool ordered = true;   ///< false: the polyline does not advance monotonically along the primitive
};

/// Two-sided deviation between the polyline `pts` and the segment pts.front() -> pts.back().
/// Both measures stop early, with a result above `stop_above_mm`, once the deviation
/// exceeds it (the fitter only needs to know that a candidate fails); arc_deviation() may
/// then also return less than the largest distance when it does not exceed the stop (parts
/// of the arc that cannot reach it are not measured). The default measures it all.
Deviation line_deviation(std::span<const Vec3> pts, double stop_above_mm = HUGE_VAL);
/// Two-sided deviation between the polyline `pts` and `arc` (which should start at
/// pts.front() and end at pts.back()).
Deviation arc_deviation(std::span<const Vec3> pts, const ArcGeom& arc, double stop_above_mm = HUGE_VAL);

/// Which side of the input path the output may lie on (--band-side), relative to the
/// direction of travel in the plane (left: counter-clockwise of it, seen from the plane's
/// normal, as G41 and G3 count). Both: either, the band's whole width.
enum class BandSide { Both, Left, Right };

/// How far the polyline `pts` (in the plane: x and y) lies on the side of a primitive that
/// `side` forbids it, in mm; 0 where it lies on the allowed side or on the primitive. The
/// primitive replaces the polyline, from its first point to its last: with Left the
/// primitive must lie left of the polyline, so the polyline must lie right of it. The
/// primitive is the line through the polyline's ends, or the circle about `centre` through
/// them (`ccw`: the way it turns); the offset is measured from the whole line or circle,
/// exactly: at the vertices, and at each segment's point nearest the centre, where its
/// offset from a circle is extreme.
double wrong_side_of_line_mm(std::span<const Vec3> pts, BandSide side);
double wrong_side_of_arc_mm(std::span<const Vec3> pts, const Vec2& centre, bool ccw, BandSide side);
/// The same measure by angles (atan2, sin, cos) for any arc and polyline, helices included.
/// arc_deviation() uses it for helices and polylines off the arc's plane, and a faster
/// trigonometry-free form of it otherwise. Off the plane, each segment and the arc's piece
/// between its vertices' angles are matched by share, and the largest gap between matched
/// points (within 1e-9 mm) stands for the distance both ways: never less than either.
Deviation arc_deviation_by_angles(std::span<const Vec3> pts, const ArcGeom& arc, double stop_above_mm = HUGE_VAL);
/// An upper bound (mm) of the two-sided distance between the polyline `pts` and the chords a
/// controller moves along in place of `arc`: from pts.front() through the chord ends `ends`
/// (in the plane, in order along the turn: a firmware's, executed_chord_ends()) to
/// pts.back() (arc and polyline share their ends, as a fitted arc does). The turn is cut at
/// every vertex's angle and every chord end's: each piece of the polyline lies beside one
/// chord and each piece of a chord beside one segment, and distance to a segment is convex
/// along a segment, so the pieces' ends bound both ways. Nothing for a helix, a whole turn,
/// or a polyline or chord ends that do not advance along the arc's turn; the measure stops
/// early, with a result above `stop_above_mm`, once it exceeds it.
std::optional<double> chords_deviation_bound(std::span<const Vec3> pts, const ArcGeom& arc, std::span<const Vec2> ends,
                                             double stop_above_mm = HUGE_VAL);
/// True when the path a -> b -> c has a real corner at b: it turns by more than
/// `corner_angle_deg`, or so sharply for its segment lengths that no tangent-continuous
/// path through b stays within `band_mm` of both segments. (With tangent T at b making
/// angles α1, α2 with the segments, the arcs through a and c bulge by about L·α/4; the best
/// split of the turn θ gives θ·L1·L2 / (4·(L1 + L2)).) Zero-length segments are corners.
bool is_corner(const Vec3& a, const Vec3& b, const Vec3& c, double band_mm, double corner_angle_deg);
/// The rule beside a corner, for a vertex b that is_corner() leaves smooth: `a_is_corner`,
/// `c_is_corner` say whether is_corner() holds at its neighbours a and c; `z` is the vertex
/// before a and `d` the one after c (null where the path ends). Next to a corner, say a, the
/// arc that rounds b must leave a and end following the path after b, which turns at c as it
/// does (its turn there is what a circle through the samples would turn too). What b turns
/// beyond that, δ, only the arc from a can take up, so b is a corner too when
/// |δ|·L / 4 > band, L the segment from a. Turns are signed in the first two coordinates
/// (the plane's). With corners on both sides the tangent is free at both: no extra corner.
bool is_corner_beside_corner(const Vec3* z, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3* d,
                             bool a_is_corner, bool c_is_corner, double band_mm);

/// Where along a block (its progress, 0 at its start to 1 at its end, with which the
/// controller carries the block's other axes, A/B/C and U/V/W, linearly) the tool passes
/// nearest a point, as far as moving the point, or the arc's centre, by `slack_mm` can move
/// that: one or two stretches of progress (two where an arc's window wraps past its start).
/// Around the point's foot on a line (`slack_mm` of the line's length either way), or its
/// direction from an arc's centre (the turn `slack_mm` makes at its distance); the whole arc
/// for a point within `slack_mm` of its centre, where every point of it is about as near.
/// The slack of the fitter's windows (ProgressWindow), as a share of its band.
inline constexpr double kFitNearShare = 0.01;
struct ProgressWindow {
  double lo[2] = {0, 0}, hi[2] = {0, 0};
  int count = 1;
  /// The least |v0 + t (v1 - v0) - target| for t in the window: how near the block carries
  /// an axis going from v0 to v1 to `target` while it passes within the band of the point.
  double least_gap(double v0, double v1, double target) const;
};
/// Along the line a-b (a line shorter than kLengthEpsMm: its start).
ProgressWindow line_progress_near(const Vec3& p, const Vec3& a, const Vec3& b, double slack_mm);
/// Along `arc`, p in its plane's coordinates, measured in the plane.
ProgressWindow arc_progress_near(const Vec3& p, const ArcGeom& arc, double slack_mm);

/// The point of the segment a-b nearest p (a, for a segment shorter than kLengthEpsMm).
Vec3 nearest_on_segment(const Vec3& p, const Vec3& a, const Vec3& b);
/// Distance from point p to the segment a-b.
double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b);

}  // namespace arcpress
