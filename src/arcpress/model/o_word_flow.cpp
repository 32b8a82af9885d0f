// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/model/o_word_flow.hpp"

namespace arcpress {

OWordFlow follow_o_word(ModalState& s, const OWord& w, Frame& frame) {
  using K = OWord::Kind;
  BlockNesting& n = s.nesting;
  const uint8_t mode = BlockNesting::mode_of(frame.absolute, s.distance_unknown);
  OWordFlow flow;
  switch (w.kind) {
    case K::If: n.open(w.label, false); break;
    case K::Do: case K::Repeat: n.open(w.label, w.kind == K::Do, true, mode); break;
    case K::While:  // (the end of a `do`, or a loop of its own)
      if (n.in_do(w.label)) flow.join = n.close(w.label, mode);
      else n.open(w.label, false, true, mode);
      break;
    case K::ElseIf: case K::Else:  // (entered from where the `if` began, not from the branch before)
      flow.join = n.close(w.label, mode);
      n.open(w.label, false);
      break;
    case K::EndIf: case K::EndWhile: case K::EndRepeat: flow.join = n.close(w.label, mode); break;
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
