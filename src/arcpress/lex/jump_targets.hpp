// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The blocks a program's jumps may enter. A controller that runs `GOTO 100` or `M99 P100`
// goes on at the block numbered N100 from wherever it was; such a block must stay a block
// of its own with its number, and the position before it is not the one its neighbour in the
// text leaves. Read from the text, before the blocks are: a jump back names a block read
// before it.
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace arcpress {

/// Jumps name their targets by key: a block number (an N word's value, whole, below 10^15),
/// or this bit and the hash of a label's name (Sinumerik's `LOOP1:`, named by `GOTOB LOOP1`).
inline constexpr uint64_t kLabelKey = uint64_t(1) << 61;
/// The hash of label `name` (any case; 52 bits, so a double holds it exactly): the value of
/// its label word, and with kLabelKey the key of the jumps to it.
uint64_t label_hash(std::string_view name);
/// The key of block number `n` (an N word's value): none where no jump can name it.
std::optional<uint64_t> number_key(double n);

/// Targets read so far as no jump's, for a program read as it comes: a jump read later that
/// names one of them comes too late for it (JumpTargets::Late).
class PassedNumbers {
 public:
  /// The target of key `key` (a block number, or a label's) was read as no jump's.
  void pass(uint64_t key);
  bool passed(uint64_t key) const;
  /// Whether a numbered block was read as no jump's target (a computed jump may name it).
  bool any() const { return any_; }

 private:
  // A bit each below kBits; above it only that there were some.
  static constexpr uint64_t kBits = uint64_t(1) << 20;
  std::vector<uint64_t> bits_;
  bool any_ = false, high_ = false;
};

/// The key of the block the jump in `line` names (`GOTO 100`, `IF [..] GOTO 100`, `M99 P100`,
/// `GOTOB LOOP1`; not a call, which returns), read as JumpTargets::read() reads it; none where
/// the line holds no such jump or the program computes the number.
std::optional<uint64_t> jump_named(std::string_view line);
/// Whether `line` jumps to a block number the program computes (`GOTO #1`, `M99 P#5`), which
/// may be any numbered block's.
bool jump_computed(std::string_view line);
/// The key of the label Heidenhain's `G98 Ln` sets (label_hash() of `Ln`), for label number `n`.
uint64_t numbered_label_hash(uint64_t n);
/// Whether `line` calls the lines after a numbered label (Heidenhain's `L1,0`), which return
/// to the line after it in the modes they leave.
bool calls_label(std::string_view line);

class JumpTargets {
 public:
  /// Reads the jumps in `text`, whole lines, the first of them line `first_line`:
  /// `GOTO n` (Fanuc's and Haas's macro language, in an `IF [...] GOTO n` too; Okuma's
  /// `GOTO N100`; Sinumerik's `GOTOF`, `GOTOB`, `GOTOC`), `M99 Pn` (a subprogram's return to
  /// block n, or a jump there), `M97 Pn` (Haas's call of block n of the same program) and
  /// `M98 P.. Qn` (a call of a program from its block n, Mitsubishi's and Okuma's). A
  /// number computed by the program (`GOTO #1`, `M99 P#5`) may be any block's. A jump to a
  /// label (`GOTOB LOOP1`, Sinumerik's) names the label's key, as do Heidenhain's repeat of the
  /// lines after label n (`Ln,m`, m times) and call of them (`Ln,0`), which enter it from
  /// elsewhere. Comments and quoted text are skipped. A line that opens or ends a loop of blocks
  /// (`do`, `DO1`, `while`, `repeat`) is noted too (loops()). With `passed`, a jump to a block among them is
  /// noted as late(). Returns where in `text` the first line holding a program end (M2, M30,
  /// M99) ends, after which a file holds the subprograms its calls run, else npos.
  size_t read(std::string_view text, uint32_t first_line, const PassedNumbers* passed = nullptr);
  /// Adds the targets of `other` (and its late jump, if this has none).
  void merge(const JumpTargets& other);

  /// Whether a jump names some block, a computed one any, or the program has loops of
  /// blocks (`WHILE [..] DO1`, `o1 do`, `while`), which run their first lines again: whether
  /// its flow goes elsewhere than the next line.
  bool any() const { return computed_ || loops_ || !numbers_.empty(); }
  /// Whether the program has loops of blocks.
  bool loops() const { return loops_; }
  /// Whether a jump may enter the block of key `key` (its number's, number_key(), or its label's).
  bool enters(uint64_t key) const;
  /// Whether only calls enter it (M97 Pn, M98 P.. Qn), which return: no jump (GOTO, M99 P) does.
  bool only_called(uint64_t key) const;

  /// The first jump read after the block it names had been read as no target.
  struct Late {
    uint32_t line = 0;       ///< the jump's
    uint64_t number = 0;     ///< the block's key (0 with `computed`)
    bool computed = false;   ///< a computed jump, read after numbered blocks
  };
  const std::optional<Late>& late() const { return late_; }

 private:
  std::vector<uint64_t> numbers_;  // sorted, each once
  std::vector<uint64_t> jumped_;   // ... those a jump names, not only a call
  bool computed_ = false;
  bool loops_ = false;
  std::optional<Late> late_;
};

}  // namespace arcpress
