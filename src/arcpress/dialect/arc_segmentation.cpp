// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/dialect/arc_segmentation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace arcpress {

namespace {

using Rule = ArcSegmentation::Rule;

/// A count the firmware would compute in an unsigned integer, clamped to kMaxArcSegments.
uint32_t count_of(double x) { return static_cast<uint32_t>(std::clamp(x, 0.0, double(kMaxArcSegments))); }

/// The count of each rule in `Real`, the number type the firmware counts in, from the radius
/// and the turn's size it works out (`sweep`, radians, >= 0).
template <class Real>
uint32_t segments_in(const ArcSegmentation& s, Real r, Real sweep, Real normal_travel_mm) {
  const Real flat_mm = r * sweep;
  const Real max_mm = Real(s.max_segment_mm), min_mm = Real(s.min_segment_mm), deviation = Real(s.max_deviation_mm);
  switch (s.rule) {
    case Rule::None:
      return 0;
    case Rule::Marlin: {
      // plan_arc(): whole segments of the longest length, at least MIN_CIRCLE_SEGMENTS per
      // circle; then, where that makes them too long or too short, the count that honours
      // MAX_ARC_SEGMENT_MM or MIN_ARC_SEGMENT_MM (the flat length, not the helix's).
      const Real min_segments = std::ceil(Real(s.min_circle_segments) * (sweep / Real(2 * std::numbers::pi)));
      const Real nominal = std::max(std::floor(flat_mm / max_mm), min_segments);
      if (nominal <= 0) return 1;
      // (The limits are double constants there: compared and divided by in double.)
      const Real nominal_mm = flat_mm / nominal;
      Real n = nominal;
      if (double(nominal_mm) > s.max_segment_mm)
        n = std::ceil(Real(double(flat_mm) / s.max_segment_mm));
      else if (double(nominal_mm) < s.min_segment_mm)
        n = std::max(Real(1), std::floor(Real(double(flat_mm) / s.min_segment_mm)));
      return std::max<uint32_t>(1, count_of(double(n)));
    }
    case Rule::Klipper:
      return std::max<uint32_t>(1, count_of(double(std::floor(std::hypot(flat_mm, normal_travel_mm) / max_mm))));
    case Rule::RepRapFirmware:
    case Rule::PrusaBuddy: {
      // (Each firmware cuts shorter segments at low feed rates too: count_may_grow().)
      // (RRF adds a double 0.8 to its float quotient, Buddy a float 0.8f.)
      const Real seg = std::clamp(std::sqrt(8 * r * deviation), min_mm, std::max(min_mm, max_mm));
      const double count = s.rule == Rule::RepRapFirmware ? double(flat_mm / seg) + 0.8 : double(flat_mm / seg + Real(0.8));
      return std::max<uint32_t>(1, count_of(count));
    }
    case Rule::PrusaMk3: {
      // mc_arc(): the segment of MIN_ARC_SEGMENTS a circle (r (2π / N), in floats: the AVR's
      // double is a float, M_PI too), else the longest, within MIN_MM_PER_ARC_SEGMENT ..
      // MM_PER_ARC_SEGMENT; the length along the helix over it, rounded up.
      const Real turn = Real(2) * Real(float(std::numbers::pi));
      Real seg = s.min_circle_segments > 0 ? r * (turn / Real(s.min_circle_segments)) : max_mm;
      if (seg < min_mm)
        seg = min_mm;
      else if (seg > max_mm)
        seg = max_mm;
      return std::max<uint32_t>(1, count_of(double(std::ceil(std::hypot(flat_mm, normal_travel_mm) / seg))));
    }
    case Rule::Grbl:
    case Rule::GrblHAL: {
      const Real w = deviation * (2 * r - deviation);
      if (w <= 0) return 1;
      return std::max<uint32_t>(1, count_of(double(std::floor(Real(0.5) * sweep * r / std::sqrt(w)))));
    }
    case Rule::Smoothieware: {
      Real seg = max_mm;
      if (deviation > 0 && 2 * r > deviation) {
        const Real err_seg = 2 * std::sqrt(deviation * (2 * r - deviation));
        if (seg < err_seg) seg = err_seg;
      }
      if (seg < Real(0.0001)) seg = Real(0.5);
      const Real n = std::floor(std::hypot(flat_mm, normal_travel_mm) / seg);
      return n > 1 ? count_of(double(n)) : 1;
    }
  }
  return 0;
}

}  // namespace

uint32_t executed_segments(const ArcSegmentation& s, double radius_mm, double sweep_rad, double normal_travel_mm) {
  return segments_in<double>(s, std::abs(radius_mm), std::abs(sweep_rad), normal_travel_mm);
}

int ArcSegmentation::correction_period_or_default() const {
  if (correction_period > 0) return correction_period;
  switch (rule) {
    case Rule::Marlin:
    case Rule::PrusaBuddy:
    case Rule::PrusaMk3: return 25;       // Configuration_adv.h N_ARC_CORRECTION (the MK3's variants/*.h)
    case Rule::Grbl:
    case Rule::GrblHAL: return 12;        // config.h N_ARC_CORRECTION
    case Rule::Smoothieware: return 5;    // arc_correction
    case Rule::RepRapFirmware: return 8;  // SegmentsPerFulArcCalculation
    case Rule::None:
    case Rule::Klipper: return 1;
  }
  return 1;
}

namespace {

/// Marlin plan_arc(), Grbl mc_arc() and Smoothieware append_arc(): the centre is the start
/// plus the offset, in floats; the radius vector turns by a rotation built from small-angle
/// sine and cosine, and is computed from the offset exactly at the corrections. `exact_at`
/// says, for the index i of a chord end (from 1), whether that end is computed exactly, and
/// `Real` is the radius vector's number type (grblHAL keeps it in double).
template <class Real, class ExactAt>
void rotated_ends(const Vec2& start, const Vec2& centre, uint32_t segments, float sin_t, float cos_t, float theta,
                  ExactAt exact_at, bool centre_in_real, std::vector<Vec2>& out) {
  const float px = float(start.x()), py = float(start.y());
  const float ox = float(centre.x() - start.x()), oy = float(centre.y() - start.y());  // I, J as the firmware reads them
  Real cx, cy;
  if (centre_in_real) {
    cx = Real(px) + Real(ox);
    cy = Real(py) + Real(oy);
  } else {
    cx = Real(px + ox);
    cy = Real(py + oy);
  }
  Real rx = -Real(ox), ry = -Real(oy);
  for (uint32_t i = 1; i < segments; ++i) {
    if (exact_at(i)) {
      const float ti = float(i) * theta;
      const float cos_ti = std::cos(ti), sin_ti = std::sin(ti);
      rx = Real(-ox * cos_ti + oy * sin_ti);
      ry = Real(-ox * sin_ti - oy * cos_ti);
    } else {
      const Real next_y = rx * Real(sin_t) + ry * Real(cos_t);
      rx = rx * Real(cos_t) - ry * Real(sin_t);
      ry = next_y;
    }
    // The position the firmware keeps is a float.
    out.emplace_back(double(float(cx + rx)), double(float(cy + ry)));
  }
}

/// The turn as Marlin, Grbl and Smoothieware compute it from the numbers they read: the
/// angle between the radius vectors to the start and to the end, by atan2 in `Real` (the
/// centre the start plus the offset), taken the way and as many whole turns as `sweep_rad`.
template <class Real>
float firmware_travel(const Vec2& start, const Vec2& centre, const Vec2& end, double sweep_rad) {
  const float ox = float(centre.x() - start.x()), oy = float(centre.y() - start.y());
  const Real cx = Real(float(start.x())) + Real(ox), cy = Real(float(start.y())) + Real(oy);
  const Real r0 = -Real(ox), r1 = -Real(oy), t0 = Real(float(end.x())) - cx, t1 = Real(float(end.y())) - cy;
  float travel = float(std::atan2(r0 * t1 - r1 * t0, r0 * t0 + r1 * t1));
  constexpr float kTurn = float(2 * std::numbers::pi), kHalf = float(std::numbers::pi);
  while (double(travel) - sweep_rad > kHalf) travel -= kTurn;
  while (sweep_rad - double(travel) > kHalf) travel += kTurn;
  return travel;
}

/// RepRapFirmware's DoArcMove(): the turn's size (totalArc) from the start's angle about the
/// centre to the end's, the way the arc turns, whole turns as `sweep_rad` has them, in floats;
/// and the start's angle (`start_angle`).
float rrf_total_arc(const Vec2& start, const Vec2& centre, const Vec2& end, double sweep_rad, float& start_angle) {
  const float ox = float(centre.x() - start.x()), oy = float(centre.y() - start.y());
  const float cx = float(start.x()) + ox, cy = float(start.y()) + oy;
  start_angle = std::atan2(-oy, -ox);
  const float final_angle = std::atan2(float(end.y()) - cy, float(end.x()) - cx);
  float total = sweep_rad >= 0 ? final_angle - start_angle : start_angle - final_angle;
  constexpr float kTurn = float(2 * std::numbers::pi), kHalf = float(std::numbers::pi);
  while (double(total) - std::abs(sweep_rad) > kHalf) total -= kTurn;
  while (std::abs(sweep_rad) - double(total) > kHalf) total += kTurn;
  return total;
}

}  // namespace

uint32_t executed_segments_read(const ArcSegmentation& s, const Vec2& start, const Vec2& centre, const Vec2& end,
                                double sweep_rad, double normal_travel_mm) {
  switch (s.rule) {
    case Rule::None:
      return 0;
    case Rule::Klipper:  // (Python's doubles)
      return executed_segments(s, (start - centre).norm(), sweep_rad, normal_travel_mm);
    case Rule::RepRapFirmware: {
      // DoArcMove(): the radius from the offsets, the turn from the start's and end's angles.
      const float ox = float(centre.x() - start.x()), oy = float(centre.y() - start.y());
      float start_angle = 0;
      const float total = rrf_total_arc(start, centre, end, sweep_rad, start_angle);
      return segments_in<float>(s, std::sqrt(ox * ox + oy * oy), total, float(normal_travel_mm));
    }
    default: {
      // plan_arc(), mc_arc(), append_arc(): the radius from the offsets, the turn by atan2,
      // in floats (grblHAL's turn from doubles).
      const float ox = float(centre.x() - start.x()), oy = float(centre.y() - start.y());
      const float travel = s.rule == Rule::GrblHAL ? firmware_travel<double>(start, centre, end, sweep_rad)
                                                   : firmware_travel<float>(start, centre, end, sweep_rad);
      return segments_in<float>(s, std::sqrt(ox * ox + oy * oy), std::abs(travel), float(normal_travel_mm));
    }
  }
}

void executed_chord_ends(const ArcSegmentation& s, const Vec2& start, const Vec2& centre, const Vec2& end,
                         double sweep_rad, uint32_t segments, std::vector<Vec2>& out) {
  if (segments < 2) return;
  const int period = s.correction_period_or_default();
  switch (s.rule) {
    case Rule::None:
    case Rule::Klipper: {
      // Klipper planArc() (Python floats): every end turned exactly from the start's radius.
      const double theta = sweep_rad / segments;
      const Vec2 r0 = start - centre;
      for (uint32_t i = 1; i < segments; ++i) {
        const double c = std::cos(i * theta), sn = std::sin(i * theta);
        out.emplace_back(centre.x() + r0.x() * c - r0.y() * sn, centre.y() + r0.x() * sn + r0.y() * c);
      }
      return;
    }
    case Rule::Marlin: {
      // plan_arc(): sin θ ≈ θ − θ³/6, cos θ ≈ 1 − θ²/2; `if (--arc_recalc_count)` turns, so
      // every period-th end (i = period, 2·period, ...) is exact.
      const float theta = firmware_travel<float>(start, centre, end, sweep_rad) / float(segments);
      const float sq = theta * theta;
      const float sin_t = theta - sq * theta / 6, cos_t = 1 - 0.5f * sq;
      rotated_ends<float>(start, centre, segments, sin_t, cos_t, theta,
                          [&](uint32_t i) { return i % uint32_t(period) == 0; }, false, out);
      return;
    }
    case Rule::PrusaMk3: {
      // The MK3's mc_arc(): Marlin's small-angle steps, and `if (n_arc_correction-- == 0)`
      // makes every (period + 1)-th end exact.
      const float theta = firmware_travel<float>(start, centre, end, sweep_rad) / float(segments);
      const float sq = theta * theta;
      rotated_ends<float>(start, centre, segments, theta - sq * theta / 6, 1 - 0.5f * sq, theta,
                          [&](uint32_t i) { return i % uint32_t(period + 1) == 0; }, false, out);
      return;
    }
    case Rule::PrusaBuddy: {
      // Buddy's plan_arc(): Marlin's loop, the radius vector turned by cosf(θ) and sinf(θ)
      // themselves, every period-th end exact.
      const float theta = firmware_travel<float>(start, centre, end, sweep_rad) / float(segments);
      rotated_ends<float>(start, centre, segments, std::sin(theta), std::cos(theta), theta,
                          [&](uint32_t i) { return i % uint32_t(period) == 0; }, false, out);
      return;
    }
    case Rule::Grbl:
    case Rule::GrblHAL: {
      // mc_arc(): cos_T = (2 − θ²)/2, sin_T = θ (cos_T' + 4)/6 with cos_T' = 2 − θ²; it
      // turns while `count < N_ARC_CORRECTION`, so every (period + 1)-th end is exact.
      const float travel = s.rule == Rule::Grbl ? firmware_travel<float>(start, centre, end, sweep_rad)
                                                : firmware_travel<double>(start, centre, end, sweep_rad);
      const float theta = travel / float(segments);
      float cos_t = 2.0f - theta * theta;
      const float sin_t = theta * 0.16666667f * (cos_t + 4.0f);
      cos_t *= 0.5f;
      auto exact = [&](uint32_t i) { return i % uint32_t(period + 1) == 0; };
      if (s.rule == Rule::Grbl) rotated_ends<float>(start, centre, segments, sin_t, cos_t, theta, exact, false, out);
      else rotated_ends<double>(start, centre, segments, sin_t, cos_t, theta, exact, true, out);
      return;
    }
    case Rule::Smoothieware: {
      // append_arc(): sin_T = θ, cos_T = 1 − θ²/2; it turns while `count < arc_correction`.
      const float theta = firmware_travel<float>(start, centre, end, sweep_rad) / float(segments);
      const float cos_t = 1 - 0.5f * theta * theta, sin_t = theta;
      rotated_ends<float>(start, centre, segments, sin_t, cos_t, theta,
                          [&](uint32_t i) { return i % uint32_t(period + 1) == 0; }, false, out);
      return;
    }
    case Rule::RepRapFirmware: {
      // GCodes::DoArcMove() and ReadMove(): the angle advances by a float increment; its sine
      // and cosine are computed at the first end and then every (period + 1)-th, and in between
      // turned by the increment's exact sine and cosine; an end is the centre plus the radius
      // times them.
      const float ox = float(centre.x() - start.x()), oy = float(centre.y() - start.y());
      const float cx = float(start.x()) + ox, cy = float(start.y()) + oy;
      const float radius = std::sqrt(ox * ox + oy * oy);
      float angle = 0;
      const float total = rrf_total_arc(start, centre, end, sweep_rad, angle);
      const float increment = (sweep_rad >= 0 ? total : -total) / float(segments);
      const float inc_sin = std::sin(increment), inc_cos = std::cos(increment);
      float cur_cos = 0, cur_sin = 0;
      int till_full = 0;
      for (uint32_t i = 1; i < segments; ++i) {
        angle += increment;
        if (till_full == 0) {
          till_full = period;
          cur_cos = std::cos(angle);
          cur_sin = std::sin(angle);
        } else {
          --till_full;
          const float next_cos = cur_cos * inc_cos - cur_sin * inc_sin;
          const float next_sin = cur_sin * inc_cos + cur_cos * inc_sin;
          cur_cos = next_cos;
          cur_sin = next_sin;
        }
        out.emplace_back(double(cx + radius * cur_cos), double(cy + radius * cur_sin));
      }
      return;
    }
  }
}

double chords_sagitta_mm(double radius_mm, double sweep_rad, uint32_t segments) {
  if (segments == 0) return 0;
  const double half = std::min(std::abs(sweep_rad) / (2.0 * segments), std::numbers::pi);
  return std::abs(radius_mm) * (1 - std::cos(half));
}

double chords_drift_mm(const Vec2& start, const Vec2& centre, double sweep_rad, const std::vector<Vec2>& ends) {
  // The circle's own points at the chord ends, turned one chord at a time from the start.
  const double step = sweep_rad / double(ends.size() + 1), c = std::cos(step), s = std::sin(step);
  Vec2 radius = start - centre;
  double drift = 0;
  for (const Vec2& end : ends) {
    radius = Vec2(radius.x() * c - radius.y() * s, radius.x() * s + radius.y() * c);
    drift = std::max(drift, (end - (centre + radius)).norm());
  }
  return drift;
}

Deviation ring_deviation(const ArcSegmentation& s, std::span<const Vec3> pts, const ArcGeom& arc,
                         const std::vector<Vec2>& ends, double stop_above_mm) {
  const double drift_mm = chords_drift_mm(Vec2(pts.front().x(), pts.front().y()), arc.center, arc.sweep, ends);
  Deviation d = ring_deviation_before_drift(s, pts, arc, uint32_t(ends.size()) + 1, stop_above_mm - drift_mm);
  d.max_mm += drift_mm;
  return d;
}

Deviation ring_deviation_before_drift(const ArcSegmentation& s, std::span<const Vec3> pts, const ArcGeom& arc,
                                      uint32_t chords, double stop_above_mm) {
  // Single precision's unit in the last place, relative; the turns between exact ends; the
  // end's own coordinates rounded.
  constexpr double kFloatUnit = 0x1p-24, kPerTurn = 4.8;
  const double turns = s.rule == Rule::RepRapFirmware ? s.correction_period_or_default() + 1 : s.correction_period_or_default();
  const double rounding = arc.radius_mm * kFloatUnit * kPerTurn * turns + kFloatUnit * (arc.center.norm() + arc.radius_mm);
  const double sagitta = chords_sagitta_mm(arc.radius_mm, arc.sweep, chords), half = sagitta / 2 + rounding;
  ArcGeom middle = arc;
  middle.radius_mm -= sagitta / 2;
  Deviation d = arc_deviation(pts, middle, stop_above_mm - half);
  d.max_mm += half;
  return d;
}

double executed_sagitta_mm(const ArcSegmentation& s, double radius_mm, double sweep_rad, double normal_travel_mm) {
  return chords_sagitta_mm(radius_mm, sweep_rad, executed_segments(s, radius_mm, sweep_rad, normal_travel_mm));
}

}  // namespace arcpress
