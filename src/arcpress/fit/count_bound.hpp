// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A lower bound on the primitives a fit can need, for judging the fitter's counts: the fewest
// lines and arcs (any radius, any sweep, tangent at their joints or not) whose joints are
// vertices of the polyline and which keep every vertex between, and every move's middle, within
// the band. The fitter's primitives are all of this kind (and held to more: every point of the
// moves between vertices, the joints' tangents, the options' limits), so no fit of the same
// polyline in the same band has fewer.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "arcpress/core/geometry.hpp"
#include "arcpress/fit/primitive.hpp"

namespace arcpress {

/// Vertices where every fit ends a primitive, whatever its shape: where the program between
/// two moves must stay as written (a feed change, a comment between them), or where
/// extrusion or an extra axis starts or stops (one block moves them linearly along it).
/// Per vertex of the polyline, nonzero: a primitive ends there; empty: none.
using PrimitiveEnds = std::span<const uint8_t>;

/// The fewest primitives as above over `pts` (the polyline's vertices in its plane, mm),
/// each vertex and each move's middle within `band_mm` (mm) of the circle or line of the
/// primitive spanning it, and none spanning a vertex of `ends`. Exact (dynamic programming over every pair of
/// vertices): O(n²) tests, most of them ended by the vertex that ended the test before, so
/// meant for curves of thousands of points.
size_t min_primitive_count(std::span<const Vec2> pts, double band_mm, PrimitiveEnds ends = {});

/// Tangents a chain of primitives keeps at its ends, where it joins a move that is not
/// fitted (an input arc, a lone line).
struct EndTangents {
  std::optional<Vec2> start, end;  ///< directions (any length); none: free
};

/// The fewest primitives as above that also join tangentially, each joint turning by at
/// most `g1_angle_deg`, each arc sweeping at most half a turn (the fitter's default limit)
/// and an arc over one move bulging by at most the band off it; 0 when no such chain
/// exists (a corner). The first primitive leaves, and the last arrives, within
/// `g1_angle_deg` of `joins` where they are given. Found breadth first over (vertex, tangent)
/// states, each tangent range taken once, by the first layer that reaches it; the
/// curvatures that keep the vertices in the band are bounded by half-planes over a tangent
/// range of at most a quarter degree, a piece of the range that arrived at the vertex (the
/// circle's bend over it allowed for), so a range is kept whenever some tangent in it could
/// be, and the count is still a lower bound.
/// A primitive ends at each vertex of `ends`, and the next one leaves within the G1 angle
/// of its end tangent.
size_t min_g1_primitive_count(std::span<const Vec2> pts, double band_mm, double g1_angle_deg,
                              const EndTangents& joins = {}, PrimitiveEnds ends = {});

/// min_g1_primitive_count() for the band and the G1 angle the fitter works to under `o`
/// (its tolerance_mm, g1_angle_deg and centre_step_mm): it keeps a share of each back for
/// rounding the printed arc centres (of the band, rounding_reserve_share(); of the angle at a
/// joint, all but kJointShare), so no fit of the same polyline without a forced kink has
/// fewer primitives. Where this lies above the full bound, the difference is what the
/// reserves cost, not what the search misses.
size_t min_g1_primitive_count_as_fitted(std::span<const Vec2> pts, const FitOptions& o, const EndTangents& joins = {},
                                        PrimitiveEnds ends = {});

/// min_primitive_count() in the band the fitter works to under `o`: no fit of the same
/// polyline has fewer primitives, kinked or not.
size_t min_primitive_count_as_fitted(std::span<const Vec2> pts, const FitOptions& o, PrimitiveEnds ends = {});

}  // namespace arcpress
