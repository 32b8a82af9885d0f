// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A piece of a program, compressed and checked on its own: the unit of the streaming engine
// (see compressor.hpp). A piece is a stretch of whole lines read from a known modal state
// (ModalState) into a known state; it is cut where no chain of runs goes on (after a move
// no fit may join, such as a rapid or a retraction), so that its fit is the fit the whole
// program would get there, or, where a path goes on for longer than a piece may hold, at a
// vertex (a forced cut). Everything the fit, the emitter and the check need is in the piece:
// pieces are worked on in any order, on any thread.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "arcpress/api/arcpress.hpp"
#include "arcpress/model/interpreter.hpp"

namespace arcpress {

/// The share of the band below which the self-check's whole-path measure need not be exact:
/// its maximum is exact above it, and where the paths are nowhere that far apart it reports
/// at most that (DiffOptions::least_mm).
inline constexpr double kExactShare = 0.05;

/// One end of a piece's path, kept to measure the joint with the next piece across the cut
/// (a piece's own check sees only the joints inside it).
struct PieceEnd {
  bool feed = false;        ///< the output's move at the cut is a placed feed move
  bool fitted = false;      ///< ... a fit's, not the input's own move
  Plane plane = Plane::XY;  ///< its plane; the points below are in it
  Vec2 tangent{0, 0};       ///< its direction at the cut
  Vec3 at{0, 0, 0};         ///< the cut's vertex
  std::optional<Vec3> beside;  ///< the input's vertex next to the cut on this side (past moves that go nowhere)
  std::optional<Vec3> beside2; ///< ... and the one after it, further from the cut
  uint32_t input_line = 0;  ///< the input line of the move at the cut
};

/// Whether the path is smooth at the cut between a piece ending in `tail` and the next
/// starting with `head`, where a fit made the joint: its turn there, degrees (none
/// otherwise), as compare_paths() judges the joints inside a piece.
std::optional<double> joint_turn_deg(const PieceEnd& tail, const PieceEnd& head, double band_mm,
                                     double corner_angle_deg);

struct Piece {
  size_t index = 0;        ///< 0, 1, 2 ... in program order
  Program program;         ///< its lines, numbered as in the whole program
  Interpretation in;       ///< read from `start` (in.start is the position there)
  ModalState start, end;   ///< the input's state before its first line and after its last
  EmitStart emit;          ///< how the output stands before it
  /// The piece ends after a block written back as it is (a move no fit joins, or the end of
  /// the program): the output's modal motion there is the input's. After a forced cut it may
  /// not be, and the next piece states its motion word where it needs one.
  bool clean_end = true;
  bool last = false;       ///< the program's last piece
  /// Threads that may work on this piece at once (fitting its chains, measuring its paths):
  /// 1 where pieces are shared among threads; more for a piece worked on alone. The output
  /// is the same for any number.
  unsigned threads = 1;

  // What compress_piece() makes of it.
  CompressResult result;   ///< its text, counts and checks; output lines (line_b) counted from the piece's first
  PieceEnd head, tail;     ///< the ends of its path as checked (where it was)
  size_t output_lines = 0; ///< lines in result.output
  /// With CompressOptions::block_rate: the timed blocks of the input and the output, in
  /// order, and the feed moves of each that could not be timed.
  std::vector<TimedBlock> timed_in, timed_out;
  size_t untimed_in = 0, untimed_out = 0;
};

/// Fits, emits and (with opt.verify) checks the piece: the output is read back from
/// `start` and must end in a state that reads the rest of the program as `end` does. Runs
/// the check refuses are written as their input moves, as compress() documents. Never
/// reports to a sink: the piece is worked on off the reader's thread.
void compress_piece(Piece& piece, const CompressOptions& opt);

/// verify_output() for a piece: the output is read back from `start`, and where `end` is
/// given it must end in a state that reads on as `end` does (with the modal motion where
/// `with_motion`). With `timed_out`, the output's timed blocks (block_rate.hpp) as read back
/// go there, and how many feed moves could not be timed to `untimed_out`.
void verify_piece_output(const Program& input, const Interpretation& in, const CompressOptions& opt, CompressResult& r,
                         std::span<const Run> runs, const ModalState& start, const ModalState* end, bool with_motion,
                         PieceEnd* head = nullptr, PieceEnd* tail = nullptr,
                         std::vector<TimedBlock>* timed_out = nullptr, size_t* untimed_out = nullptr);

/// Adds the counts and checks of `piece` (the next in order, whose output begins after
/// `lines_before` lines of output) to `total`.
void add_piece(CompressResult& total, const Piece& piece, size_t lines_before);

}  // namespace arcpress
