// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// LinuxCNC's subroutines in one program (`o100 sub` .. `o100 endsub`, called by `o100
// call`): a definition runs nothing where it stands, so the modes before it hold after it; a
// call runs the body in the caller's modes, and the caller goes on in the modes the body
// stated (rs274 -g: a body's G91 and G18 hold after its call).
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <utility>

#include "arcpress/model/move.hpp"

namespace arcpress {

/// Modes a body may state, as bits. (E's mode, kStatesExtrusion, is followed across jumps and
/// loops only: a subroutine's body is taken to leave it as it was.)
inline constexpr uint8_t kStatesPlane = 1, kStatesUnits = 2, kStatesDistance = 4, kStatesMotion = 8,
                         kStatesExtrusion = 16, kStatesAll = 31;

struct Subroutines {
  /// The modes before the definition being read, which hold again after it.
  struct Before {
    bool open = false;
    uint32_t label = 0;
    Frame frame;
    Plane plane = Plane::XY;
    int motion = 0;
    bool distance_unknown = false;
    bool feed_known = false;
    double feed_mm = 0;
    uint8_t unstated = 0;  ///< kStatesPlane/kStatesUnits not known where it began (ModalState::unstated)
  };
  Before before;

  /// What one body leaves where it returns (`return`, `endsub`), and the plane and units it
  /// was read in (those of its definition: a call in others would run another path).
  struct Body {
    uint32_t label = 0;
    Plane read_plane = Plane::XY;
    double read_unit_mm = 1;
    uint8_t states = 0;     ///< kStates* it leaves stated
    uint8_t ambiguous = 0;  ///< kStates* its returns leave stated differently
    Plane plane = Plane::XY;
    double unit_mm = 1;
    bool absolute = true;
    int motion = 0;
    /// The plane or units (kStatesPlane, kStatesUnits) not known where it is defined: its
    /// moves are placed only once it states them, so a call in any does not change them.
    uint8_t read_unstated = 0;
    bool operator==(const Body&) const = default;
  };
  static constexpr uint32_t kMostBodies = 32;
  std::array<Body, kMostBodies> bodies{};
  uint32_t count = 0;
  bool overflow = false;  ///< more bodies than kMostBodies: the rest are not known

  const Body* find(uint32_t label) const {
    for (uint32_t k = 0; k < count; ++k)
      if (bodies[k].label == label) return &bodies[k];
    return nullptr;
  }
  Body* find(uint32_t label) { return const_cast<Body*>(std::as_const(*this).find(label)); }
  /// Notes what the body being read leaves at a return: `states` stated, with these values.
  /// (`unknown`: kStates* it leaves not known, after a call of a body not read.)
  void leaves(uint8_t states, uint8_t unknown, Plane plane, double unit_mm, bool absolute, int motion) {
    Body* b = find(before.label);
    if (!b) {
      if (count == kMostBodies) {
        overflow = true;
        return;
      }
      b = &bodies[count++];
      *b = Body{before.label, before.plane, before.frame.unit_mm, states, unknown, plane, unit_mm, absolute, motion,
                before.unstated};
      return;
    }
    const uint8_t both = b->states & states;
    b->ambiguous |= (b->states ^ states) | unknown;
    if ((both & kStatesPlane) && b->plane != plane) b->ambiguous |= kStatesPlane;
    if ((both & kStatesUnits) && b->unit_mm != unit_mm) b->ambiguous |= kStatesUnits;
    if ((both & kStatesDistance) && b->absolute != absolute) b->ambiguous |= kStatesDistance;
    if ((both & kStatesMotion) && b->motion != motion) b->ambiguous |= kStatesMotion;
  }
  bool operator==(const Subroutines& o) const {
    return before.open == o.before.open && before.label == o.before.label && count == o.count &&
           overflow == o.overflow && std::equal(bodies.begin(), bodies.begin() + count, o.bodies.begin());
  }
};

struct ModalState;

/// `o<label> sub`: the modes before the definition are kept for its end, and the body is
/// read from nothing stated (the caller's position, distance mode and motion are the
/// interpreter's to forget).
void begin_definition(ModalState& s, uint32_t label);
/// `o.. return` or, `endsub`, `o.. endsub`: what the body leaves is noted; at its end, the modes
/// before the definition hold again (the frame in `frame`, for the interpreter to set).
void end_of_body(ModalState& s, bool endsub, Frame& frame);
/// `o<label> call`: the modes the body leaves stated take effect (the frame in `frame`), those
/// it may leave either way are unknown until the program states them (leave_body()).
/// Returns why the call cannot run the body as it was read (its definition's plane or units
/// differ), else nothing.
std::string after_call(ModalState& s, uint32_t label, Frame& frame);
/// The caller's modes after a body that leaves `body`; where null (a body not read), the plane,
/// distance mode and motion are unknown until the program states them, the units kept.
void leave_body(ModalState& s, const Subroutines::Body* body, Frame& frame);

}  // namespace arcpress
