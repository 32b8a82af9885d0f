// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The limits and shares the fitter's searches work to (private to fit/): each says what it
// bounds, and where a figure chose it, the figure.
#include <cstddef>
#include <cstdint>
#include <limits>

namespace arcpress::fit_detail {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// In-plane and normal-axis shares of the band when a primitive moves along the normal axis:
/// 0.8² + 0.6² = 1, so the 3D distance stays inside the band.
constexpr double kPlaneShare = 0.8;
constexpr double kHeightShare = 0.6;
/// Seed 000: pieces of the line detection this short (in moves) are not split further
/// unless they leave the band.
constexpr uint32_t kLoweMinMoves = 2;
/// The default search's chain is searched again layer by layer (as the global method's) when
/// this many arcs in a row each turn the other way from the one before.
constexpr int kWiggleArcs = 4;
/// How far ahead (mm) the input must run straight for the beam to offer lines along tangents
/// turned by half the joint allowance (beam_chain()).
constexpr double kStraightAheadMm = 1.0;
/// The input's direction at a vertex, and whether it runs straight ahead, are read from at
/// most this many moves each way, however short they are: a plunge written as thousands of
/// steps along the plane's normal (no direction in the plane) would otherwise be read over
/// again from every one of its vertices.
constexpr uint32_t kLocalMoves = 256;
/// Primitives a forced kink must save, at the least, where a chain wiggles (see untangle()).
constexpr size_t kKinkWorth = 4;
/// How many wiggles after the first untangle() mends in the chain it tries after a kink.
constexpr int kUntangleDepth = 4;
/// Candidates per primitive whose next step is looked at before choosing.
constexpr int kLookahead = 6;
/// How far back (in vertices) from where the beam stalled a forced kink may be placed: the
/// restart's seeds (beam_stretch()).
constexpr uint32_t kKinkSeedMoves = 2;
/// Places in each layer of the beam for the chains whose last primitive ends furthest.
constexpr size_t kFurthestEnds = 2;
/// Bits of a vertex, and of a candidate's place, in the beam's one-integer ranking keys.
constexpr int kKeyBits = 21;
/// The beam's roots at a free start (start_tangents()): the edges of the ranges of start
/// tangents that reach each of the kNearStartEnds nearest ends and of the kFarStartEnds
/// furthest, taken kStartRangeInset of the range inside.
constexpr size_t kNearStartEnds = 4;
constexpr size_t kFarStartEnds = 2;
constexpr double kStartRangeInset = 0.05;
/// Splits of a stretch into two primitives checked exactly per start tangent when merging.
constexpr size_t kSplitsTried = 12;
/// tighten(): how many moves back, and on, a window that ends in an arc is tried ending
/// instead, the line after it starting there (an arc that ran on past its fillet along a
/// straight side: sqrt(2·R·band) is 28 moves of 0.05 mm at R = 40 mm and 0.025 mm).
constexpr uint32_t kLineShiftMoves = 32;
/// Layered search: a layer keeps one state per tangent bin (this share of the G1 angle wide)
/// in each of about kLayerGroups groups of vertices over the stretch the last layer advanced.
constexpr double kTangentBinShare = 0.5;
/// The beam and the first search: two chains whose end tangents at one vertex fall in one
/// bin this share of the G1 angle wide are one state (tangent_bin()).
constexpr double kEndBinShare = 0.125;
constexpr uint32_t kLayerGroups = 4;
/// Layered search: it gives up (and the beam's chain stands) past this many states per vertex.
constexpr size_t kMaxStatesPerVertex = 64;
/// Range search: tangents scanned per degree of a state's range of start tangents.
constexpr double kRangeSamplesPerDeg = 5;
/// The tangents fan_ends() scans together at most (the range search's samples, in groups).
constexpr int kFanLanes = 16;
/// Range search: the share of the joint allowance it carries from one primitive's end
/// tangents to the next one's starts (the rest is room for a line's chord, which leaves off
/// its scanned tangent, and for the start chosen between two samples).
constexpr double kRangeJointShare = 0.95;
/// Range search: exact checks per primitive the chain is read back with at most.
constexpr size_t kRangeChecksPerPrimitive = 256;
/// The default method also runs the range search on a stretch whose beam chain has no forced
/// kink and at least kRangeMinPrimitives, at most kRangeMaxPrimitives primitives, each of
/// kRangeMovesPerPrimitive moves or more on average: there a layer of the beam keeps a few of
/// the many places a primitive can end, and over several joints the places it drops are the
/// ones the fewest primitives need (Xu's bezier1 at 0.005 mm: 6 blocks, 5 with the search).
/// Chains of shorter primitives, as printers' perimeters and most CAM passes come out, are
/// left to the beam; with fewer primitives the merges after the beam already try the other
/// joints; and the limit on primitives bounds the search's work.
constexpr size_t kRangeMinPrimitives = 4;
constexpr size_t kRangeMaxPrimitives = 64;
constexpr double kRangeMovesPerPrimitive = 25;
/// The default's range search makes states only of the ends in the far part of each layer's
/// advance, past this share of it: a quarter (plum at 0.005 mm: 39 blocks, 40 past half of
/// it, more than 5 % over its G1 bound of 38).
constexpr double kRangeFrontShare = 0.25;
/// bound_chain(): exact checks per primitive at most, and the most primitives it looks for:
/// the longer the chain, the less often one of just the count passes, and the search that
/// fails before the beam costs more than the one that passes saves (docs/benchmarks.md).
constexpr size_t kBoundChecksPerPrimitive = 8;
constexpr uint32_t kBoundMaxPrimitives = 3;

}  // namespace arcpress::fit_detail
