// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/model/subroutines.hpp"

#include <fmt/format.h>

#include "arcpress/core/geometry.hpp"
#include "arcpress/model/jump_entries.hpp"
#include "arcpress/model/modal_state.hpp"

namespace arcpress {
namespace {

/// A copy of `s`'s subroutines to change (the state's own are shared with its copies).
std::shared_ptr<Subroutines> own_copy(const ModalState& s) {
  return s.subs ? std::make_shared<Subroutines>(*s.subs) : std::make_shared<Subroutines>();
}

}  // namespace

void begin_definition(ModalState& s, uint32_t label) {
  auto subs = own_copy(s);
  subs->before = {true, label, s.frame, s.plane, s.motion, s.distance_unknown, s.feed_known, s.feed_mm,
                  uint8_t(s.unstated & (kStatesPlane | kStatesUnits))};
  s.subs = std::move(subs);
  s.stated = 0;
}

void end_of_body(ModalState& s, bool endsub, Frame& frame) {
  if (!s.subs || !s.subs->before.open) return;
  auto subs = own_copy(s);
  uint8_t states = s.stated | (s.distance_unknown ? 0 : kStatesDistance) | (s.motion < 0 ? 0 : kStatesMotion);
  // A body that returns in the plane or units it was read in leaves its caller in them, stated
  // or not: every call is made in them (after_call() fails the others). So a G18 .. G17 pair
  // around a run (the emitter's, or the program's own) does not change what the body leaves.
  const Subroutines::Before& read = subs->before;
  if (!(read.unstated & kStatesPlane) && s.plane == read.plane) states &= uint8_t(~kStatesPlane);
  if (!(read.unstated & kStatesUnits) && s.frame.unit_mm == read.frame.unit_mm) states &= uint8_t(~kStatesUnits);
  subs->leaves(states, s.unstated, s.plane, s.frame.unit_mm, s.frame.absolute, s.motion);
  if (endsub) {
    const Subroutines::Before& was = subs->before;
    frame = was.frame;
    s.plane = was.plane, s.motion = was.motion, s.distance_unknown = was.distance_unknown;
    s.feed_known = was.feed_known, s.feed_mm = was.feed_mm, s.stated = 0, s.unstated = was.unstated;
    subs->before.open = false;
  }
  s.subs = std::move(subs);
}

std::string after_call(ModalState& s, uint32_t label, Frame& frame) {
  const Subroutines::Body* body = s.subs ? s.subs->find(label) : nullptr;
  std::string problem;
  if (body && (s.unstated & (kStatesPlane | kStatesUnits) & ~body->read_unstated))
    problem = fmt::format(
        "this call runs a subroutine where the {} not known (after the call of a subroutine not read, or where a "
        "loop or jump may enter), whose body was read in G{} G{} where it is defined: its moves may have been fitted "
        "in another plane or scale; state the plane and units before the call",
        (s.unstated & kStatesPlane & ~body->read_unstated) ? "plane is" : "units are", plane_gcode(body->read_plane),
        body->read_unit_mm == 1 ? 21 : 20);
  else if (body && ((body->read_plane != s.plane && !(body->read_unstated & kStatesPlane)) ||
                     (body->read_unit_mm != frame.unit_mm && !(body->read_unstated & kStatesUnits))))
    problem = fmt::format(
        "this call runs a subroutine in G{} G{}, whose body was read in G{} G{} where it is defined: its moves may "
        "have been fitted in another plane or scale",
        plane_gcode(s.plane), frame.unit_mm == 1 ? 21 : 20, plane_gcode(body->read_plane), body->read_unit_mm == 1 ? 21 : 20);
  leave_body(s, body, frame);
  return problem;
}

void leave_body(ModalState& s, const Subroutines::Body* body, Frame& frame) {
  // A body not read is taken to keep the units: the program around the call, which states
  // them once at its start (as CAM posts write it), would be read otherwise by the controller
  // too were they changed.
  const uint8_t unknown = body ? body->ambiguous : kStatesPlane | kStatesDistance | kStatesMotion;
  const uint8_t known = body ? uint8_t(body->states & ~unknown) : 0;
  if (known & kStatesPlane) s.plane = body->plane;
  if (known & kStatesUnits) frame.unit_mm = body->unit_mm;
  s.stated |= known & (kStatesPlane | kStatesUnits);
  s.unstated &= uint8_t(~known);
  if (s.entry_pending & known) note_entry_stated(s, known);  // (stated for the entries waiting)
  if (known & kStatesDistance) frame.absolute = body->absolute, s.distance_unknown = false;
  if (known & kStatesMotion) s.motion = body->motion;
  if (unknown & kStatesDistance) s.distance_unknown = true;
  if (unknown & kStatesMotion) s.motion = -1;
  s.unstated |= unknown & (kStatesPlane | kStatesUnits);
}

}  // namespace arcpress
