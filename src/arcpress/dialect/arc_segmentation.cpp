#include "arcpress/dialect/arc_segmentation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace arcpress {

namespace {

using Rule = ArcSegmentation::Rule;

/// A count the firmware would compute in an unsigned integer: clamped to what one arc may
/// sensibly take, so a huge radius never overflows it.
uint32_t count_of(double x) { return static_cast<uint32_t>(std::clamp(x, 0.0, 1e7)); }

}  // namespace

uint32_t executed_segments(const ArcSegmentation& s, double radius_mm, double sweep_rad, double normal_travel_mm) {
  const double sweep = std::abs(sweep_rad), r = std::abs(radius_mm);
  const double flat_mm = r * sweep;
  const double travel_mm = std::hypot(flat_mm, normal_travel_mm);
  switch (s.rule) {
    case Rule::None:
      return 0;
    case Rule::Marlin: {
      // plan_arc(): whole segments of the longest length, at least MIN_CIRCLE_SEGMENTS per
      // circle; then, where that makes them too long or too short, the count that honours
      // MAX_ARC_SEGMENT_MM or MIN_ARC_SEGMENT_MM (the flat length, not the helix's).
      const double min_segments = std::ceil(s.min_circle_segments * sweep / (2 * std::numbers::pi));
      const double nominal = std::max(std::floor(flat_mm / s.max_segment_mm), min_segments);
      if (nominal <= 0) return 1;
      const double nominal_mm = flat_mm / nominal;
      double n = nominal;
      if (nominal_mm > s.max_segment_mm)
        n = std::ceil(flat_mm / s.max_segment_mm);
      else if (nominal_mm < s.min_segment_mm)
        n = std::max(1.0, std::floor(flat_mm / s.min_segment_mm));
      return std::max<uint32_t>(1, count_of(n));
    }
    case Rule::Klipper:
      return std::max<uint32_t>(1, count_of(std::floor(travel_mm / s.max_segment_mm)));
    case Rule::RepRapFirmware: {
      // (The firmware also shortens segments at low feed rates; a shorter segment only
      // brings the chords closer to the circle, so the longest is the one to hold the band on.)
      const double seg =
          std::clamp(std::sqrt(8 * r * s.max_deviation_mm), s.min_segment_mm, std::max(s.min_segment_mm, s.max_segment_mm));
      return std::max<uint32_t>(1, count_of(flat_mm / seg + 0.8));
    }
    case Rule::Grbl: {
      const double tol = s.max_deviation_mm;
      const double w = tol * (2 * r - tol);
      if (w <= 0) return 1;
      return std::max<uint32_t>(1, count_of(std::floor(0.5 * sweep * r / std::sqrt(w))));
    }
    case Rule::Smoothieware: {
      double seg = s.max_segment_mm;
      if (s.max_deviation_mm > 0 && 2 * r > s.max_deviation_mm) {
        const double err_seg = 2 * std::sqrt(s.max_deviation_mm * (2 * r - s.max_deviation_mm));
        if (seg < err_seg) seg = err_seg;
      }
      if (seg < 0.0001) seg = 0.5;
      const double n = std::floor(travel_mm / seg);
      return n > 1 ? count_of(n) : 1;
    }
  }
  return 0;
}

double chords_sagitta_mm(double radius_mm, double sweep_rad, uint32_t segments) {
  if (segments == 0) return 0;
  const double half = std::min(std::abs(sweep_rad) / (2.0 * segments), std::numbers::pi);
  return std::abs(radius_mm) * (1 - std::cos(half));
}

double executed_sagitta_mm(const ArcSegmentation& s, double radius_mm, double sweep_rad, double normal_travel_mm) {
  return chords_sagitta_mm(radius_mm, sweep_rad, executed_segments(s, radius_mm, sweep_rad, normal_travel_mm));
}

}  // namespace arcpress
