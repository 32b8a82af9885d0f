// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/model/o_word_flow.hpp"

namespace arcpress {

BlockNesting::Join follow_repeat_marker(ModalState& s, bool mark, uint32_t line) {
  constexpr uint32_t kRepeatLabel = 0x4D383038;  // ("M808"; an O-word label, a hash, is another but once in 2^32)
  if (!mark) return s.nesting.close(kRepeatLabel, s.modes());
  BlockNesting::Join j;
  const uint32_t number = s.nesting.open(kRepeatLabel, false, true, s.modes());
  if (number == BlockNesting::kUnfollowed) j.loop_unfollowed = true;
  else j.loop_entered = number, j.loop_line = line;
  return j;
}

OWordFlow follow_o_word(ModalState& s, const OWord& w, Frame& frame, uint32_t line) {
  using K = OWord::Kind;
  BlockNesting& n = s.nesting;
  const BlockNesting::Modes now = s.modes();
  OWordFlow flow;
  auto open_loop = [&](bool do_loop) {
    const uint32_t number = n.open(w.label, do_loop, true, now);
    if (number == BlockNesting::kUnfollowed) flow.join.loop_unfollowed = true;
    else flow.join.loop_entered = number, flow.join.loop_line = line;
  };
  switch (w.kind) {
    case K::If: n.open(w.label, false, false, now); break;
    case K::Do: case K::Repeat: open_loop(w.kind == K::Do); break;
    case K::While:  // (the end of a `do`, or a loop of its own)
      if (n.in_do(w.label)) {
        flow.join = n.close(w.label, now);
      } else {
        open_loop(false);
      }
      break;
    case K::ElseIf: case K::Else:  // (entered from where the `if` began, not from the branch before)
    {
      const BlockNesting::Modes at_if = n.depth > 0 && n.levels[n.depth - 1].label == w.label ? n.levels[n.depth - 1].at_open : now;
      flow.join = n.close(w.label, now);
      n.open(w.label, false, false, at_if);
      n.branch_ended(flow.join);
      break;
    }
    case K::EndIf: case K::EndWhile: case K::EndRepeat: flow.join = n.close(w.label, now); break;
    case K::Continue: flow.join.back_to(n.loop_of(w.label)); break;
    case K::Sub:
      begin_definition(s, w.label);
      flow.enters_body = true;
      break;
    case K::Call:
      flow.after_call = true;
      flow.problem = after_call(s, w.label, frame);
      break;
    case K::Return: case K::EndSub: end_of_body(s, w.kind == K::EndSub, frame); break;
    case K::Other: break;
  }
  return flow;
}

}  // namespace arcpress
