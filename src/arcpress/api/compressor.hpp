// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The streaming engine: a program compressed as it arrives, in bounded memory.
//
// Bytes pushed in are cut into whole lines, lexed and read by the modal interpreter on the
// caller's thread, and gathered into pieces (piece.hpp) of about kPieceBytes (the first
// few smaller, piece_bytes()): a piece ends after the first move no fit may join (a rapid,
// a retraction, a move with a comment or from an unknown position...) once it holds that
// much, so a chain of runs is never cut there and the fit is the one the whole program
// would get; past kCornerPieceBytes it may also end before a move that starts at a corner,
// and a path that goes on for kMaxPieceBytes without either is cut at a vertex (a forced
// cut, counted in the result). Each closed piece is fitted, written and checked on a
// worker thread; finished pieces are released in program order. At most kPiecesInFlight
// pieces per worker wait or are worked on, so memory does not grow with the program: push()
// waits for the oldest while they are that many. The text is the same for any number of
// threads and any way the bytes are cut into pushes.
#include <algorithm>
#include <cstddef>
#include <exception>
#include <memory>
#include <string>
#include <string_view>

#include "arcpress/api/arcpress.hpp"

namespace arcpress {

/// Input bytes a piece gathers before it may end at the next move no fit joins.
inline constexpr size_t kPieceBytes = size_t(1) << 17;
/// The input bytes the first piece gathers before it may end; each after it gathers twice
/// as many as the one before, up to kPieceBytes. The workers start on a program while its
/// first lines are still being read, and share a short one (a slicer's 150 KB program is
/// four pieces, not two).
inline constexpr size_t kFirstPieceBytes = size_t(1) << 14;
/// The input bytes piece `index` (0 for the first) gathers before it may end.
inline constexpr size_t piece_bytes(size_t index) {
  size_t bytes = kFirstPieceBytes;
  for (size_t i = 0; i < index && bytes < kPieceBytes; ++i) bytes *= 2;
  return std::min(bytes, kPieceBytes);
}
/// Input bytes after which a piece may also end before a move that starts at a corner.
inline constexpr size_t kCornerPieceBytes = size_t(3) << 16;
/// Input bytes after which a piece ends at the next vertex whatever it is (a forced cut):
/// before the next move a fit may rewrite, or after the next line where the last move is
/// not one (after twice as many bytes, after any line).
inline constexpr size_t kMaxPieceBytes = size_t(1) << 18;
/// Pieces per worker thread that may be read, queued, worked on or waiting for their turn.
inline constexpr size_t kPiecesInFlight = 2;

/// Makes room in a piece's program and interpretation for what kPieceBytes typically hold,
/// so that reading it does not grow them step by step.
void reserve_piece(Program& program, Interpretation& in);

class Compressor {
 public:
  /// Compresses the program called `name` with `opt`, of which it keeps its own copy
  /// (checked by check_options(): throws Error(kExitInput) for an option out of range, more
  /// than kMaxThreads threads, or the executed band on a dialect with no arc segmentation).
  /// Diagnostics go to `sink`, which must outlive the compressor; it is only written on the
  /// calls' thread.
  Compressor(std::string name, const CompressOptions& opt, DiagnosticSink& sink);
  ~Compressor();
  Compressor(const Compressor&) = delete;
  Compressor& operator=(const Compressor&) = delete;

  /// Takes the next bytes of the program, cut anywhere (in a line, in a CRLF). May wait for
  /// the workers while the pieces in flight are as many as allowed. Throws std::logic_error
  /// after finish(). A call of push(), take() or finish() that throws (a thread that cannot
  /// start, memory) leaves the compressor broken: every later call throws the same.
  void push(std::string_view bytes);
  /// Reads the jumps of the program (`GOTO 100`, `M99 P100`: JumpTargets) from its text
  /// ahead of push(), whole lines from line `first_line` on, so that a jump back to a block
  /// is known before the block is (a program pushed as it comes, from a pipe, fails where a
  /// jump back names a block already read as none's target: E-FLOW-JUMP-BACK). Once called,
  /// push() reads no more jumps: the text given here is taken to be the whole program's. The
  /// text after the program's first end is kept for the subprograms written there
  /// (read_called_programs()), whose modes hold after their calls.
  void read_jumps(std::string_view lines, uint32_t first_line);
  /// Whether read_jumps() found a jump, a call of a numbered block, or a loop of blocks
  /// (`WHILE [..] DO1`, `o1 do`, RepRapFirmware's `while`).
  bool has_jumps() const;
  /// After read_jumps() of the whole program: reads `program`, all of it, once ahead as
  /// push() will, for the loops (by a jump back, or of blocks) whose end would run their first
  /// moves in other modes than they were read in. push() then reads those loops' starts with
  /// the plane, units, motion (and for loops of blocks G90 or G91) not known, and writes the moves after them as they are until the program states
  /// those (a warning, W-FLOW-LOOP-MODES), where it would otherwise fail the program
  /// (E-FLOW-LOOP-MODES). Nothing where has_jumps() is false, or for a program over
  /// kLoopsAheadBytes (read twice more, it would hold that much memory at once).
  void read_loops(std::string_view program);
  static constexpr size_t kLoopsAheadBytes = size_t(64) << 20;
  /// Appends the output finished so far, in order, to `out` and returns how many bytes that
  /// was. Output is final once taken: it is never revised.
  size_t take(std::string& out);
  /// Ends the input and waits for every piece; take() then gives the rest of the output.
  /// Calling it again does nothing. A compressor destroyed before it stops its workers and
  /// drops what they had not finished.
  void finish();

  /// The counts and checks of the pieces taken so far (all of them after finish()). `ok` is
  /// false once the input has an error (strict mode): nothing after it is written, and what
  /// was taken before must be thrown away, as must everything when !within_band().
  const CompressResult& result() const;
  /// Bytes pushed so far, for progress.
  size_t bytes_read() const;
  /// Pieces cut at a vertex because a path went on for kMaxPieceBytes without a move that
  /// ends it (see the header's comment), so far.
  size_t forced_cuts() const;
  /// Pieces the program was cut into so far.
  size_t pieces() const;

 private:
  template <class F>
  auto guarded(F&& f) -> decltype(f());

  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::exception_ptr broken_;  ///< the failure every call after it throws again
};

}  // namespace arcpress
