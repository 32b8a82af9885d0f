// SPDX-License-Identifier: GPL-3.0-or-later
// A whole program read at once: the state its controller starts in, the keywords it is
// lexed with, and interpret(), the ModalInterpreter over every block.
#include "arcpress/model/interpreter.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "arcpress/lex/jump_targets.hpp"
#include "arcpress/model/called_programs.hpp"
#include "arcpress/model/jump_entries.hpp"

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

LexRules lex_rules(const Dialect& dialect) {
  LexRules out;
  for (const CodeReading& c : dialect.codes)
    if (c.letter == '&')
      out.keywords.push_back({c.keyword, c.meaning == CodeMeaning::CycleCalls || c.meaning == CodeMeaning::MacroCalls});
  out.assignments = dialect.assignments;
  out.labels = dialect.labels;
  out.numbered_labels = dialect.numbered_labels;
  return out;
}

LoopsFound loops_in_other_modes(const Program& program, const Dialect& dialect, const ModalState& start) {
  LoopsFound found;
  // (A program lexed without its jumps read, JumpTargets, may still loop by blocks.)
  auto loops_by_blocks = [&] {
    JumpTargets t;
    t.read(program.text, 1);
    return t.loops();
  };
  if (!program.jumps && !loops_by_blocks()) return found;
  // (A start marked reads the moves after it unplaced, which may leave another loop's jump
  // in a mode not known: read again, a few times at most.)
  constexpr int kRounds = 4;
  for (int round = 0; round < kRounds; ++round) {
    DiagnosticSink quiet(program.name);
    ModalState s = start;
    seed_loops(s, found.starts);
    (void)interpret(program, quiet, dialect, &s);
    const std::vector<JumpEntries::Entry> more = refused_loops(s);
    if (more.empty()) break;
    for (const JumpEntries::Entry& e : more) {
      found.starts.push_back(e.number);
      found.told.push_back({Severity::Warning, {e.refused_line, 1}, "W-FLOW-LOOP-MODES", loop_written_as_is(e)});
    }
    std::sort(found.starts.begin(), found.starts.end());
    found.starts.erase(std::unique(found.starts.begin(), found.starts.end()), found.starts.end());
  }
  return found;
}

ModalState whole_program_start(const Program& program, const Dialect& dialect, DiagnosticSink& sink) {
  ModalState start = initial_state(dialect);
  start.called = called_programs_of(program, dialect);  // (read whole: its subprograms too)
  const LoopsFound loops = loops_in_other_modes(program, dialect, start);
  seed_loops(start, loops.starts);
  for (const Diagnostic& d : loops.told) sink.warning(d.at, d.code, d.message);
  return start;
}

Interpretation interpret(const Program& program, DiagnosticSink& sink, const Dialect& dialect, ModalState* state) {
  Interpretation out;
  const ModalState start = state ? *state : whole_program_start(program, dialect, sink);
  ModalInterpreter it(dialect, sink, start);
  it.begin(program, out);
  out.move_of_block.assign(program.blocks.size(), -1);
  out.moves.reserve(program.blocks.size());
  for (size_t bi = 0; bi < program.blocks.size(); ++bi) it.step(uint32_t(bi));
  if (state) *state = it.state();
  return out;
}

}  // namespace arcpress
