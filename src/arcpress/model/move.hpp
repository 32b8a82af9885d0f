// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The interpreter's output: the machine state ("frame") under which words are read, and
// one Move per block that changes position.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "arcpress/core/geometry.hpp"

namespace arcpress {

/// Axis slots, in this order everywhere: X Y Z A B C U V W E.
enum Axis : int { kX, kY, kZ, kA, kB, kC, kU, kV, kW, kE, kAxisCount };
inline constexpr char kAxisLetters[kAxisCount] = {'X', 'Y', 'Z', 'A', 'B', 'C', 'U', 'V', 'W', 'E'};
/// The axis slot of a word's (upper-case) letter, or -1.
inline constexpr int axis_of_letter(char c) {
  switch (c) {
    case 'X': return kX;
    case 'Y': return kY;
    case 'Z': return kZ;
    case 'A': return kA;
    case 'B': return kB;
    case 'C': return kC;
    case 'U': return kU;
    case 'V': return kV;
    case 'W': return kW;
    case 'E': return kE;
    default: return -1;
  }
}
/// Linear axes scale with G20/G21; rotary A/B/C are degrees in both.
inline constexpr bool kAxisIsLinear[kAxisCount] = {true, true, true, false, false, false, true, true, true, true};
using AxisValues = std::array<double, kAxisCount>;

/// Position `v`'s X, Y and Z.
inline Vec3 xyz(const AxisValues& v) { return {v[kX], v[kY], v[kZ]}; }

/// Position `v`'s X, Y, Z in the coordinates of plane `p` (first, second, normal).
inline Vec3 in_plane(const AxisValues& v, Plane p) {
  const auto a = axes_of(p);
  return {v[a.first], v[a.second], v[a.normal]};
}

/// How program words turn into absolute positions. A new Frame starts whenever any of these
/// modal settings changes, so every Move can be written back in its own frame.
struct Frame {
  double unit_mm = 1.0;      ///< 1 for G21 (mm), 25.4 for G20 (inch)
  AxisValues offset{};       ///< G92 offset: absolute = programmed * unit + offset (mm or deg)
  bool absolute = true;      ///< G90 (true) / G91 (false) for X..W
  bool arc_absolute = false; ///< G90.1 (true) / G91.1 (false, default) for I/J/K
  bool e_relative = false;   ///< E words are relative: M83, or G91 where the dialect reads E so
  bool m83 = false;          ///< E's own mode: M83 (true) / M82 (false), and G91/G90 where they set it
  bool diameter_mode = false;///< lathe G7: X words are diameters
  bool inverse_time = false; ///< G93: F is 1/minutes per block
  int work_offset = 54;      ///< G54..G59 as 540..593 / 10; tracked, values unknown
  bool polar = false;        ///< G16 (G15 off): the plane's two words are a radius and an angle, not computed

  double to_mm(int axis, double programmed) const {
    return programmed * (kAxisIsLinear[axis] ? unit_mm : 1.0) + offset[axis];
  }
  double to_program(int axis, double mm) const {
    return (mm - offset[axis]) / (kAxisIsLinear[axis] ? unit_mm : 1.0);
  }
  bool same_as(const Frame& o) const {
    return unit_mm == o.unit_mm && offset == o.offset && absolute == o.absolute &&
           arc_absolute == o.arc_absolute && e_relative == o.e_relative && m83 == o.m83 &&
           diameter_mode == o.diameter_mode && inverse_time == o.inverse_time &&
           work_offset == o.work_offset && polar == o.polar;
  }
};

enum class MoveKind : uint8_t {
  Rapid,   ///< G0
  Line,    ///< G1
  ArcCW,   ///< G2
  ArcCCW,  ///< G3
  Other,   ///< canned cycle, spline, probe, homing: a position change we do not model as a path
};

/// G2 or G3.
inline bool is_arc(MoveKind k) { return k == MoveKind::ArcCW || k == MoveKind::ArcCCW; }
/// A move along the programmed path at feed: G1, G2 or G3.
inline bool is_feed(MoveKind k) { return k == MoveKind::Line || is_arc(k); }

/// Why a move is not one a fitter may rewrite (Unfit::None: it is). Placement first: a move
/// whose path is not known is never compared or fitted; then what keeps a placed G1 block
/// as it is.
enum class Unfit : uint8_t {
  None,
  // The move could not be placed: it moves an axis whose position is not known.
  UnknownAtStart,       ///< the axis has not been set since the program began
  UnknownAfterHoming,   ///< G28/G30 sent it to a stored position, or G29 probed the bed
  UnknownAfterMachine,  ///< G53 moved it in machine coordinates
  UnknownAfterCycle,    ///< a canned, lathe or probing cycle, a spline or G10 left it anywhere
  UnknownAfterExpression,  ///< an expression set it
  UnknownAfterControl,  ///< flow control, a subprogram, a macro or host command ran
  UnknownAfterOffset,   ///< a work offset (G54..) or the tool length offset (G43, G49) changed under it
  UnknownInPolar,          ///< polar coordinates (G16): the plane's words are a radius and an angle
  UnknownAfterToolChange,  ///< a tool change (M6, a tool call): the controller may move the tool, and goes on from where it is
  UnknownAfterCodeMove,    ///< a code the dialect says may move the tool where the program does not say (Heidenhain's M140)
  UnknownAtEntry,          ///< a block a jump or a call may enter (JumpTargets; after M99; an O number after a program end; BlockNesting)
  UnknownDistanceMode,     ///< moved where G90 or G91 was not known (after an entry, until the program states it)
  UnknownAfterUnmodelled,  ///< a G-code arcpress does not model
  // The block cannot be read as a path: no controller runs it as written.
  UnreadableArc,    ///< G2/G3 without a centre (no I/J/K in its plane, no R), or R shorter than half its chord
  RepeatedWord,     ///< an axis, centre, R, F or P word twice in one block
  // Placed, and kept as it is.
  NotLine,          ///< G0, G2/G3 or another motion: only G1 is fitted
  OtherWords,       ///< the block carries words besides G1, axes, F, S and N (modal codes, M, T, ...)
  Comment,          ///< a comment inside the block (kept with its move)
  Expression,       ///< an expression word
  BlockDelete,      ///< '/' block delete: the controller may skip it
  Checksum,         ///< a checksum or line number the host checks
  InverseTime,      ///< G93 inverse-time feed: F belongs to the block
  DiameterMode,     ///< lathe G7: X words are diameters
  FeedUnknown,      ///< no F in force yet
  ExtrusionModeUnknown,  ///< an E word where M82 or M83 is not known (after the ways in that may leave either, until stated)
  NoPathAxis,       ///< it moves only E or the extra axes (a retraction, a rotary index)
  FarFromOrigin,    ///< so far from the origin that the check could not measure a fit of it (farthest_measurable_mm())
  CycleCall,        ///< it calls a cycle at its end (the dialect's modal cycle call, Heidenhain's M89)
  BeforeUnmodelled, ///< a block after it that arcpress does not read (a code it does not model, a line it does not
                    ///< understand) may go on from it (a chamfer, a rounding, a tangential arc)
};

/// A few words on `why`, for reports: "comment in the block", ...
const char* describe(Unfit why);
/// True for the reasons that say the move's position was not known (an axis it moves).
inline bool is_position_unknown(Unfit why) { return why >= Unfit::UnknownAtStart && why <= Unfit::UnknownAfterUnmodelled; }

struct Move {
  AxisValues to{};            ///< absolute end position (mm for linear axes, degrees for A/B/C)
  Vec3 center{0, 0, 0};       ///< arcs: absolute centre, mm (in-plane components meaningful)
  double feed_mm_min = 0;     ///< F in force (mm/min; inverse-time value when the frame says so)
  /// S in force during the move (spindle speed, or laser power where S on a feed block sets
  /// it): a fitted primitive never spans a change of it.
  double spindle = 0;
  uint32_t block = 0;         ///< index of the block that made this move
  uint32_t frame = 0;         ///< index into Interpretation::frames
  int16_t turns = 1;          ///< arcs: P word (full turns + 1), 1 when absent
  /// Bit per axis (1 << Axis): the axes whose position is not known during this move. They
  /// do not move in a placed move; they keep a stand-in value and are never printed.
  uint16_t unknown_axes = 0;
  MoveKind kind = MoveKind::Line;
  Plane plane = Plane::XY;
  bool known = true;          ///< the path is known: no axis of unknown position moves, and the block reads as one
  /// Every axis it moves ends at a known position, so its end point is known even where
  /// its start is not (the move into the first known position after homing).
  bool end_known = true;
  /// It starts where an entry left the position standing in for one not known, from which
  /// its axes float (ModalState::floating): the move before it in the text is no neighbour.
  bool entered = false;
  Unfit unfit = Unfit::NotLine;  ///< Unfit::None: a plain G1 feed block a fitter may rewrite

  bool fittable() const { return unfit == Unfit::None; }
  /// Whether a chain of runs goes on through it (extract/run.hpp, chain_runs()): a move a fit
  /// may rewrite, or one kept as it is whose path is known and which the fit beside it joins
  /// tangentially: an input arc, or the last move before a block arcpress does not read.
  bool in_chain() const { return fittable() || (known && (is_arc(kind) || unfit == Unfit::BeforeUnmodelled)); }
  Vec3 xyz() const { return {to[kX], to[kY], to[kZ]}; }
};

/// Whether two values of one axis are the same place, but for the floating noise of summing
/// relative words (G91, or M83 for E) in other groups: an E counter summed over arcs rather
/// than over the moves they replace (0.1 + 0.3 + 0.1 against five times 0.1). A sum of n
/// doubles drifts by at most n units in the last place of its largest partial sum, 10⁻¹⁰ of
/// it for a million words; the share allowed is ten times that, and the smallest digit a
/// program prints moves a value by more (10⁻⁵ at 1 000 mm).
inline bool same_place(double a, double b) {
  constexpr double kSumNoiseShare = 1e-9;
  return std::abs(a - b) <= kSumNoiseShare * std::max({1.0, std::abs(a), std::abs(b)});
}

/// same_place() on every axis.
inline bool same_places(const AxisValues& a, const AxisValues& b) {
  for (size_t ax = 0; ax < a.size(); ++ax)
    if (!same_place(a[ax], b[ax])) return false;
  return true;
}

/// A feed move (G1/G2/G3) that could not be placed, and what made its axis unknown.
struct UnplacedMove {
  uint32_t move = 0;        ///< index into Interpretation::moves
  uint32_t cause_line = 0;  ///< the line that made the axis unknown; 0: never set
};

/// A feed move from an unknown position into a known one (the first move after homing):
/// its path is not known, its end point is, and it is compared by that.
inline bool enters_from_unknown(const Move& m) {
  return is_feed(m.kind) && !m.known && m.end_known && is_position_unknown(m.unfit);
}

/// A block that turns about the centre the dialect's I/J/K left in force (Dialect::centre_modal;
/// Heidenhain's pole): an arc without centre words, a polar move. Its words are the ones that
/// state that centre again, as the program would write them there.
struct PoleRead {
  uint32_t block = 0;
  Plane plane = Plane::XY;
  bool known = false;                ///< the program set the centre's axes in this plane
  bool arc = false;                  ///< an arc without centre words (else a polar move)
  std::array<double, 3> words{};     ///< I, J, K: the centre in program units, absolute, or from the present point under G91
};

/// A block with a code that turns the way the last programmed arc turned (Dialect::last_turn):
/// the way the program set last, 2 (clockwise, G02) or 3 (counter-clockwise, G03), 0 where
/// it set none.
struct TurnRead {
  uint32_t block = 0;
  uint8_t turn = 0;
};

/// Everything the interpreter learned about a program.
struct Interpretation {
  std::vector<Frame> frames;
  std::vector<Move> moves;
  /// Per block: index of its move in `moves`, or -1 for blocks that do not move.
  std::vector<int32_t> move_of_block;
  /// Absolute position before the first move (unknown axes are 0).
  AxisValues start{};
  bool start_known = false;
  /// Every feed move that could not be placed, in order (move.unfit says why): those whose
  /// end is known (Move::end_known) and those whose end is not either.
  std::vector<UnplacedMove> unplaced;
  /// The blocks that read the centre I/J/K left in force, in order (Dialect::centre_modal).
  std::vector<PoleRead> pole_reads;
  /// The blocks that turn as the last programmed arc did, in order (Dialect::last_turn).
  std::vector<TurnRead> turn_reads;
  /// Moves [0, arcless_moves) are fitted with lines only: a block after them turns as the
  /// last programmed arc did where the program has programmed none, so an arc of arcpress's
  /// before it would decide its way.
  uint32_t arcless_moves = 0;

  /// A copy of everything but the moves (for a path made anew from this one's). Names
  /// every field: one added above belongs here too.
  Interpretation without_moves() const {
    Interpretation o;
    o.frames = frames;
    o.move_of_block = move_of_block;
    o.start = start;
    o.start_known = start_known;
    o.unplaced = unplaced;
    o.pole_reads = pole_reads;
    o.turn_reads = turn_reads;
    o.arcless_moves = arcless_moves;
    return o;
  }

  /// Start of move `i` (end of the previous move, or `start`).
  const AxisValues& from(size_t i) const { return i == 0 ? start : moves[i - 1].to; }
  /// Whether move `i` is a G1 that goes nowhere (every axis as before). A fit steps over
  /// such moves; a joint is named by the first move after it that goes somewhere.
  bool goes_nowhere(size_t i) const { return moves[i].kind == MoveKind::Line && moves[i].to == from(i); }
  /// How many of the moves [i, t) go somewhere.
  size_t moves_going(size_t i, size_t t) const {
    size_t n = 0;
    for (size_t k = i; k < t; ++k) n += !goes_nowhere(k);
    return n;
  }
  /// The move that names the joint at the start of move `i`: the first from `i` on that does
  /// not go nowhere (or the last move).
  size_t joint_move(size_t i) const {
    while (i + 1 < moves.size() && goes_nowhere(i)) ++i;
    return i;
  }
  /// The vertex nearest to vertex v (the start of move v) along the feed path that is not
  /// v itself, before it (step -1) or after it (step +1): past moves that go nowhere, as
  /// fits and the corner rule step past them. None where the feed path ends first.
  std::optional<size_t> vertex_beside(size_t v, int step) const {
    for (size_t u = v;;) {
      if (step < 0 ? u == 0 : u >= moves.size()) return std::nullopt;
      const size_t move = step < 0 ? u - 1 : u;  // the move between u and the next vertex out
      if (!is_feed(moves[move].kind)) return std::nullopt;
      u = step < 0 ? u - 1 : u + 1;
      if (!goes_nowhere(move)) return u;
    }
  }
};

}  // namespace arcpress
