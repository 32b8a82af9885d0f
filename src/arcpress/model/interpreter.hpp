// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Modal interpreter stage: blocks -> moves in absolute millimetres, tracking every modal
// group that changes how words are read. What it cannot evaluate (expressions, flow
// control, canned cycles, machine-coordinate moves) makes the position unknown and is a
// barrier that later stages never fit across.
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "arcpress/core/diagnostic.hpp"
#include "arcpress/dialect/dialect.hpp"
#include "arcpress/lex/block.hpp"
#include "arcpress/model/modal_state.hpp"
#include "arcpress/model/move.hpp"

namespace arcpress {

/// The state at the start of a program read by `dialect`'s controller.
ModalState initial_state(const Dialect& dialect);
/// What a program that writes a length before stating its units is told (W-MODEL-UNITS): the
/// lengths are read in millimetres, as the frame of initial_state() says, unless told otherwise.
std::string start_units_warning(const Dialect& dialect);

/// Reads a program block by block, from a given state: for a program that arrives in pieces.
class ModalInterpreter {
 public:
  ModalInterpreter(const Dialect& dialect, DiagnosticSink& sink, const ModalState& start);
  ~ModalInterpreter();
  ModalInterpreter(ModalInterpreter&&) noexcept;
  /// Reads blocks of `program` into `out` from here on (out.start is the present position);
  /// both must outlive the step() calls, and `program` may grow between them.
  void begin(const Program& program, Interpretation& out);
  /// Reads block `block` of the program; blocks are read in order, each once.
  void step(uint32_t block);
  const ModalState& state() const;
  /// Goes back to `state` (one the reader was in before a block it read since), as if the
  /// blocks after it had not been read; the caller takes them out of the program and its
  /// interpretation.
  void reset(const ModalState& state);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// How a program in `dialect` is lexed (Program::rules): the keywords its [codes] give a
/// meaning, a modal call's taking the call after it, and its assignments and labels ([lines]).
LexRules lex_rules(const Dialect& dialect);

/// Reads `program` as `dialect`'s controller would (centre form, G18 direction, numbers
/// without a decimal point); the default is generic RS274. With `state`, reading starts
/// from it and it is left as the program ends; without, from whole_program_start().
Interpretation interpret(const Program& program, DiagnosticSink& sink, const Dialect& dialect = Dialect{},
                         ModalState* state = nullptr);

/// The loops of `program` read from `start` whose jump back would run their first moves in
/// other modes than they were read in (E-FLOW-LOOP-MODES, model/jump_entries.hpp): the
/// numbers of their starts, and why, as warnings (W-FLOW-LOOP-MODES). Read with those starts
/// in seed_loops() (read again until no other is found), the program is refused nowhere:
/// the moves after each start are written as they are until the program states the modes.
struct LoopsFound {
  std::vector<uint64_t> starts;
  std::vector<Diagnostic> told;
};
LoopsFound loops_in_other_modes(const Program& program, const Dialect& dialect, const ModalState& start);
/// The state interpret() without a state starts `program` in: initial_state() and what the
/// subprograms after its end leave; with the starts of loops_in_other_modes() marked, the
/// warnings told to `sink`.
ModalState whole_program_start(const Program& program, const Dialect& dialect, DiagnosticSink& sink);

}  // namespace arcpress
