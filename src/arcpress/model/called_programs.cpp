// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/model/called_programs.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "arcpress/model/modal_state.hpp"

namespace arcpress {
namespace {

/// The modes a body's jump, call or end leaves unknown where it returns. Its units too where it
/// states them; where it does not, they are kept, as after a call of a body not read
/// (leave_body()): a program states its units once.
constexpr uint8_t kFlowModes = kStatesPlane | kStatesDistance | kStatesMotion;
uint8_t unknown_after_flow(const Subroutines::Body& b) { return uint8_t(kFlowModes | (b.states & kStatesUnits)); }

/// A label's number, where `w` names one (O2000, N1000, P2000): a whole number, no expression.
bool label_number(const Word& w, uint64_t& n) {
  if (w.is_expr || !(w.value >= 0) || w.value >= 1e15 || w.value != std::floor(w.value)) return false;
  n = uint64_t(w.value);
  return true;
}

/// What one block does to the modes a body leaves.
struct Effect {
  bool returns = false;  ///< M99: the body returns after this block
  bool ends = false;     ///< M2, M30: the program ends, nothing returns
  bool flow = false;     ///< a jump, a call, an expression in a code: what it leaves is not known
  Subroutines::Body sets;  ///< the modes the block states (sets.states) and their values
};

/// Notes code `g` (times ten, as RS274 reads it) into `e`.
void note_g(int g, Effect& e) {
  Subroutines::Body& s = e.sets;
  switch (g) {
    case 170: case 180: case 190: s.plane = Plane((g - 170) / 10), s.states |= kStatesPlane; break;
    case 200: case 210: s.unit_mm = g == 200 ? 25.4 : 1.0, s.states |= kStatesUnits; break;
    case 900: case 910: s.absolute = g == 900, s.states |= kStatesDistance; break;
    case 0: case 10: case 20: case 30: s.motion = g, s.states |= kStatesMotion; break;
    // The rest of the motion group (threading, cycles, probing, splines): a motion the caller's
    // bare moves would not be read in.
    case 50: case 51: case 52: case 53: case 320: case 330: case 331: case 382: case 383: case 384: case 385:
    case 730: case 760: case 800: case 810: case 820: case 830: case 840: case 850: case 860: case 870: case 880:
    case 890:
      s.motion = -1, s.states |= kStatesMotion;
      break;
    case 650: e.flow = true; break;  // a macro call
    default: break;
  }
}

/// Notes G-code `g` (times ten) as dialect `d` reads it into `e`.
void note_g(int g, const Dialect& d, Effect& e) {
  if (const CodeMeaning* m = d.meaning_of('G', g)) {
    if (*m == CodeMeaning::Inch || *m == CodeMeaning::Mm) note_g(*m == CodeMeaning::Inch ? 200 : 210, e);
    if (*m == CodeMeaning::Unmodelled || *m == CodeMeaning::Moves) e.flow = true;
  } else if (d.turn_reading(g) || d.turn_set_by(g)) {
    e.sets.motion = -1, e.sets.states |= kStatesMotion;  // (the way the last arc turned: not read here)
  } else {
    note_g(g, e);
  }
}

Effect effect_of(const Program& p, const Block& b, const Dialect& d) {
  Effect e;
  if (b.kind == BlockKind::Control || b.kind == BlockKind::Macro || b.kind == BlockKind::Opaque) e.flow = true;
  if (b.kind != BlockKind::Code) return e;
  for (const Word* w = p.words_begin(b); w != p.words_end(b); ++w) {
    if (w->letter == 'G') {
      if (w->is_expr) {
        e.flow = true;
        continue;
      }
      note_g(w->code10(), d, e);
    } else if (w->letter == 'M') {
      const int m = w->code10();
      if (w->is_expr || m == 970 || m == 980) e.flow = true;
      if (m == 990) e.returns = true;
      if (m == 20 || m == 300) e.ends = true;
    }
  }
  return e;
}

/// The modes `later` leaves, read before them the modes of `earlier`: those `later` states
/// stand, `earlier`'s hold for the rest.
void state_before(Subroutines::Body& later, const Subroutines::Body& earlier) {
  const uint8_t add = earlier.states & ~later.states;
  if (add & kStatesPlane) later.plane = earlier.plane;
  if (add & kStatesUnits) later.unit_mm = earlier.unit_mm;
  if (add & kStatesDistance) later.absolute = earlier.absolute;
  if (add & kStatesMotion) later.motion = earlier.motion;
  later.states |= add;
}

bool is_end(const Program& p, const Block& b) {
  if (b.kind != BlockKind::Code) return false;
  for (const Word* w = p.words_begin(b); w != p.words_end(b); ++w)
    if (w->letter == 'M' && !w->is_expr && (w->code10() == 20 || w->code10() == 300 || w->code10() == 990)) return true;
  return false;
}

/// The label a call in block `b` names, or none.
std::optional<ProgramCall> call_in(const Program& p, const Block& b) {
  if (b.kind != BlockKind::Code) return std::nullopt;
  for (const Word* w = p.words_begin(b); w != p.words_end(b); ++w)
    if ((w->letter == 'M' && (w->code10() == 970 || w->code10() == 980)) || (w->letter == 'G' && w->code10() == 650))
      return read_call(p, b, w->code10());
  return std::nullopt;
}

}  // namespace

uint64_t CalledPrograms::key_of(const Word& w) {
  uint64_t n = 0;
  if (!label_number(w, n) || n >= kBlockLabel) return kNoLabel;
  return w.letter == 'N' ? block_key(n) : program_key(n);
}

uint8_t modes_stated(const Program& p, const Block& b, const Dialect& d) { return effect_of(p, b, d).sets.states; }

uint8_t modes_set_by(int code10, const Dialect& d) {
  Effect e;
  note_g(code10, d, e);
  return e.sets.states;
}

const CalledPrograms::Entry* CalledPrograms::find(uint64_t key) const {
  const auto at = std::lower_bound(entries.begin(), entries.end(), key, [](const Entry& e, uint64_t k) { return e.key < k; });
  return at != entries.end() && at->key == key ? &*at : nullptr;
}

std::shared_ptr<const CalledPrograms> read_called_programs(const Program& p, uint32_t from, const Dialect& d) {
  auto out = std::make_shared<CalledPrograms>();
  // From the last block back: what the blocks from each label to the next return state,
  // the last statement of each mode first found. Past the text's end no return is read.
  Subroutines::Body after;
  after.ambiguous = kFlowModes;
  bool computed_call = false;
  std::vector<uint64_t> called;
  for (uint32_t bi = uint32_t(p.blocks.size()); bi-- > from;) {
    const Block& b = p.blocks[bi];
    const Effect e = effect_of(p, b, d);
    if (e.returns) after = Subroutines::Body{};
    if (e.ends) after = Subroutines::Body{}, after.ambiguous = kFlowModes;
    if (e.flow) after.ambiguous |= unknown_after_flow(after);
    state_before(after, e.sets);  // (this block's statements hold where no later one states the mode again)
    if (const std::optional<ProgramCall> c = call_in(p, b)) {
      if (!c->known) computed_call = true;
      else called.insert(called.end(), {c->key, c->fallback_key});
    }
    for (const Word* w = p.words_begin(b); w != p.words_end(b); ++w)
      if (w->letter == 'O' || w->letter == 'N')
        if (const uint64_t key = CalledPrograms::key_of(*w); key != CalledPrograms::kNoLabel)
          out->entries.push_back({key, after, false});
  }
  // (Read back to front: a label written twice keeps its first body, and is not known.)
  std::reverse(out->entries.begin(), out->entries.end());
  std::stable_sort(out->entries.begin(), out->entries.end(),
                   [](const CalledPrograms::Entry& x, const CalledPrograms::Entry& y) { return x.key < y.key; });
  std::vector<CalledPrograms::Entry> once;
  for (const CalledPrograms::Entry& e : out->entries) {
    if (!once.empty() && once.back().key == e.key) {
      Subroutines::Body& b = once.back().leaves;
      b.states |= e.leaves.states;
      b.ambiguous |= unknown_after_flow(b);
      continue;
    }
    once.push_back(e);
  }
  out->entries.swap(once);
  std::sort(called.begin(), called.end());
  for (CalledPrograms::Entry& e : out->entries)
    e.called_inside = computed_call || std::binary_search(called.begin(), called.end(), e.key);
  return out;
}

std::shared_ptr<const CalledPrograms> called_programs_of(const Program& p, const Dialect& d) {
  for (uint32_t bi = 0; bi < p.blocks.size(); ++bi)
    if (is_end(p, p.blocks[bi])) return read_called_programs(p, bi + 1, d);
  return nullptr;
}

ProgramCall read_call(const Program& p, const Block& b, int code10) {
  ProgramCall c;
  uint64_t n = 0;
  const Word* w = p.find(b, 'P');
  if (!w || !label_number(*w, n) || n >= (uint64_t(1) << 62)) return c;
  c.known = true;
  c.key = code10 == 970 ? CalledPrograms::block_key(n) : CalledPrograms::program_key(n);
  c.fallback_key = n >= 10000 && code10 == 980 ? CalledPrograms::program_key(n % 10000) : c.key;
  for (char count : {'L', 'K'})
    if (const Word* r = p.find(b, count)) c.repeats = r->is_expr ? 2 : int(std::clamp(r->value, 0.0, 1e6));
  return c;
}

namespace {

/// Notes the modes a call made in state `s` (frame `f`) enters its body in.
void note_call(ModalState& s, const Frame& f) {
  ModalState::CallModes& c = s.calls;
  c.distance |= s.distance_unknown ? 2 : f.absolute ? 1 : 2;
  c.planes |= (s.unstated & kStatesPlane) ? 8 : uint8_t(1u << int(s.plane));
  c.units |= (s.unstated & kStatesUnits) ? 4 : f.unit_mm == 1 ? 1 : 2;
  c.motion = c.motion == ModalState::CallModes::kNoCall || c.motion == s.motion ? int16_t(s.motion) : int16_t(-1);
}

}  // namespace

void return_from_call(ModalState& s, const ProgramCall& c, Frame& frame) {
  note_call(s, frame);
  const CalledPrograms::Entry* body = nullptr;
  int repeats = c.repeats;
  if (s.called && c.known) {
    body = s.called->find(c.key);
    if (!body && c.fallback_key != c.key && (body = s.called->find(c.fallback_key))) repeats = int(c.key / 10000);
  }
  leave_body(s, body ? &body->leaves : nullptr, frame);
  // Run again, the body is entered in the modes it left.
  if (repeats > 1) note_call(s, frame);
}

void enter_called(ModalState& s, uint64_t key, Frame& frame) {
  const CalledPrograms::Entry* body = s.called ? s.called->find(key) : nullptr;
  // (Calls not all read: the distance mode, plane and motion are unknown; the units kept, as
  // after a call of a body not read, leave_body().)
  const ModalState::CallModes c = body && !body->called_inside ? s.calls : ModalState::CallModes{2, 8, 0, -1};
  if (c.distance & 2) s.distance_unknown = true;
  else frame.absolute = true, s.distance_unknown = false;
  // A mode no call was made in yet stays as the program's end left it.
  if (std::has_single_bit(c.planes) && c.planes < 8) s.plane = Plane(std::countr_zero(c.planes)), s.unstated &= ~kStatesPlane;
  else if (c.planes) s.unstated |= kStatesPlane;
  if (c.units == 1 || c.units == 2) frame.unit_mm = c.units == 2 ? 25.4 : 1.0, s.unstated &= ~kStatesUnits;
  else if (c.units) s.unstated |= kStatesUnits;
  if (c.motion != ModalState::CallModes::kNoCall) s.motion = c.motion;
}

bool end_program(ModalState& s, Frame& frame) {
  frame.absolute = true;
  frame.inverse_time = false;
  const bool offset = frame.work_offset != 54 && frame.work_offset != 540;  // (G54 is read as 540, at the start 54)
  if (offset) frame.work_offset = 540;
  s.distance_unknown = false;
  s.plane = Plane::XY;
  s.motion = 10;
  return offset;
}

}  // namespace arcpress
