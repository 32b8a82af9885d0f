// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/model/jump_entries.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "arcpress/lex/jump_targets.hpp"
#include "arcpress/model/modal_state.hpp"

namespace arcpress {

namespace {

/// The modes in force in `s` under `frame`.
JumpEntries::Modes modes_of(const ModalState& s, const Frame& frame) {
  JumpEntries::Modes m;
  m.planes = (s.unstated & kStatesPlane) ? 8 : uint8_t(1u << int(s.plane));
  m.units = (s.unstated & kStatesUnits) ? 4 : frame.unit_mm == 1.0 ? 1 : 2;
  m.distance = s.distance_unknown ? 4 : frame.absolute ? 1 : 2;
  m.motion = int16_t(s.motion);
  m.extrusion = s.extrusion_unknown ? 4 : frame.e_relative ? 2 : 1;
  return m;
}

/// `s`'s entries, its own: copied first where other states share them.
JumpEntries& own_entries(ModalState& s) {
  // (A state no other shares is changed in place: one copy per piece, not one per jump.)
  std::shared_ptr<JumpEntries> copy = !s.jump_entries              ? std::make_shared<JumpEntries>()
                                      : s.jump_entries.use_count() == 1 ? std::const_pointer_cast<JumpEntries>(s.jump_entries)
                                                                        : std::make_shared<JumpEntries>(*s.jump_entries);
  JumpEntries& own = *copy;
  s.jump_entries = std::move(copy);
  return own;
}

/// Entry `number` of `s`'s entries, made where there is none.
JumpEntries::Entry& entry_of(ModalState& s, uint64_t number) {
  auto& list = own_entries(s).entries;
  auto at = std::lower_bound(list.begin(), list.end(), number,
                             [](const JumpEntries::Entry& e, uint64_t n) { return e.number < n; });
  if (at == list.end() || at->number != number) {
    JumpEntries::Entry e;
    e.number = number;
    at = list.insert(at, e);
  }
  return *at;
}

const char* plane_name(uint8_t planes) {
  return planes == 1 ? "G17" : planes == 2 ? "G18" : planes == 4 ? "G19" : "a plane not known";
}

const char* units_name(uint8_t units) { return units == 1 ? "G21" : units == 2 ? "G20" : "units not known"; }

std::string motion_name(int16_t motion) {
  return motion < 0 ? std::string("a motion not known") : fmt::format("G{}", motion / 10);
}

const char* distance_name(uint8_t distance) { return distance == 1 ? "G90" : distance == 2 ? "G91" : "G90 or G91 not known"; }

const char* extrusion_name(uint8_t e) { return e == 1 ? "E absolute" : e == 2 ? "E relative" : "E's mode not known"; }

/// Joins modes `m` into `into`, those of `bits` (kStates*).
void join(JumpEntries::Modes& into, const JumpEntries::Modes& m, uint8_t bits) {
  if (bits & kStatesPlane) into.planes |= m.planes;
  if (bits & kStatesUnits) into.units |= m.units;
  if (bits & kStatesDistance) into.distance |= m.distance;
  if (bits & kStatesMotion) into.motion = into.motion == -3 || into.motion == m.motion ? m.motion : int16_t(-1);
  if (bits & kStatesExtrusion) into.extrusion |= m.extrusion;
}

bool is_loop_of_blocks(uint64_t number) { return (number & JumpEntries::kLoopOfBlocks) != 0; }

/// The block entry `e` names: `N100`, or its label's line.
std::string target_name(const JumpEntries::Entry& e) {
  return e.number & kLabelKey ? fmt::format("the label at line {}", e.line) : fmt::format("N{}", e.number);
}

/// What a jump back to entry `e` is called where it runs lines again otherwise: `what` differs.
std::string refused_jump(const JumpEntries::Entry& e, const std::string& what) {
  if (is_loop_of_blocks(e.number))
    return fmt::format("the loop that begins at line {} runs its first lines again in other modes than they were "
                       "read in ({}), which moves there depend on: state them at the loop's start",
                       e.line, what);
  return fmt::format("the jump back to {0} runs the lines after it again in other modes than they were read in ({1}), "
                     "which moves there depend on: state them in that block",
                     target_name(e), what);
}

/// What differs between modes `here` and those entry `e` was read in that its first moves
/// used (a jump back), else empty; noted in `e` as refused at line `line`.
std::string refusal(JumpEntries::Entry& e, const JumpEntries::Modes& here, uint32_t line) {
  std::string what;
  auto differ = [&](const std::string& text) { what += (what.empty() ? "" : ", ") + text; };
  if ((e.used & kStatesPlane) && e.modes.planes != here.planes)
    differ(fmt::format("{} there, {} here", plane_name(e.modes.planes), plane_name(here.planes)));
  if ((e.used & kStatesUnits) && e.modes.units != here.units)
    differ(fmt::format("{} there, {} here", units_name(e.modes.units), units_name(here.units)));
  if ((e.used & kStatesMotion) && e.modes.motion != here.motion)
    differ(fmt::format("{} there, {} here", motion_name(e.modes.motion), motion_name(here.motion)));
  if ((e.used & kStatesDistance) && e.modes.distance != here.distance)
    differ(fmt::format("{} there, {} here", distance_name(e.modes.distance), distance_name(here.distance)));
  if ((e.used & kStatesExtrusion) && e.modes.extrusion != here.extrusion)
    differ(fmt::format("{} there, {} here", extrusion_name(e.modes.extrusion), extrusion_name(here.extrusion)));
  if (!what.empty() && e.refused.empty()) e.refused = what, e.refused_line = line;
  return what;
}

/// A jump at line `line` to block `number` in state `s`: what differs from the modes the
/// target's first moves used (read_jump()), else empty.
std::string jump_to(ModalState& s, uint64_t number, uint32_t line) {
  const JumpEntries::Modes here = modes_of(s, s.frame);
  JumpEntries::Entry& e = entry_of(s, number);
  if (!e.read) {  // ahead: the target is read in these modes too
    join(e.modes, here, kStatesPlane | kStatesUnits | kStatesMotion | kStatesExtrusion);
    return {};
  }
  return refusal(e, here, line);
}

/// A jump at line `line` to a number state `s` computes: ahead, the numbered blocks read after
/// it are read in its modes too; back, each numbered target read whose first moves used a mode
/// that differs here is refused (`used`, joined over all entries, says first whether any may
/// be). The first refused and what differed there, else nothing.
std::pair<uint64_t, std::string> computed_jump(ModalState& s, uint32_t line) {
  const JumpEntries::Modes here = modes_of(s, s.frame);
  JumpEntries& all = own_entries(s);
  join(all.computed, here, kStatesPlane | kStatesUnits | kStatesMotion | kStatesExtrusion);
  all.computed_jumps = true;
  const JumpEntries::Modes& used = all.used;
  auto differs = [](uint8_t set, uint8_t one) { return set != 0 && set != one; };
  if (!differs(used.planes, here.planes) && !differs(used.units, here.units) &&
      !differs(used.distance, here.distance) && !differs(used.extrusion, here.extrusion) &&
      (used.motion == -3 || used.motion == here.motion))
    return {};
  std::pair<uint64_t, std::string> first;
  for (JumpEntries::Entry& e : all.entries)
    if (e.read && !is_loop_of_blocks(e.number) && !(e.number & kLabelKey))  // (a number names neither a loop's start nor a label)
      if (std::string what = refusal(e, here, line); !what.empty() && first.second.empty()) first = {e.number, what};
  return first;
}

}  // namespace

void read_jump(ModalState& s, std::string_view line, uint32_t line_number, DiagnosticSink& sink) {
  if (const auto n = jump_named(line)) {
    if (const std::string what = jump_to(s, *n, line_number); !what.empty())
      sink.error({line_number, 1}, "E-FLOW-LOOP-MODES", refused_jump(entry_of(s, *n), what));
    if (calls_label(line)) s.forget_modes(kStatesAll);  // (the lines called return in the modes they leave)
  } else if (jump_computed(line)) {
    if (const auto [target, what] = computed_jump(s, line_number); !what.empty())
      sink.error({line_number, 1}, "E-FLOW-LOOP-MODES",
                 "a jump to a number the program computes, which may be back: " + refused_jump(entry_of(s, target), what));
  }
}

void loop_back(ModalState& s, uint32_t loop, uint32_t line_number, DiagnosticSink& sink) {
  const uint64_t key = JumpEntries::kLoopOfBlocks | loop;
  if (const std::string what = jump_to(s, key, line_number); !what.empty())
    sink.error({line_number, 1}, "E-FLOW-LOOP-MODES", refused_jump(entry_of(s, key), what));
}

namespace {

/// Entry `number` is entered in state `s` (`frame`): its modes are kept, and wait for a move
/// to use them.
void entered(ModalState& s, const Frame& frame, JumpEntries::Entry& e) {
  e.read = true;
  e.modes = modes_of(s, frame);
  auto& waiting = own_entries(s).waiting;
  for (uint32_t k = 0; k < waiting.size(); ++k)
    if (!(e.pending & (1u << k))) waiting[k].push_back(e.number);
  e.pending = kStatesAll;
  s.entry_pending |= e.pending;
}

}  // namespace

void enter_jumped(ModalState& s, Frame& frame, uint64_t key, uint32_t line) {
  const JumpEntries::Modes here = modes_of(s, frame);
  JumpEntries::Entry& e = entry_of(s, key);
  e.line = line;
  if (!e.read) {
    JumpEntries::Modes in = e.modes;  // the jumps' ahead of it (none: as here)
    if (s.jump_entries->computed_jumps) join(in, s.jump_entries->computed, kStatesAll);
    if ((in.planes | here.planes) != here.planes) s.unstated |= kStatesPlane;
    if ((in.units | here.units) != here.units) s.unstated |= kStatesUnits;
    if (in.motion != -3 && in.motion != here.motion) s.motion = -1;
    if ((in.extrusion | here.extrusion) != here.extrusion) s.extrusion_unknown = true;
  }
  if (e.loop) s.unstated |= kStatesPlane | kStatesUnits, s.motion = -1, s.extrusion_unknown = true;
  entered(s, frame, e);
}

void enter_loop(ModalState& s, uint32_t loop, uint32_t line) {
  JumpEntries::Entry& e = entry_of(s, JumpEntries::kLoopOfBlocks | loop);
  e.line = line;
  if (e.loop) s.forget_modes(kStatesAll);
  entered(s, s.frame, e);
}

namespace {

/// Modes `modes` of the entries waiting in `s` are settled: stated, or (`use`) used by a move.
void settle(ModalState& s, uint8_t modes, bool use) {
  auto& waiting = own_entries(s).waiting;
  uint8_t pending = 0;
  for (uint32_t k = 0; k < waiting.size(); ++k) {
    const uint8_t bit = uint8_t(1u << k);
    if (modes & bit) {
      for (const uint64_t number : waiting[k]) {
        JumpEntries::Entry& e = entry_of(s, number);
        e.pending &= uint8_t(~bit);
        if (use) e.used |= bit, join(own_entries(s).used, e.modes, bit);
      }
      waiting[k].clear();
    }
    if (!waiting[k].empty()) pending |= bit;
  }
  s.entry_pending = pending;
}

}  // namespace

void note_entry_use(ModalState& s, uint8_t modes) { settle(s, modes, true); }

void note_entry_stated(ModalState& s, uint8_t modes) { settle(s, modes, false); }

std::string loop_written_as_is(const JumpEntries::Entry& e) {
  if (is_loop_of_blocks(e.number))
    return fmt::format("the loop that begins at line {} runs its first lines again in other modes than they were read "
                       "in ({}): its moves are written as they are until the program states those modes (stated at "
                       "the loop's start, they are fitted)",
                       e.line, e.refused);
  return fmt::format("the jump back to {0} runs the lines after it again in other modes than they were read in ({1}): "
                     "the moves after it are written as they are until the program states those modes (stated in "
                     "that block, they are fitted)",
                     target_name(e), e.refused);
}

std::vector<JumpEntries::Entry> refused_loops(const ModalState& s) {
  std::vector<JumpEntries::Entry> out;
  if (s.jump_entries)
    for (const JumpEntries::Entry& e : s.jump_entries->entries)
      if (!e.refused.empty()) out.push_back(e);
  return out;
}

void seed_loops(ModalState& s, const std::vector<uint64_t>& numbers) {
  for (uint64_t n : numbers) entry_of(s, n).loop = true;
}

bool JumpEntries::reads_as(const JumpEntries& o) const {
  return std::equal(entries.begin(), entries.end(), o.entries.begin(), o.entries.end(), [](const Entry& x, const Entry& y) {
    return x.number == y.number && x.read == y.read && x.loop == y.loop && (x.read || x.modes == y.modes);
  }) && computed_jumps == o.computed_jumps && computed == o.computed;
}

bool ModalState::same_entries(const ModalState& o) const {
  return jump_entries == o.jump_entries || (jump_entries && o.jump_entries && jump_entries->reads_as(*o.jump_entries));
}

}  // namespace arcpress
