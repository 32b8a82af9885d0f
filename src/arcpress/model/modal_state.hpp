// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The modal interpreter's state between two blocks.
#include <array>
#include <cstdint>
#include <memory>

#include "arcpress/model/block_nesting.hpp"
#include "arcpress/model/move.hpp"
#include "arcpress/model/subroutines.hpp"

namespace arcpress {

struct CalledPrograms;
struct JumpEntries;

/// What the interpreter knows between two blocks: every modal setting, the position and
/// which axes of it are known and why not. A program read in pieces (a stream) is read on
/// from the state the previous piece ended in, exactly as if it were read whole.
struct ModalState {
  Frame frame;
  Plane plane = Plane::XY;
  AxisValues pos{};                 ///< mm (degrees for A/B/C); stand-ins where not known
  uint32_t known = 1u << kE;        ///< bit per axis: position known; E is a counter from 0
  /// Per axis whose position is not known: why, and the line that made it so (0: never set).
  struct Why {
    Unfit reason = Unfit::UnknownAtStart;
    uint32_t line = 0;
  };
  std::array<Why, kAxisCount> why{};
  uint32_t cause_line = 0;          ///< of the last unplaced move
  /// The S in force after an S word that is an expression: constant until the next S word.
  static constexpr double kSpindleUnknown = -1;
  double spindle = 0;               ///< S in force
  int motion = 0;                   ///< modal motion G-code x10; G0 at power-up
  double feed_mm = 0;               ///< F in force, mm/min (or inverse time)
  bool feed_known = false;
  /// G20 or G21 has been read, or lengths were read in the dialect's start units and a
  /// warning said so (once): either way, nothing more to say of the units. It changes no
  /// reading, so reads_as() does not compare it.
  bool units_told = false;
  /// Whether G90 or G91 is in force is not known: the blocks from here on may be entered from
  /// elsewhere (after M2, M30 or M99, at a jump's target), until the program states one.
  bool distance_unknown = false;
  /// Whether E's words are places or increments (M82 or M83, and G90/G91 where the dialect's
  /// firmware reads E's mode with them) is not known: the blocks from here on may be entered
  /// with another (a loop's start its end runs again), until the program states it.
  bool extrusion_unknown = false;
  /// A program's end (M2, M30, M99) has been read: a program number after it (`O2000`) begins
  /// a program that runs when a call enters it (Mach3's and Fanuc's subprograms in one file).
  bool ended = false;
  /// The modes the calls read so far (M97, M98, G65) were made in, bits of those seen: a body
  /// only calls enter (JumpTargets::only_called(), a program number after an end) is read in
  /// them where they agree (enter_called()).
  struct CallModes {
    static constexpr int16_t kNoCall = -2;
    uint8_t distance = 0;         ///< 1: G90; 2: G91, or not known
    uint8_t planes = 0;           ///< 1 << Plane; 8: not known
    uint8_t units = 0;            ///< 1: mm; 2: inch; 4: not known
    int16_t motion = kNoCall;     ///< the motion (x10) every call was made in; -1 where they differ
    bool operator==(const CallModes&) const = default;
  };
  CallModes calls;
  /// What the bodies after the program's end leave, read ahead (null: not read).
  std::shared_ptr<const CalledPrograms> called;
  /// The modes the blocks jumps name are entered in (model/jump_entries.hpp; null: no jump yet).
  std::shared_ptr<const JumpEntries> jump_entries;
  /// The modes (kStates*) some jump target or loop entered was read in that no block has
  /// stated since and no move used yet (JumpEntries::Entry::pending, of them all).
  uint8_t entry_pending = 0;
  /// Bit per axis: known only up to a shift the program never states. Where an entry left the
  /// position unknown, G91 moves are read from the place it stands in for: placed relative to
  /// one another, as their increments are. G90 makes such an axis unknown again.
  uint32_t floating = 0;
  /// G90.1 or G91.1 has been read, or an arc showed how a controller set by a setting of its
  /// own reads I/J/K (Dialect::start_centres): no more to learn of it. Told, not compared.
  bool centre_told = false;
  /// Where the dialect's I/J/K set a centre that holds (Dialect::centre_modal): that centre,
  /// mm, absolute, by axis X/Y/Z, and the axes of it known (bit per axis). Arcs arcpress
  /// writes move it, and the emitter states the program's again before a block that reads it,
  /// so it is told, not compared.
  Vec3 pole{0, 0, 0};
  uint32_t pole_known = 0;
  /// Every move calls the cycle last defined at its end (a dialect's "cycle-calls" code,
  /// Heidenhain's M89), until a "cycle-call" code (M99, G79).
  bool cycle_calls = false;
  /// The way the program's last arc code turned, for the codes that turn as it did
  /// (Dialect::last_turn): 2 clockwise, 3 counter-clockwise, 0 none yet. Arcs arcpress writes
  /// change it, and the emitter spells the program's out where it is read, so it is told,
  /// not compared.
  uint8_t turn = 0;
  /// The blocks the leading blanks have opened, where they open blocks
  /// (Dialect::indented_blocks).
  BlockNesting nesting;
  /// The subroutines read so far and the definition being read (null: none).
  std::shared_ptr<const Subroutines> subs;
  /// The plane or units (kStatesPlane, kStatesUnits) stated since the definition being read began.
  uint8_t stated = 0;
  /// The plane or units (kStatesPlane, kStatesUnits) not known since a call of a subroutine that
  /// may change them (one not read), until the program states them: moves are not placed.
  uint8_t unstated = 0;

  /// The modes BlockNesting compares on a block's ways out.
  BlockNesting::Modes modes() const {
    return {uint8_t(plane), uint8_t(frame.unit_mm == 1.0 ? 1 : 2), uint8_t(distance_unknown ? 3 : frame.absolute ? 1 : 2),
            unstated, int16_t(motion), uint8_t(extrusion_unknown ? 3 : frame.e_relative ? 2 : 1)};
  }
  /// Modes `modes` (kStates*) are no longer known: a line entered on ways they differ on.
  void forget_modes(uint8_t modes) {
    if (modes & kStatesDistance) distance_unknown = true;
    if (modes & kStatesMotion) motion = -1;
    if (modes & kStatesExtrusion) extrusion_unknown = true;
    unstated |= modes & (kStatesPlane | kStatesUnits);
  }
  /// Whether the jump entries of this and `o` agree (model/jump_entries.cpp).
  bool same_entries(const ModalState& o) const;
  /// Whether a reader in state `o` reads every following block as one in this state does:
  /// the same position, known axes, frame, plane, feed and spindle, and (where
  /// `with_motion`) modal motion. The reasons axes are unknown, and their lines, are only told.
  /// Positions agree to the floating noise of summing relative moves (same_place()).
  /// (So are the G92 offsets, taken from such positions.)
  bool reads_as(const ModalState& o, bool with_motion) const {
    Frame f = frame;
    for (int ax = 0; ax < kAxisCount; ++ax) {
      if (!same_place(pos[ax], o.pos[ax]) || !same_place(frame.offset[ax], o.frame.offset[ax])) return false;
      f.offset[ax] = o.frame.offset[ax];
    }
    return f.same_as(o.frame) && plane == o.plane && known == o.known && spindle == o.spindle && cycle_calls == o.cycle_calls &&
           distance_unknown == o.distance_unknown && extrusion_unknown == o.extrusion_unknown && ended == o.ended &&
           calls == o.calls && called == o.called && same_entries(o) &&
           floating == o.floating && nesting == o.nesting &&
           stated == o.stated && unstated == o.unstated && (subs == o.subs || (subs && o.subs && *subs == *o.subs)) &&
           feed_known == o.feed_known && (!feed_known || feed_mm == o.feed_mm) && (!with_motion || motion == o.motion);
  }
};

}  // namespace arcpress
