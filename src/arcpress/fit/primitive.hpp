// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The fitter's vocabulary: a run is replaced by primitives (lines and arcs) whose end points
// are vertices of the run, so positions, E and extra axes at every joint are the input's own.
#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "arcpress/core/deviation.hpp"
#include "arcpress/core/geometry.hpp"
#include "arcpress/dialect/arc_segmentation.hpp"

namespace arcpress {

struct Primitive {
  enum class Kind : uint8_t { Line, Arc };
  uint32_t end_vertex = 0;  ///< the primitive runs from the previous one's end (or vertex 0) to here
  Kind kind = Kind::Line;
  bool ccw = false;         ///< arcs: counter-clockwise seen from the plane's normal (G3)
  Vec2 center{0, 0};        ///< arcs: centre in the run's plane coordinates, mm
  double radius_mm = 0;     ///< arcs
};

/// What the fitter may do and the band it must stay in. Every length is in mm.
struct FitOptions {
  enum class Method : uint8_t {
    Keep,  ///< every G1 stays as it is (the pipeline without fitting)
    Arcs,    ///< G1-continuous lines and arcs, fewest found by a beam search over chains (default)
    Global,  ///< as Arcs, and searches over (vertex, tangent) and (vertex, range of tangents) states where shorter
    Greedy,  ///< G1-continuous lines and arcs, one primitive at a time with a short look-ahead
    Stream,  ///< seeds 001/003: arcs through both end points grown one vertex at a time, then seed 000's G1 adjustment
    Lowe,    ///< seed 000: Lowe's line detection, arcs over runs of the lines, then its G1 adjustment
  };
  Method method = Method::Arcs;
  bool arcs = true;                ///< false: lines only (the controller takes no arcs here)
  double tolerance_mm = 0.01;      ///< max distance between fitted path and input path, both ways
  /// The finest step (mm) the target controller reads an arc centre to (its most decimals):
  /// the fitter keeps back what rounding a centre to it can cost (rounding_reserve_share()).
  /// 0: not known, the most is kept back.
  double centre_step_mm = 0.0;
  double g1_angle_deg = 0.5;       ///< max tangent change at a joint where the input is smooth
  double corner_angle_deg = 30.0;  ///< an input turn sharper than this is a corner kept sharp
  double min_radius_mm = 0.05;     ///< smaller arcs become lines
  double max_radius_mm = 1000.0;   ///< larger arcs become lines
  double max_sweep_deg = 180.0;    ///< per block
  double min_sweep_deg = 0.0;      ///< flatter arcs become lines (controllers misread near-zero sweeps)
  double min_arc_length_mm = 0.0;  ///< shorter arcs become lines (firmware re-segmentation)
  uint32_t min_arc_moves = 0;      ///< an arc must replace at least this many input moves
  double min_chord_mm = 0.0;       ///< arcs whose ends lie closer in their plane become lines (read as full circles)
  bool helical = true;             ///< arcs may move along the plane's normal axis
  /// Arcs may move the extra axes (A/B/C, U/V/W), which the controller carries linearly along
  /// the block. Lines always may; either way a primitive only spans moves along which every
  /// extra axis moves linearly by path length, within the band (see the fitter).
  bool extra_axes = true;
  /// Seed 004: a lone sharp jag whose vertex lies within half the band of its neighbours'
  /// chord (noise in digitised paths) is not a corner. Off by default: every turn sharper
  /// than corner_angle_deg is a corner.
  bool spikes = false;
  uint32_t beam_width = 8;         ///< Arcs and Global methods: chains kept per primitive count
  int beam_branch = 3;             ///< Arcs and Global methods: checked primitives per chain and start tangent
  bool merge = true;               ///< Arcs and Global methods: merge neighbouring primitives after the search
  /// Arcs and Global methods: look first, depth first, for a chain of as few primitives as a
  /// chain that may break its tangent at every joint needs (fit/bound_search.cpp)
  bool bound_search = true;
  uint32_t stream_window = 256;    ///< Stream method: most moves one primitive may replace
  /// How much the extrusion (E) or an extra axis per mm of path may differ between two
  /// neighbouring moves inside one primitive, as a share of the larger rate: a primitive
  /// ends where the rate changes by more, and wherever extrusion starts or stops (a travel,
  /// a retraction or a wipe never joins an extruding primitive).
  double extrusion_variance = 0.05;
  /// The firmware's arc segmentation when the band is held on the chords it moves along
  /// (--band executed): an arc must keep the band with its chords' sagitta taken off it.
  /// Rule::None: the band is held on the programmed circle.
  ArcSegmentation executed;
  /// The side of the input path the primitives may lie on (--band-side): Both, or only left
  /// or right of it (relative to the direction of travel), within the band.
  BandSide band_side = BandSide::Both;

  bool operator==(const FitOptions&) const = default;
};

/// The share of the band the fitter keeps back for rounding printed arc centres: twice the
/// furthest a centre rounded to `centre_step_mm` on both axes moves (0.71 of a step), as a
/// share of the band, at least kMinRoundingReserve and at most kMaxRoundingReserve (also
/// where the step is not known). The emitter tries the dialect's decimals up to its finest,
/// and at each the centres round the fitted one, and checks each rounded arc in the band.
inline constexpr double kMinRoundingReserve = 0.01;
inline constexpr double kMaxRoundingReserve = 0.03;
inline double rounding_reserve_share(const FitOptions& o) {
  if (!(o.centre_step_mm > 0) || !(o.tolerance_mm > 0)) return kMaxRoundingReserve;
  return std::clamp(2 * 0.71 * o.centre_step_mm / o.tolerance_mm, kMinRoundingReserve, kMaxRoundingReserve);
}

/// The share of the band by which a one-sided band's check lets the input lie on the wrong
/// side of the output: the fitter keeps the primitives on their side exactly, and the
/// rounding of arc centres to the printed digits moves them by less than the share it keeps
/// back (rounding_reserve_share()), at most this whatever the dialect (the check, as
/// `arcpress diff`, need not know it).
inline constexpr double kBandSideRoundingShare = kMaxRoundingReserve;

/// The methods' names as --method writes them, in the order of FitOptions::Method.
inline constexpr std::array<std::string_view, 6> kMethodNames{"keep", "arcs", "global", "greedy", "stream", "lowe"};
inline std::string_view method_name(FitOptions::Method m) { return kMethodNames[static_cast<size_t>(m)]; }
/// The method of that name, if any.
inline std::optional<FitOptions::Method> method_named(std::string_view name) {
  for (size_t i = 0; i < kMethodNames.size(); ++i)
    if (kMethodNames[i] == name) return static_cast<FitOptions::Method>(i);
  return std::nullopt;
}

struct FitResult {
  std::vector<Primitive> prims;
  /// Vertices of the run (0 .. move_count) at smooth joints where no tangent-continuous
  /// primitive fitted the band, so the tangent direction changes there (the band wins over
  /// tangency). The run's last vertex stands for its joint with a lone move after it.
  std::vector<uint32_t> forced_at;
};

}  // namespace arcpress
