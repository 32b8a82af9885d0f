// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/model/arc_centre.hpp"

#include <fmt/format.h>

#include <cmath>

namespace arcpress {

Vec3 ijk_centre(const Frame& frame, Plane plane, const AxisValues& from, const double* ijk, const bool* ijk_seen,
                bool as_absolute) {
  const auto a = axes_of(plane);
  Vec3 at(from[kX], from[kY], from[kZ]);
  for (int k = 0; k < 3; ++k) {
    if (k == a.normal) continue;
    const double off = ijk_seen[k] ? ijk[k] : 0.0;
    if (as_absolute)
      at[k] = ijk_seen[k] ? frame.to_mm(k, off) : from[k];
    else
      at[k] = from[k] + off * frame.unit_mm;
  }
  return at;
}

RadiusGap radius_gap(const Dialect& dialect, Plane plane, const AxisValues& from, const Vec3& centre,
                     const AxisValues& to) {
  const auto a = axes_of(plane);
  const Vec2 cc(centre[a.first], centre[a.second]);
  const double r0 = (Vec2(from[a.first], from[a.second]) - cc).norm();
  const double r1 = (Vec2(to[a.first], to[a.second]) - cc).norm();
  const double allowed =
      dialect.radius_rel > 0 ? std::max(dialect.radius_abs_mm, dialect.radius_rel * r0) : dialect.radius_abs_mm;
  return {std::abs(r1 - r0), allowed};
}

RadiusCentre radius_centre(const Vec2& s, const Vec2& e, double r_mm, bool ccw, double allowance_mm) {
  RadiusCentre out;
  const Vec2 chord = e - s;
  const double d = chord.norm();
  out.half_chord_mm = d / 2;
  if (d < kLengthEpsMm) {
    out.coincident = true;
    return out;
  }
  if (std::abs(r_mm) < d / 2 - allowance_mm) return out;
  const double h2 = r_mm * r_mm - d * d / 4;
  const double h = h2 > 0 ? std::sqrt(h2) : 0.0;
  // G3 with R > 0 (short way round): centre on the left of the chord; G2: on the right.
  const double side = (ccw ? 1.0 : -1.0) * (r_mm >= 0 ? 1.0 : -1.0);
  out.centre = (s + e) / 2 + side * h * left_normal(chord / d);
  return out;
}

ArcCentreRead read_arc_centre(const Dialect& d, const Frame& fr, Plane plane, const AxisValues& from,
                              const AxisValues& target, const ArcWords& words, bool ccw, const Vec3& pole,
                              uint32_t pole_known, DiagnosticSink& sink, uint32_t line) {
  ArcCentreRead out;
  const auto a = axes_of(plane);
  const double* ijk = words.ijk;
  const bool* ijk_seen = words.ijk_seen;
  // I/J/K belong to X/Y/Z respectively.
  Vec3& c = out.centre;
  c = Vec3(from[kX], from[kY], from[kZ]);
  if (words.r_seen) {
    // A radius shorter than half the chord reaches no circle through both ends; controllers
    // take one within their radius check as the half circle and refuse the rest.
    const double allowance_mm = d.radius_abs_mm > 0 ? d.radius_abs_mm : kRadiusAimMm;
    const double r = words.r_value * fr.unit_mm;
    const RadiusCentre rc = radius_centre(Vec2(from[a.first], from[a.second]), Vec2(target[a.first], target[a.second]),
                                          r, ccw, allowance_mm);
    if (rc.coincident) {
      sink.warning({line, 1}, "W-MODEL-ARC-R", "R-form arc with coincident end points has no defined centre");
      out.known = false;
    } else if (!rc.centre) {
      sink.problem({line, 1}, "E-MODEL-ARC-RADIUS",
                    fmt::format("R {:.4f} mm is shorter than half the chord, {:.4f} mm (allowed {:.4f} mm less); "
                                "no circle joins the end points",
                                std::abs(r), rc.half_chord_mm, allowance_mm));
      out.known = false;
    } else {
      c[a.first] = rc.centre->x();
      c[a.second] = rc.centre->y();
    }
    return out;
  }
  // RS274 reads I/J/K as offsets from the start unless G90.1; a dialect that reads them
  // as the absolute centre does so unless the program is in incremental mode (G91).
  if (!ijk_seen[a.first] && !ijk_seen[a.second] && d.centre_modal) {
    const uint32_t plane_bits = (1u << a.first) | (1u << a.second);
    out.reads_pole = true;
    if ((pole_known & plane_bits) == plane_bits) {
      c[a.first] = pole[a.first];
      c[a.second] = pole[a.second];
    } else {
      sink.problem({line, 1}, "E-MODEL-ARC-CENTRE",
                    fmt::format("G{} has no centre: neither {} nor {} nor R is given, and the program has set no "
                                "centre before it; it is kept and not measured",
                                ccw ? 3 : 2, char('I' + a.first), char('I' + a.second)));
      out.known = false;
      return out;
    }
  } else if (!ijk_seen[a.first] && !ijk_seen[a.second]) {
    sink.problem({line, 1}, "E-MODEL-ARC-CENTRE",
                  fmt::format("G{} has no centre: neither {} nor {} nor R is given; it is kept and not measured",
                              ccw ? 3 : 2, char('I' + a.first), char('I' + a.second)));
    out.known = false;
    return out;
  }
  bool absolute = d.centre == CentreReading::Absolute ? fr.absolute : fr.arc_absolute;
  if (ijk_seen[a.first] || ijk_seen[a.second]) c = ijk_centre(fr, plane, from, ijk, ijk_seen, absolute);
  // The controller refuses an arc whose end lies off the circle through its start about the
  // centre by more than its radius check; where it does not check (printers), it goes on.
  if (d.radius_abs_mm > 0) {
    const RadiusGap g = radius_gap(d, plane, from, c, target);
    if (!readable_arc(g)) {
      // Read the other way (an offset as the centre, or the centre as an offset), where the
      // program could say which: the radii may agree, and the program rely on a setting.
      std::string other;
      if (d.centre == CentreReading::Incremental && d.centre_mode_words) {
        if (whole_arc(radius_gap(d, plane, from, ijk_centre(fr, plane, from, ijk, ijk_seen, !absolute), target), d))
          other = fmt::format("; read as {} (G{}), the radii agree: say so in the program, as a controller set "
                              "the other way reads it",
                              absolute ? "offsets from the start" : "the absolute centre", absolute ? "91.1" : "90.1");
      }
      sink.problem({line, 1}, "E-MODEL-ARC-RADIUS",
                    fmt::format("the end lies {:.4f} mm off the circle through the start about the centre "
                                "(read as drawn up to {:.4f} mm){}; the arc is kept and not measured",
                                g.gap_mm, std::max(g.allowed_mm, kReadRadiusSlackMm), other));
      out.known = false;
    }
  }
  return out;
}

int read_turn(const Dialect& dialect, int g, uint8_t& turn, Interpretation& out, uint32_t bi, DiagnosticSink& sink,
              SourceLoc at, std::string_view spelled) {
  if (const TurnReading* t = dialect.turn_reading(g)) {
    if (turn == 0) {
      sink.warning(at, "W-MODEL-ARC-TURN",
                   fmt::format("{} turns the way the last arc programmed before it turned, and the program has "
                               "programmed none: not modelled, and the moves before it are fitted with lines only "
                               "(an arc of arcpress's would decide the way; in a long program, those of the first "
                               "pieces may already be written: --method keep writes none)",
                               spelled));
      out.arcless_moves = uint32_t(out.moves.size());
    }
    if (out.turn_reads.empty() || out.turn_reads.back().block != bi) out.turn_reads.push_back({bi, turn});
    return turn == 0 ? g : turn == 2 ? t->cw10 : t->ccw10;
  }
  if (const int way = dialect.turn_set_by(g)) turn = uint8_t(way);
  return g;
}

void set_pole(ModalState& s, const double* ijk, const bool* ijk_seen, bool pole_here) {
  for (int k = 0; k < 3; ++k) {
    const bool from_words = ijk_seen[k] && !pole_here;
    if (!from_words && !(pole_here && k != axes_of(s.plane).normal)) continue;
    const bool absolute = from_words && s.frame.absolute;
    s.pole[k] = !from_words ? s.pos[k] : absolute ? s.frame.to_mm(k, ijk[k]) : s.pos[k] + ijk[k] * s.frame.unit_mm;
    const bool known = absolute || ((s.known >> k) & 1u);
    s.pole_known = known ? s.pole_known | 1u << k : s.pole_known & ~(1u << k);
  }
}

PoleRead pole_read(const ModalState& s, uint32_t block, bool arc) {
  PoleRead r;
  r.block = block;
  r.arc = arc;
  r.plane = s.plane;
  const auto a = axes_of(s.plane);
  const uint32_t plane_bits = (1u << a.first) | (1u << a.second);
  r.known = (s.pole_known & plane_bits) == plane_bits && (s.frame.absolute || (s.known & plane_bits) == plane_bits);
  for (int k = 0; k < 3; ++k)
    r.words[k] = s.frame.absolute ? s.frame.to_program(k, s.pole[k]) : (s.pole[k] - s.pos[k]) / s.frame.unit_mm;
  return r;
}

void read_centre_mode(const Dialect& d, ModalState& s, Frame& frame, const AxisValues& target, const double* ijk,
                      const bool* ijk_seen, DiagnosticSink& sink, uint32_t line) {
  const auto a = axes_of(s.plane);
  if (!ijk_seen[a.first] && !ijk_seen[a.second]) return;
  const bool now = s.frame.arc_absolute;
  auto gap_when = [&](bool absolute) {
    return radius_gap(d, s.plane, s.pos, ijk_centre(s.frame, s.plane, s.pos, ijk, ijk_seen, absolute), target);
  };
  if (readable_arc(gap_when(now))) {
    s.centre_told = true;
  } else if (whole_arc(gap_when(!now), d)) {
    frame.arc_absolute = !now;
    s.centre_told = true;
    sink.warning({line, 1}, "W-MODEL-ARC-MODE",
                 fmt::format("this arc is whole only with I/J/K read as {}, as the controller's own setting must have "
                             "it: read so from here on (G{} at the program's start says so)",
                             now ? "offsets from its start" : "the absolute centre", now ? "91.1" : "90.1"));
  }
}

}  // namespace arcpress
