// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The modes a jump's target is entered in. A controller that jumps (`GOTO 50`, `IF [..] GOTO
// 10`, `M99 P10`) goes on at the target in the plane, units and motion in force at the jump,
// which need not be those of the line before the target in the text: a jump ahead may pass
// over a `G18`, and a jump back, a loop, runs its first lines again in the modes its last
// lines left. A jump ahead is read before its target: the target is read in the modes of
// every way in, and a mode in which they differ is not known there until the program
// states it. A jump back comes after its target was read: where the loop's first lines
// used a mode (a move from a known place, before the program stated the mode again) that
// differs at the jump, no output can match both passes, and the run fails
// (E-FLOW-LOOP-MODES). The loops of blocks (`WHILE [..] DO1` .. `END1`, LinuxCNC's `o1 do`
// .. `o1 while`, RepRapFirmware's `while`: model/block_nesting.hpp) are read so too: the
// line after the one opening the loop is the entry, and the loop's end the jump back; their
// G90 or G91 counts as a mode too (a jump's target is read with it not known).
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "arcpress/core/diagnostic.hpp"
#include "arcpress/model/move.hpp"

namespace arcpress {

struct ModalState;

/// Per block number a jump names: the modes of the jumps to it read before it, or, once it
/// was read, the modes it was read in and which of them its first lines used.
struct JumpEntries {
  struct Modes {
    uint8_t planes = 0;     ///< 1 << Plane; 8: not known
    uint8_t units = 0;      ///< 1: mm; 2: inch; 4: not known
    uint8_t distance = 0;   ///< 1: G90; 2: G91; 4: not known
    int16_t motion = -3;    ///< modal motion x10; -1: not known or differing; -3: none yet
    uint8_t extrusion = 0;  ///< 1: E words are places (M82); 2: increments (M83); 4: not known
    bool operator==(const Modes&) const = default;
  };
  /// The number of a loop of blocks' entry: this bit and the loop's (BlockNesting::loops).
  static constexpr uint64_t kLoopOfBlocks = uint64_t(1) << 62;
  struct Entry {
    uint64_t number = 0;  ///< the target's key (a block number, kLabelKey | a label's hash), or kLoopOfBlocks | a loop's number
    uint32_t line = 0;    ///< a loop of blocks': the line that opens it, a label's: its line, where read
    bool read = false;  ///< the target has been read: `modes` are those it was read in
    Modes modes;        ///< the jumps' before it is read; its own after
    uint8_t used = 0;   ///< kStates* (model/subroutines.hpp) its first lines used
    uint8_t pending = 0;  ///< kStates* it was read in that no block has stated since and no move used yet
    std::string refused;        ///< what differed where a jump back to it was refused, else empty
    uint32_t refused_line = 0;  ///< that jump's line
    /// A first reading of the whole program found a jump back to it in other modes
    /// (seed_loops()): it is entered with its plane, units and motion not known.
    bool loop = false;
  };
  std::vector<Entry> entries;  ///< sorted by number
  /// Per mode (the bits of kStates*, lowest first): the numbers of the entries still waiting
  /// for it. The first block after an entry that states a mode, or move that uses it, settles
  /// it for every entry waiting (each is settled once: the cost stays linear).
  std::array<std::vector<uint64_t>, 5> waiting;
  /// The modes of the computed jumps (`GOTO #1`) read so far, joined: a numbered block read
  /// after them may be entered in any (`computed_jumps`: there were some).
  Modes computed;
  bool computed_jumps = false;
  /// The modes the targets read were read in, joined over those their first lines used: a
  /// computed jump back, which may enter any of them, is checked against these first.
  Modes used;
  /// Whether later blocks are read alike after these entries and `o`: the same targets read,
  /// those not yet read to be read in the same modes, and the same computed jumps. (What a target read was read in,
  /// and used, only decides whether a jump back is refused: an output, whose fitted blocks
  /// state their motion where the input's moves used the one in force, refuses no jump its
  /// input passed; where one did, the check would refuse that output.)
  bool reads_as(const JumpEntries& o) const;
};

/// Line `line` (line number `line_number`) read in state `s`: where it jumps to a numbered
/// block (jump_named()), ahead, its modes join those the target will be read in; back, where
/// the target's first lines used a mode that differs here, no output can match both passes:
/// an error (E-FLOW-LOOP-MODES) to `sink`.
void read_jump(ModalState& s, std::string_view line, uint32_t line_number, DiagnosticSink& sink);
/// Line `line_number`, read in state `s`, ends the loop of blocks numbered `loop` or runs it
/// again (BlockNesting::Join::loops_back): a jump back to its entry, as read_jump().
void loop_back(ModalState& s, uint32_t loop, uint32_t line_number, DiagnosticSink& sink);
/// The block of key `key` (JumpTargets: a block number, or a label's), a jump's target, is
/// entered at line `line`: where the jumps ahead of it were made in other modes than the text
/// before it leaves, or it is a loop's start seed_loops() marked, those are not known (the
/// plane and units until stated, the motion until a block names one); the modes it is read in
/// are kept for the jumps back to it, and which of them its first lines use (note_entry_use()).
void enter_jumped(ModalState& s, Frame& frame, uint64_t key, uint32_t line);
/// The first lines of the loop of blocks numbered `loop`, opened at line `line`, begin: its
/// entry, read as enter_jumped() reads a target no jump ahead names, where G90 or G91 is
/// known and kept.
void enter_loop(ModalState& s, uint32_t loop, uint32_t line);
/// A move from a known place read while modes of targets entered are pending
/// (ModalState::entry_pending): it uses `modes` of them (kStates*: a feed move all, a rapid
/// the units and G90 or G91 that place the moves after it), as the targets' first lines read
/// them. (A move from a place not known is written back as it is, and reads the same in the
/// output as in the input, whatever the modes.)
void note_entry_use(ModalState& s, uint8_t modes);
/// Modes `modes` (kStates*) are stated: the targets entered no longer wait for them.
void note_entry_stated(ModalState& s, uint8_t modes);
/// What is said of the loop `e` a first reading of a whole program refused (refused_loops()),
/// whose moves the reading after it writes as they are.
std::string loop_written_as_is(const JumpEntries::Entry& e);
/// The blocks a jump back to was refused in state `s`, a whole program's reading ended in.
std::vector<JumpEntries::Entry> refused_loops(const ModalState& s);
/// Marks blocks `numbers` in `s`, the state a program's reading starts in, as loops' starts
/// that a jump back runs again in other modes (refused_loops() of a first reading): each is
/// entered with its plane, units and motion not known until the program states them, so
/// that the moves after it are written as they are, not fitted, and no jump back is refused.
void seed_loops(ModalState& s, const std::vector<uint64_t>& numbers);

}  // namespace arcpress
