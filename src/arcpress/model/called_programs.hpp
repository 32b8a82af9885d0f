// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Subprograms a call runs (Fanuc's and Haas's `M98 P2000` of program O2000, Haas's `M97
// P1000` of block N1000, Fanuc's macro call `G65 P2000`), written after the main program's
// end in the same file. A controller runs a body in the modes of the call, and the caller goes
// on in the modes the body leaves: a body that states G91 and returns leaves its caller's
// absolute words read as increments. The body comes after the call in the text, so what each
// leaves is read ahead of the blocks (read_called_programs()); how each was entered is what
// the calls read before it say (ModalState::calls).
#include <cstdint>
#include <memory>
#include <vector>

#include "arcpress/dialect/dialect.hpp"
#include "arcpress/lex/block.hpp"
#include "arcpress/model/subroutines.hpp"

namespace arcpress {

struct ModalState;

/// What the bodies after a program's end leave where they return, by the label a call names.
struct CalledPrograms {
  struct Entry {
    uint64_t key = 0;            ///< program_key() or block_key()
    Subroutines::Body leaves;    ///< the modes stated from the label to the body's return
    bool called_inside = false;  ///< a body after the end calls it too (in modes not read ahead)
  };
  std::vector<Entry> entries;  ///< sorted by key, each once

  static uint64_t program_key(uint64_t number) { return number; }              ///< O2000, `M98 P2000`
  static uint64_t block_key(uint64_t number) { return number | kBlockLabel; }  ///< N1000, `M97 P1000`
  /// The key of label word `w` (O or N), or kNoLabel where it names none (O#1, N10.5).
  static uint64_t key_of(const Word& w);
  static constexpr uint64_t kNoLabel = ~uint64_t(0);
  const Entry* find(uint64_t key) const;

 private:
  static constexpr uint64_t kBlockLabel = uint64_t(1) << 62;
};

/// The bodies in blocks [from, end) of `program`, read with `dialect`'s codes: for each block
/// with an O or N number, the plane, units, distance mode and motion stated from it to the
/// first return (M99) after it. A jump or call before that return, or a program end, leaves
/// the plane, distance mode and motion unknown (Subroutines::Body::ambiguous), and the units
/// where the body states them.
std::shared_ptr<const CalledPrograms> read_called_programs(const Program& program, uint32_t from,
                                                           const Dialect& dialect);
/// The same for a whole program: the bodies after its first end (M2, M30, M99), as the
/// compressor reads them from the text after that end. Null where it has no end.
std::shared_ptr<const CalledPrograms> called_programs_of(const Program& program, const Dialect& dialect);

/// The modes block `b` states (kStates*: G17..G19, G20/G21 and `dialect`'s own codes for them,
/// G90/G91, a motion code).
uint8_t modes_stated(const Program& program, const Block& b, const Dialect& dialect);
/// The modes G-code `code10` (the code times ten) sets as `dialect` reads it, as modes_stated().
uint8_t modes_set_by(int code10, const Dialect& dialect);

/// The call in block `b` (its code times ten: 970, 980 or 650): the label its P names and
/// how many times it runs (L or K; Fanuc's `M98 P30002000` runs O2000 three times).
struct ProgramCall {
  bool known = false;  ///< P names a label (no expression, no missing P)
  uint64_t key = 0;
  uint64_t fallback_key = 0;  ///< (where P has more than 4 digits: its last 4, a count before them)
  int repeats = 1;
};
ProgramCall read_call(const Program& program, const Block& b, int code10);

/// The caller's modes after block `bi` made call `c` (Subroutines' rules: those the body leaves
/// stated hold, those it may leave either way, or a body not read ahead, are unknown until
/// the program states them); the frame in `frame`, for the interpreter to set. The modes the
/// call was made in are noted for the body's entry (enter_called()).
void return_from_call(ModalState& s, const ProgramCall& c, Frame& frame);
/// A body only calls enter, at the block labelled `key`: read in the modes every call so far
/// was made in, where they agree, else with them unknown. A body a later body calls too, or one
/// with no bodies read ahead (a program read as it comes), is entered with the distance mode,
/// plane and motion unknown, in the units in force.
void enter_called(ModalState& s, uint64_t key, Frame& frame);
/// An M2 or M30 read in state `s` (its frame `frame`): RS274's program end (LinuxCNC's,
/// Grbl's) puts G1, G17, G90, G94 and G54 in force; a sender that streams on runs what
/// follows so. Returns whether the work offset changed (the position is then not known).
bool end_program(ModalState& s, Frame& frame);

}  // namespace arcpress
