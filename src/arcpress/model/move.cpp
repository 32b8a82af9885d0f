// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/model/move.hpp"

namespace arcpress {

const char* describe(Unfit why) {
  switch (why) {
    case Unfit::None: return "a lone G1 move: no fittable move beside it to make a run with";
    case Unfit::UnknownAtStart: return "position unknown: an axis it moves was never set before it";
    case Unfit::UnknownAfterHoming: return "position unknown after homing or bed probing (G28/G29/G30)";
    case Unfit::UnknownAfterMachine: return "position unknown after a machine-coordinate move (G53)";
    case Unfit::UnknownAfterCycle: return "position unknown after a cycle, probe, spline or G10";
    case Unfit::UnknownAfterExpression: return "position unknown after an expression";
    case Unfit::UnknownAfterControl:
      return "position unknown after flow control, a macro or parameter line, a subprogram or a host command";
    case Unfit::UnknownAfterOffset: return "position unknown after a work or tool offset change";
    case Unfit::UnknownInPolar: return "position not computed in polar coordinates (G16)";
    case Unfit::UnknownAfterToolChange: return "position unknown after a tool change (M6, or the dialect's tool call), which may move the tool";
    case Unfit::UnknownAfterCodeMove: return "position unknown after a code the dialect says may move the tool";
    case Unfit::UnknownAtEntry:
      return "position unknown where the program may arrive from elsewhere (the target of a GOTO, M99 P, M97 P or "
             "M98 Q, a loop's start (M808 L), after M99 or a subroutine call, a program number after a program's end, a subroutine's start, a "
             "line that ends an if, else or loop block)";
    case Unfit::UnknownDistanceMode:
      return "position unknown: moved after such an entry before the program stated G90 or G91 (after a call of a "
             "subroutine not read, at a jump's target or loop's start entered in other modes, after a block that "
             "changed them, a line not read or a G word with an expression; also G17/G18/G19, G20/G21 and G0/G1)";
    case Unfit::UnknownAfterUnmodelled: return "position unknown after a G-code arcpress does not model";
    case Unfit::UnreadableArc: return "an arc the controller cannot run: no centre, or R too short for its chord";
    case Unfit::RepeatedWord: return "a word repeated in the block";
    case Unfit::NotLine: return "not a G1 move";
    case Unfit::OtherWords: return "other words in the block (modal codes, M, T, arc words)";
    case Unfit::Comment: return "comment in the block";
    case Unfit::Expression: return "expression in the block";
    case Unfit::BlockDelete: return "block delete ('/')";
    case Unfit::Checksum: return "checksum in the block";
    case Unfit::InverseTime: return "inverse-time feed (G93)";
    case Unfit::DiameterMode: return "lathe diameter mode (G7): left as it is";
    case Unfit::FeedUnknown: return "no feed rate in force";
    case Unfit::ExtrusionModeUnknown:
      return "E words where E's mode (M82 or M83) is not known: the ways in may leave either (a jump, a loop, the end of "
             "an if block, a line not read), until the program states it";
    case Unfit::NoPathAxis: return "moves only E or extra axes";
    case Unfit::FarFromOrigin: return "too far from the origin for the check to measure a fit of it within the band";
    case Unfit::CycleCall: return "it calls a cycle at its end (a modal cycle call: M89)";
    case Unfit::BeforeUnmodelled:
      return "the last move before a code or line arcpress does not read, which may go on from it (a chamfer or "
             "rounding after it, a tangential arc)";
  }
  return "?";
}

}  // namespace arcpress
