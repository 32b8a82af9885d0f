// SPDX-License-Identifier: GPL-3.0-or-later
// A whole program read at once: the state its controller starts in, the keywords it is
// lexed with, and interpret(), the ModalInterpreter over every block.
#include "arcpress/model/interpreter.hpp"

#include <fmt/format.h>

#include "arcpress/model/called_programs.hpp"

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

std::string start_units_warning(const Dialect& dialect) {
  auto g_name = [](int c10) { return c10 % 10 ? fmt::format("G{}.{}", c10 / 10, c10 % 10) : fmt::format("G{}", c10 / 10); };
  return fmt::format("a length before any {} or {}: read in millimetres until the program states its units; a "
                     "controller set to start in inches reads it 25.4 times larger (--units inch; --units mm, or a "
                     "printer's --dialect, says it starts in millimetres)",
                     g_name(dialect.code_for(CodeMeaning::Inch, 200)), g_name(dialect.code_for(CodeMeaning::Mm, 210)));
}

std::vector<KeywordSpelling> keywords_read(const Dialect& dialect) {
  std::vector<KeywordSpelling> out;
  for (const CodeReading& c : dialect.codes)
    if (c.letter == '&') out.push_back({c.keyword, c.meaning == CodeMeaning::CycleCalls || c.meaning == CodeMeaning::MacroCalls});
  return out;
}

Interpretation interpret(const Program& program, DiagnosticSink& sink, const Dialect& dialect, ModalState* state) {
  Interpretation out;
  ModalState start = state ? *state : initial_state(dialect);
  if (!state) start.called = called_programs_of(program, dialect);  // (read whole: its subprograms too)
  ModalInterpreter it(dialect, sink, start);
  it.begin(program, out);
  out.move_of_block.assign(program.blocks.size(), -1);
  out.moves.reserve(program.blocks.size());
  for (size_t bi = 0; bi < program.blocks.size(); ++bi) it.step(uint32_t(bi));
  if (state) *state = it.state();
  return out;
}

}  // namespace arcpress
