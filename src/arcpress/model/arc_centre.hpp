// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// How a controller finds an arc's centre from its words (I/J/K or R), and whether it runs
// the arc as drawn: the end must lie on the circle through the start about that centre, up
// to the controller's radius check. The modal interpreter reads input arcs with these.
#include <algorithm>
#include <optional>
#include <string_view>

#include "arcpress/core/diagnostic.hpp"
#include "arcpress/core/geometry.hpp"
#include "arcpress/dialect/dialect.hpp"
#include "arcpress/model/modal_state.hpp"
#include "arcpress/model/move.hpp"

namespace arcpress {

/// An input arc off its circle by no more than the controller's radius check, or than
/// LinuxCNC's default one (CENTER_ARC_RADIUS_TOLERANCE_MM, mm), is read as drawn: a
/// dialect's check may be the strictest setting (what arcpress writes must pass any), while
/// programs are written for the machine's own.
inline constexpr double kReadRadiusSlackMm = 0.0283;

/// The centre from I/J/K words (`ijk`, where `ijk_seen`) of an arc in `plane` from `from`:
/// offsets from it, or `as_absolute` the centre in `frame`'s coordinates. The plane's normal
/// axis, and an unseen word's axis under `as_absolute`, are `from`'s.
Vec3 ijk_centre(const Frame& frame, Plane plane, const AxisValues& from, const double* ijk, const bool* ijk_seen,
                bool as_absolute);

/// How far (mm) an arc in `plane` about `centre` from `from` ends off its circle at `to`,
/// and how far `dialect`'s radius check lets it.
struct RadiusGap {
  double gap_mm = 0, allowed_mm = 0;
};
RadiusGap radius_gap(const Dialect& dialect, Plane plane, const AxisValues& from, const Vec3& centre,
                     const AxisValues& to);

/// Whether the controller runs an arc with this gap as drawn (its check, or kReadRadiusSlackMm).
inline bool readable_arc(const RadiusGap& g) { return g.gap_mm <= std::max(g.allowed_mm, kReadRadiusSlackMm); }
/// Whether its radii agree to the dialect's absolute check (no share of a radius: read the
/// other way, a centre far off agrees by its share and would prove nothing).
inline bool whole_arc(const RadiusGap& g, const Dialect& dialect) {
  return g.gap_mm <= (dialect.radius_abs_mm > 0 ? dialect.radius_abs_mm : kRadiusAimMm);
}

/// The in-plane centre of an R-form arc from `s` to `e` (mm, in the plane) of radius `r_mm`
/// (negative: the long way round), `ccw` for G3 as RS274 turns. Nothing where the end
/// points coincide (`coincident`) or the radius falls short of half the chord by more than
/// `allowance_mm` (no circle joins them; controllers take one within their check as the
/// half circle).
struct RadiusCentre {
  std::optional<Vec2> centre;
  bool coincident = false;
  double half_chord_mm = 0;
};
RadiusCentre radius_centre(const Vec2& s, const Vec2& e, double r_mm, bool ccw, double allowance_mm);

/// An arc block's centre words: I/J/K where `ijk_seen` (indexed by X/Y/Z), or the radius R.
struct ArcWords {
  const double* ijk = nullptr;
  const bool* ijk_seen = nullptr;
  bool r_seen = false;
  double r_value = 0;  ///< R as written (program units; negative the long way round)
};

/// What the controller takes for an arc's centre: `known` false where no controller runs the
/// arc as drawn (no centre, an R too short, an end off the circle past the radius check).
struct ArcCentreRead {
  Vec3 centre{0, 0, 0};
  bool known = true;
  bool reads_pole = false;  ///< it turns about the centre left in force (Dialect::centre_modal)
};

/// The centre of an arc in `plane` from `from` to `target` (mm; `ccw` for G3 as RS274 turns)
/// with `words`, read in `frame` as `dialect`'s controller reads them; where the dialect's
/// centre is modal and the block has no centre words, about `pole` (the axes `pole_known`
/// says are known). Problems (E-MODEL-ARC-*, W-MODEL-ARC-R) go to `sink` at `line`.
ArcCentreRead read_arc_centre(const Dialect& dialect, const Frame& frame, Plane plane, const AxisValues& from,
                              const AxisValues& target, const ArcWords& words, bool ccw, const Vec3& pole,
                              uint32_t pole_known, DiagnosticSink& sink, uint32_t line);

/// Where the controller's own setting decides how I/J/K read (CentreReading::Incremental, the
/// setting not yet told), the program's first arc whose centre words name a point (one in
/// `plane` from `s.pos` to `target` with `ijk` where `ijk_seen`, its ends known) tells it:
/// read whole as they are, the setting is so; whole only the other way, it is the other way
/// from here on (`frame`'s arc_absolute, for the interpreter to set; W-MODEL-ARC-MODE at `line`).
void read_centre_mode(const Dialect& dialect, ModalState& s, Frame& frame, const AxisValues& target, const double* ijk,
                      const bool* ijk_seen, DiagnosticSink& sink, uint32_t line);

/// Where I/J/K set a centre that holds (Dialect::centre_modal, Heidenhain's pole): sets it in
/// `s` from a block's words (`ijk` where `ijk_seen`): the centre itself, or under G91 an
/// offset from the present point; where the block's own code sets it (`pole_here`, G29), the
/// present point.
void set_pole(ModalState& s, const double* ijk, const bool* ijk_seen, bool pole_here);

/// What block `block` of a program in state `s`, which reads the centre left in force (an
/// arc without centre words where `arc`, else a polar move), needs to state it again.
PoleRead pole_read(const ModalState& s, uint32_t block, bool arc);

/// Where `dialect` has codes that turn as the last programmed arc did (Dialect::last_turn):
/// G-code `g` (times ten) of block `bi` sets that way in `turn` (2 clockwise, 3
/// counter-clockwise, 0 none yet), or reads it (a TurnRead in `out` for the emitter; where no
/// arc set it, W-MODEL-ARC-TURN at `at`, the code spelled `spelled`) and is read as the code
/// that turns that way (G05 after a G02 as G02). Returns the code to read.
int read_turn(const Dialect& dialect, int g, uint8_t& turn, Interpretation& out, uint32_t bi, DiagnosticSink& sink,
              SourceLoc at, std::string_view spelled);

}  // namespace arcpress
