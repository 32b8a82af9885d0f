// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// How a controller cuts an arc into the chords it really moves along. Printer firmwares and
// Grbl never move on the circle: they split each G2/G3 into straight segments, and the
// part is made by those. A dialect names its firmware's rule and the settings it uses
// (dialects/README.md cites each rule's source); the fitter holds the band on the chords
// (--band executed) and the verifier measures them (executed_path()).
#include <array>
#include <cstdint>
#include <cmath>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "arcpress/core/deviation.hpp"
#include "arcpress/core/geometry.hpp"

namespace arcpress {

struct ArcSegmentation {
  enum class Rule : uint8_t {
    None,            ///< the controller moves on the circle (or its rule is not known): the program is the path
    Marlin,          ///< Marlin 2.1 plan_arc(): MAX/MIN_ARC_SEGMENT_MM, MIN_CIRCLE_SEGMENTS
    Klipper,         ///< Klipper gcode_arcs: floor(length / resolution) segments, at least 1
    RepRapFirmware,  ///< RRF 3: segment sqrt(8 r MaxArcDeviation) within [min, max], count rounded up from 0.2
    Grbl,            ///< Grbl 1.1 mc_arc(): floor(half the length / sqrt($12 (2r - $12))), 0 meaning one chord
    Smoothieware,    ///< Smoothieware append_arc(): segment from mm_max_arc_error (or mm_per_arc_segment), floor
    GrblHAL,         ///< grblHAL mc_arc(): Grbl's count; its radius vector is rotated in double precision
    PrusaBuddy,      ///< Prusa's Buddy firmware plan_arc(): RRF's count, Marlin's loop turned by the exact sine and cosine
    PrusaMk3,        ///< Prusa-Firmware (MK3) mc_arc(): r 2π / MIN_ARC_SEGMENTS within its limits, rounded up
  };
  Rule rule = Rule::None;
  /// Longest segment, mm: Marlin MAX_ARC_SEGMENT_MM, Klipper `resolution`, RRF
  /// MaxArcSegmentLength, Smoothieware mm_per_arc_segment (0: from the arc error only).
  /// (Buddy: MAX_ARC_SEGMENT_MM, MIN_ARC_SEGMENT_MM and MAX_ARC_DEVIATION as RRF's.)
  double max_segment_mm = 1.0;
  /// Shortest segment, mm: Marlin MIN_ARC_SEGMENT_MM, RRF MinArcSegmentLength.
  double min_segment_mm = 0.1;
  /// Marlin MIN_CIRCLE_SEGMENTS: segments in a whole circle at the least.
  int min_circle_segments = 72;
  /// The chord error the firmware aims at, mm: RRF MaxArcDeviation, Grbl $12 arc_tolerance,
  /// Smoothieware mm_max_arc_error.
  double max_deviation_mm = 0.002;
  /// How often the firmware computes a chord end from the sine and cosine of its angle
  /// instead of turning the last one by a small-angle step (each step pulls the end in by
  /// about r θ⁴/24): Marlin and Grbl N_ARC_CORRECTION, Smoothieware arc_correction, RRF
  /// SegmentsPerFulArcCalculation; what it counts is each firmware's own (dialects/README.md).
  /// 0: the firmware's default (correction_period_or_default()).
  int correction_period = 0;

  bool moves_on_chords() const { return rule != Rule::None; }
  /// The firmware cuts shorter segments than executed_segments() counts where the feed is
  /// low (RepRapFirmware under MinArcSegmentsPerSec, Buddy under MIN_ARC_SEGMENTS_PER_SEC
  /// segments a second): any count from that one up may run. Each such set of chords lies in
  /// the ring about the circle that the first's does, but not on its chords, so the band is
  /// held on that ring (ring_deviation()) rather than on one set of chords.
  bool count_may_grow() const { return rule == Rule::RepRapFirmware || rule == Rule::PrusaBuddy; }
  /// correction_period, or the firmware's default where it is 0: Marlin, Buddy and the MK3's
  /// 25, Grbl and grblHAL 12, Smoothieware 5, RepRapFirmware 8 (Klipper computes every end: 1).
  int correction_period_or_default() const;
  bool operator==(const ArcSegmentation&) const = default;
};

/// The rules' names as dialect files write them, in the order of ArcSegmentation::Rule.
inline constexpr std::array<std::string_view, 9> kRuleNames{
    "none", "marlin", "klipper", "reprapfirmware", "grbl", "smoothieware", "grblhal", "prusa-buddy", "prusa-mk3"};
inline std::string_view rule_name(ArcSegmentation::Rule rule) { return kRuleNames[static_cast<size_t>(rule)]; }
/// The rule of that name, if any.
inline std::optional<ArcSegmentation::Rule> rule_named(std::string_view name) {
  for (size_t i = 0; i < kRuleNames.size(); ++i)
    if (kRuleNames[i] == name) return static_cast<ArcSegmentation::Rule>(i);
  return std::nullopt;
}

/// The most segments one arc is cut into: Marlin's plan_arc() and Grbl's mc_arc() count them
/// in 16 bits, so a count above is not what those firmwares run. (Grbl's count grows
/// without bound as the radius nears half its arc tolerance: a circle that small lies within
/// the tolerance of any chord.) arcpress writes no arc that asks for as many.
inline constexpr uint32_t kMaxArcSegments = 65535;

/// How many straight segments the firmware moves along for an arc of `radius_mm` turning
/// by `sweep_rad` (either sign) while the plane's normal axis travels `normal_travel_mm`:
/// 1 means one chord from start to end. Always at least 1, at most kMaxArcSegments (a
/// count the rule would make larger is read as that many); 0 for Rule::None (the circle).
uint32_t executed_segments(const ArcSegmentation& s, double radius_mm, double sweep_rad, double normal_travel_mm = 0);

/// The same count as the firmware works it out from the numbers it reads: an arc from `start`
/// about `centre` to `end` (the plane's coordinates, mm, as printed) turning by `sweep_rad`,
/// its radius and turn computed from them, and the rule's formula, in the firmware's number
/// type (single precision but for Klipper's). Where a count lies on the edge between two
/// (a quotient just under 2 in floats, just over in doubles), this one is the firmware's:
/// the output's arcs are checked on it.
uint32_t executed_segments_read(const ArcSegmentation& s, const Vec2& start, const Vec2& centre, const Vec2& end,
                                double sweep_rad, double normal_travel_mm = 0);

/// Where the firmware of `s` ends one chord and begins the next on an arc from `start` about
/// `centre` to `end` (the plane's coordinates, mm) turning by `sweep_rad` (> 0
/// counter-clockwise) in `segments` chords (executed_segments()): the segments - 1 points
/// between start and end, appended to `out`, computed as that firmware computes them from
/// the numbers it reads: its turn from the end point (atan2), its number type (single
/// precision but for Klipper's, and grblHAL's radius vector), its small-angle rotation
/// between exact ends and its correction period. The last chord ends at the arc's end.
/// Sources: dialects/README.md.
void executed_chord_ends(const ArcSegmentation& s, const Vec2& start, const Vec2& centre, const Vec2& end,
                         double sweep_rad, uint32_t segments, std::vector<Vec2>& out);

/// How far (mm) `segments` equal chords of an arc of `radius_mm` turning by `sweep_rad` lie
/// inside the circle at most: the sagitta of one segment's angle. 0 for no segments.
double chords_sagitta_mm(double radius_mm, double sweep_rad, uint32_t segments);

/// How far (mm) the firmware's chord ends `ends` (executed_chord_ends()) of an arc from
/// `start` about `centre` turning by `sweep_rad` lie from the circle's own points at their
/// turns at most: where small-angle steps pull them off it (the chords lie within their
/// sagitta and this of the circle).
double chords_drift_mm(const Vec2& start, const Vec2& centre, double sweep_rad, const std::vector<Vec2>& ends);

/// An upper bound (mm) of the two-sided distance between the polyline `pts` (from the arc's
/// start) and every set of chords that the firmware of `s`, whose count may grow
/// (count_may_grow()), cuts `arc` into, from the count whose chord ends are `ends`
/// (executed_chord_ends()) up. Each such path, as the polyline, meets each turn about the
/// centre once (Deviation::ordered), and lies in the ring from the radius less those chords'
/// sagitta and their ends' drift (chords_drift_mm()) to the radius and the drift, the drift of
/// another count taken as this one's and all single-precision rounding could add (each turn
/// of the radius vector rounds its products and sums, some 4.8 units in the last place of the
/// radius, and every turn between two exact ends adds to it): at each turn the two lie no
/// farther apart than the polyline lies from the ring's middle circle and half its width.
Deviation ring_deviation(const ArcSegmentation& s, std::span<const Vec3> pts, const ArcGeom& arc,
                         const std::vector<Vec2>& ends, double stop_above_mm = HUGE_VAL);
/// ring_deviation() of `chords` chords before their ends' drift, which it adds to this: a
/// figure above the band here is above it there, and the ends need not be worked out.
Deviation ring_deviation_before_drift(const ArcSegmentation& s, std::span<const Vec3> pts, const ArcGeom& arc,
                                      uint32_t chords, double stop_above_mm = HUGE_VAL);

/// The same for the chords the firmware cuts that arc into (executed_segments()).
double executed_sagitta_mm(const ArcSegmentation& s, double radius_mm, double sweep_rad, double normal_travel_mm = 0);

}  // namespace arcpress
