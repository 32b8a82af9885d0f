// SPDX-License-Identifier: GPL-3.0-or-later
// A whole program read at once: the state its controller starts in, the keywords it is
// lexed with, and interpret(), the ModalInterpreter over every block.
#include "arcpress/model/interpreter.hpp"

namespace arcpress {

ModalState initial_state(const Dialect& dialect) {
  ModalState s;
  s.frame.diameter_mode = dialect.diameter_x;
  s.frame.unit_mm = dialect.start_units == StartUnits::Inch ? 25.4 : 1.0;
  s.units_told = dialect.start_units != StartUnits::Machine;
  s.frame.arc_absolute = dialect.start_centres == StartCentres::Absolute;
  s.centre_told = dialect.start_centres != StartCentres::Machine;
  return s;
}

std::vector<KeywordSpelling> keywords_read(const Dialect& dialect) {
  std::vector<KeywordSpelling> out;
  for (const CodeReading& c : dialect.codes)
    if (c.letter == '&') out.push_back({c.keyword, c.meaning == CodeMeaning::CycleCalls || c.meaning == CodeMeaning::MacroCalls});
  return out;
}

Interpretation interpret(const Program& program, DiagnosticSink& sink, const Dialect& dialect, ModalState* state) {
  Interpretation out;
  ModalInterpreter it(dialect, sink, state ? *state : initial_state(dialect));
  it.begin(program, out);
  out.move_of_block.assign(program.blocks.size(), -1);
  out.moves.reserve(program.blocks.size());
  for (size_t bi = 0; bi < program.blocks.size(); ++bi) it.step(uint32_t(bi));
  if (state) *state = it.state();
  return out;
}

}  // namespace arcpress
