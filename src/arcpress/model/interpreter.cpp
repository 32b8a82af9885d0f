#include "arcpress/model/interpreter.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace arcpress {
namespace {

int axis_of_letter(char c) {
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

/// G-code number times ten, so G90.1 is 901 and G1 is 10.
int gcode10(double v) { return int(std::lround(v * 10.0)); }

constexpr uint32_t kAllAxes = (1u << kAxisCount) - 1;
constexpr uint32_t kXyzMask = (1u << kX) | (1u << kY) | (1u << kZ);
/// The S in force after an S word that is an expression: constant until the next S word.
constexpr double kSpindleUnknown = -1;

class Interpreter {
 public:
  Interpreter(const Program& p, const Dialect& d, DiagnosticSink& sink) : p_(p), d_(d), sink_(sink) {
    frame_.diameter_mode = d.diameter_x;
    out_.frames.push_back(frame_);
    out_.move_of_block.assign(p.blocks.size(), -1);
    out_.moves.reserve(p.blocks.size());
  }

  Interpretation run() {
    for (size_t bi = 0; bi < p_.blocks.size(); ++bi) block(uint32_t(bi), p_.blocks[bi]);
    return std::move(out_);
  }

 private:
  void block(uint32_t bi, const Block& b) {
    switch (b.kind) {
      case BlockKind::Empty:
      case BlockKind::Percent:
        return;
      case BlockKind::Code:
        break;
      case BlockKind::HostCommand:
        // Firmware M-codes with a text argument (a message, an object label, a printer check,
        // a file name) move nothing; M32 starts another program, and other host commands
        // (`$H` homing, `$J=` jogging, firmware macros) may move anything.
        if (b.word_count > 0 && p_.words_begin(b)->letter == 'M' && !p_.words_begin(b)->is_expr &&
            std::lround(p_.words_begin(b)->value) != 32)
          return;
        forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterControl, bi);
        return;
      default:
        // Flow control, macros and unread lines may move anything.
        forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterControl, bi);
        return;
    }
    bool other_words = false;   // words a fitted block could not carry along
    int motion = -1;            // G-code ×10 of a motion word in this block
    bool g92 = false, g92_reset = false, g53 = false, axis_consumer = false, homing = false;
    bool words_seen[kAxisCount] = {};
    bool expr_axis[kAxisCount] = {};
    bool flag_axis[kAxisCount] = {};
    double value[kAxisCount] = {};
    double ijk[3] = {0, 0, 0};
    bool ijk_seen[3] = {};
    bool r_seen = false;
    double r_value = 0;
    int turns = 1;
    // Most blocks change no modal setting: copy the frame only when one is touched.
    std::optional<Frame> fedit;
    auto F = [&]() -> Frame& {
      if (!fedit) fedit = frame_;
      return *fedit;
    };
    double feed = 0;
    bool feed_set = false;

    bool repeated = false;  // a word the controller refuses to see twice
    uint32_t letters_seen = 0;
    for (auto* w = p_.words_begin(b); w != p_.words_end(b); ++w) {
      char L = w->letter;
      if (std::string_view("XYZABCUVWEIJKRFP").find(L) != std::string_view::npos && !w->flag) {
        const uint32_t bit = 1u << (L - 'A');
        if (letters_seen & bit) {
          repeated = true;
          sink_.problem({b.line, w->col}, "E-MODEL-REPEATED-WORD",
                        fmt::format("{} appears twice in the block ('{}'); controllers refuse it", L, p_.raw(b, *w)));
        }
        letters_seen |= bit;
      }
      if (int ax = axis_of_letter(L); ax >= 0) {
        if (w->flag) {
          flag_axis[ax] = true;
          continue;
        }
        words_seen[ax] = true;
        expr_axis[ax] = w->is_expr;
        value[ax] = ax == kE ? w->value : number(*w);
        continue;
      }
      if (w->is_expr) {
        if (L == 'G' || L == 'M') other_words = true, forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterExpression, bi);
        if (L == 'F') feed_known_ = false;
        if (L == 'S') spindle_ = kSpindleUnknown;
        continue;
      }
      switch (L) {
        case 'G': {
          int g = gcode10(w->value);
          if (g != 10) other_words = true;
          switch (g) {
            case 0: case 10: case 20: case 30: motion = g; break;
            case 50: case 51: case 52: case 53: motion = g; break;  // G5, G5.1, G5.2, G5.3
            case 330: case 331: case 382: case 383: case 384: case 385: case 760:
            case 730: case 810: case 820: case 830: case 840: case 850: case 860: case 870: case 880: case 890:
              motion = g;
              break;
            case 800: motion = 800; break;
            case 40: break;  // dwell
            case 170: f_plane_ = Plane::XY; break;
            case 180: f_plane_ = Plane::ZX; break;
            case 190: f_plane_ = Plane::YZ; break;
            case 200: F().unit_mm = 25.4; break;
            case 210: F().unit_mm = 1.0; break;
            case 70: F().diameter_mode = true; break;
            case 80: F().diameter_mode = false; break;
            case 900: F().absolute = true; F().e_relative = false; break;
            case 910: F().absolute = false; F().e_relative = true; break;
            case 901: F().arc_absolute = true; break;
            case 911: F().arc_absolute = false; break;
            case 920: g92 = true; axis_consumer = true; break;
            case 921: case 922: g92_reset = true; break;
            case 923: break;
            case 930: F().inverse_time = true; break;
            case 940: case 950: F().inverse_time = false; break;
            case 280: case 300: homing = true; axis_consumer = true; break;
            case 281: case 301: break;
            case 700: case 710: case 720: case 740: case 750:  // lathe turning cycles: run elsewhere
            case 100:                                           // G10: offsets and tables
              axis_consumer = true;
              forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterCycle, bi);
              break;
            case 530: g53 = true; break;
            case 540: case 550: case 560: case 570: case 580: case 590: case 591: case 592: case 593:
              if (frame_.work_offset != g)  // same machine point, new coordinates
                forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterOffset, bi);
              F().work_offset = g;
              break;
            case 400: case 410: case 411: case 420: case 421:  // cutter compensation
            case 430: case 431: case 432: case 490:             // tool length
            case 610: case 611: case 640:                       // path control
            case 980: case 990: case 150: case 160:             // canned-cycle return, polar
            case 290:                                           // Marlin bed levelling
            case 310: case 320:
            case 500: case 960: case 970:                       // lathe spindle limits, CSS
              break;
            default:
              sink_.problem({b.line, w->col}, "E-MODEL-GCODE",
                            fmt::format("{} is not modelled; the block is kept and not fitted",
                                        p_.raw(b, *w)));
              forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterUnmodelled, bi);
              break;
          }
          break;
        }
        case 'M': {
          other_words = true;
          int m = int(std::lround(w->value));
          if (m == 82) F().e_relative = false;
          if (m == 83) F().e_relative = true;
          if (m == 98 || m == 99)  // subprogram call / return
            forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterControl, bi);
          break;
        }
        case 'F':
          feed = w->value;
          feed_set = true;
          break;
        case 'I': case 'J': case 'K': {
          int k = L - 'I';
          ijk[k] = number(*w);
          ijk_seen[k] = true;
          other_words = true;
          break;
        }
        case 'R':
          r_seen = true;
          r_value = number(*w);
          other_words = true;
          break;
        case 'P':
          turns = int(std::clamp<double>(std::round(w->value), -32768, 32767));
          other_words = true;
          break;
        case 'S':  // spindle speed, or laser power on a feed move: a fitted block carries it
          spindle_ = w->value;
          break;
        case 'N':
          break;
        default:
          other_words = true;
          break;
      }
    }
    const Frame& fnow = fedit ? *fedit : frame_;
    if (feed_set) {
      feed_mm_ = fnow.inverse_time ? feed : feed * fnow.unit_mm;
      feed_known_ = true;
    }

    // G92 and G92.1 change the offsets; positions in mm stay where they are.
    if (g92_reset) F().offset = AxisValues{};
    if (g92) {
      Frame& f = F();
      for (int ax = 0; ax < kAxisCount; ++ax) {
        if (!words_seen[ax]) continue;
        if (expr_axis[ax]) {
          forget(1u << ax, Unfit::UnknownAfterExpression, bi);
          continue;
        }
        double scale = kAxisIsLinear[ax] ? f.unit_mm : 1.0;
        f.offset[ax] = pos_[ax] - value[ax] * scale;
      }
    }
    if (fedit) set_frame(*fedit);
    if (motion >= 0) motion_ = motion;

    bool any_axis = false;
    for (int ax = 0; ax < kAxisCount; ++ax) any_axis |= words_seen[ax];
    if (homing) {
      // G28/G30: through an optional point to a stored position we do not know.
      bool any_flag = false;
      for (int ax = 0; ax < kAxisCount; ++ax) any_flag |= flag_axis[ax];
      for (int ax = 0; ax < kE; ++ax)
        if (words_seen[ax] || flag_axis[ax] || (!any_axis && !any_flag)) {
          forget(1u << ax, Unfit::UnknownAfterHoming, bi);
          // One stand-in for the home position, whatever came before, so that two programs
          // that home alike hold the same stand-in for an axis they do not set again.
          pos_[ax] = 0;
        }
      Move& m = add_move(bi, MoveKind::Other, pos_, false, 1);
      m.unknown_axes = uint16_t(kAllAxes & ~known_);
      m.end_known = false;
      return;
    }
    if (!any_axis || axis_consumer) {
      // Arc words without axes (a full circle in I/J form) still move along a path.
      if (!(motion_ == 20 || motion_ == 30) || !(ijk_seen[0] || ijk_seen[1] || ijk_seen[2]) || axis_consumer)
        return;
    }

    const Frame& fr = frame_;
    AxisValues target = pos_;
    uint32_t known_after = known_;
    uint32_t written = 0;  // axes this block writes
    Unfit after_why[kAxisCount];
    for (int ax = 0; ax < kAxisCount; ++ax) after_why[ax] = why_[ax].reason;
    bool reasons_changed = false;  // this block makes an axis unknown for a reason of its own
    for (int ax = 0; ax < kAxisCount; ++ax) {
      if (!words_seen[ax]) continue;
      written |= 1u << ax;
      if (expr_axis[ax]) {
        known_after &= ~(1u << ax);
        after_why[ax] = Unfit::UnknownAfterExpression, reasons_changed = true;
        continue;
      }
      double v = value[ax];
      if (ax == kX && fr.diameter_mode) v *= 0.5;
      double scale = kAxisIsLinear[ax] ? fr.unit_mm : 1.0;
      bool relative = ax == kE ? fr.e_relative : !fr.absolute;
      if (g53) {
        known_after &= ~(1u << ax);  // machine coordinates: not in our frame
        after_why[ax] = Unfit::UnknownAfterMachine, reasons_changed = true;
        target[ax] = v * scale;
      } else if (relative) {
        target[ax] = pos_[ax] + v * scale;
      } else {
        target[ax] = fr.to_mm(ax, v);
        known_after |= (1u << ax);
      }
    }

    MoveKind kind = MoveKind::Other;
    if (!g53) {
      // A dialect whose G18 arcs turn the other way is read back into RS274's sense here.
      bool flip = d_.zx_reversed && f_plane_ == Plane::ZX;
      if (motion_ == 0) kind = MoveKind::Rapid;
      else if (motion_ == 10) kind = MoveKind::Line;
      else if (motion_ == 20) kind = flip ? MoveKind::ArcCCW : MoveKind::ArcCW;
      else if (motion_ == 30) kind = flip ? MoveKind::ArcCW : MoveKind::ArcCCW;
    }
    // The axes the move moves: those it writes, and an arc's two plane axes, which it
    // moves around the centre whether it writes them or not. An axis it does not move
    // stays where it is, known or not (a 2-D program never sets Z; a lathe never sets Y),
    // so the move is placed where every axis it moves is known at both ends.
    uint32_t moved = written;
    if (is_arc(kind)) moved |= (1u << axes_of(f_plane_).first) | (1u << axes_of(f_plane_).second);
    const uint32_t unknown_moved = moved & ~(known_ & known_after);
    bool known = unknown_moved == 0;
    Unfit unplaced_why = Unfit::None;
    for (int ax = 0; ax < kAxisCount && !known; ++ax)
      if ((unknown_moved >> ax) & 1u) {
        // The axis unknown at the start says why; one this block makes unknown, this block.
        const bool at_start = !((known_ >> ax) & 1u);
        unplaced_why = at_start ? why_[ax].reason : after_why[ax];
        cause_block_ = at_start ? why_[ax].block : int64_t(bi);
        break;
      }
    if (kind == MoveKind::Other && motion_ != 0) {  // cycles end where they like
      for (int ax : {kX, kY, kZ})
        if ((known_after >> ax) & 1u) after_why[ax] = Unfit::UnknownAfterCycle, reasons_changed = true;
      known_after &= ~kXyzMask;
    }
    Move& m = add_move(bi, kind, target, known, turns);
    m.unknown_axes = uint16_t(kAllAxes & ~(known_ & known_after));
    m.end_known = known || (moved & ~known_after) == 0;
    if (repeated && m.known) {
      m.known = false;
      unplaced_why = Unfit::RepeatedWord;
      cause_block_ = bi;
    }
    if (kind == MoveKind::ArcCW || kind == MoveKind::ArcCCW) {
      bool readable = true;
      m.center = arc_center(b, fr, target, ijk, ijk_seen, r_seen, r_value, kind, readable);
      if (!readable && m.known) {
        m.known = false;
        unplaced_why = Unfit::UnreadableArc;
        cause_block_ = bi;
      }
    }
    // A move along X, Y or Z, or one that goes nowhere at all (which the fitter steps over);
    // not one that moves only E or the extra axes (a retraction, a rotary index).
    bool moved_xyz = target[kX] != pos_[kX] || target[kY] != pos_[kY] || target[kZ] != pos_[kZ];
    m.unfit = !m.known                        ? (unplaced_why == Unfit::None ? Unfit::UnknownAfterUnmodelled : unplaced_why)
              : kind != MoveKind::Line        ? Unfit::NotLine
              : b.has_expr                    ? Unfit::Expression
              : b.has_comment                 ? Unfit::Comment
              : b.block_delete                ? Unfit::BlockDelete
              : b.has_checksum                ? Unfit::Checksum
              : other_words                   ? Unfit::OtherWords
              : fr.inverse_time               ? Unfit::InverseTime
              : fr.diameter_mode              ? Unfit::DiameterMode
              : !feed_known_                  ? Unfit::FeedUnknown
              : !(moved_xyz || target == pos_) ? Unfit::NoPathAxis
                                              : Unfit::None;
    if (!m.known && is_feed(kind)) out_.unplaced.push_back({uint32_t(out_.moves.size() - 1), cause_block_});
    pos_ = target;
    const bool known_changed = known_after != known_;
    known_ = known_after;
    for (int ax = 0; ax < kAxisCount && (known_changed || reasons_changed); ++ax) {
      if ((known_ >> ax) & 1u) why_[ax] = {Unfit::None, -1};
      else if (after_why[ax] != why_[ax].reason) why_[ax] = {after_why[ax], int64_t(bi)};
    }
  }

  /// Axes in `mask` become unknown, `why`, from block `bi` on (the latest reason is kept).
  void forget(uint32_t mask, Unfit why, uint32_t bi) {
    for (int ax = 0; ax < kAxisCount; ++ax)
      if ((mask >> ax) & 1u) why_[ax] = {why, int64_t(bi)};
    known_ &= ~mask;
  }

  Vec3 arc_center(const Block& b, const Frame& fr, const AxisValues& target, const double* ijk,
                  const bool* ijk_seen, bool r_seen, double r_value, MoveKind kind, bool& known) {
    auto a = axes_of(f_plane_);
    // I/J/K belong to X/Y/Z respectively.
    Vec3 c(pos_[kX], pos_[kY], pos_[kZ]);
    if (r_seen) {
      Vec2 s(pos_[a.first], pos_[a.second]), e(target[a.first], target[a.second]);
      double r = r_value * fr.unit_mm;
      Vec2 chord = e - s;
      double d = chord.norm();
      if (d < kLengthEpsMm) {
        sink_.warning({b.line, 1}, "W-MODEL-ARC-R", "R-form arc with coincident end points has no defined centre");
        known = false;
        return c;
      }
      // A radius shorter than half the chord reaches no circle through both ends; controllers
      // take one within their radius check as the half circle and refuse the rest.
      const double allowance_mm = d_.radius_abs_mm > 0 ? d_.radius_abs_mm : kRadiusAimMm;
      if (std::abs(r) < d / 2 - allowance_mm) {
        sink_.problem({b.line, 1}, "E-MODEL-ARC-RADIUS",
                      fmt::format("R {:.4f} mm is shorter than half the chord, {:.4f} mm (allowed {:.4f} mm less); "
                                  "no circle joins the end points",
                                  std::abs(r), d / 2, allowance_mm));
        known = false;
        return c;
      }
      double h2 = r * r - d * d / 4;
      double h = h2 > 0 ? std::sqrt(h2) : 0.0;
      Vec2 n = left_normal(chord / d);
      // G3 with R > 0 (short way round): centre on the left of the chord; G2: on the right.
      double side = (kind == MoveKind::ArcCCW ? 1.0 : -1.0) * (r >= 0 ? 1.0 : -1.0);
      Vec2 cc = (s + e) / 2 + side * h * n;
      c[a.first] = cc.x();
      c[a.second] = cc.y();
      return c;
    }
    // RS274 reads I/J/K as offsets from the start unless G90.1; a dialect that reads them
    // as the absolute centre does so unless the program is in incremental mode (G91).
    if (!ijk_seen[a.first] && !ijk_seen[a.second]) {
      sink_.problem({b.line, 1}, "E-MODEL-ARC-CENTRE",
                    fmt::format("G{} has no centre: neither {} nor {} nor R is given; it is kept and not measured",
                                kind == MoveKind::ArcCW ? 2 : 3, char('I' + a.first), char('I' + a.second)));
      known = false;
      return c;
    }
    bool absolute = d_.centre == CentreReading::Absolute ? fr.absolute : fr.arc_absolute;
    for (int k = 0; k < 3; ++k) {
      if (k == a.normal) continue;
      double off = ijk_seen[k] ? ijk[k] : 0.0;
      if (absolute)
        c[k] = ijk_seen[k] ? fr.to_mm(k, off) : pos_[k];
      else
        c[k] = pos_[k] + off * fr.unit_mm;
    }
    return c;
  }

  Move& add_move(uint32_t bi, MoveKind kind, const AxisValues& to, bool known, int turns) {
    Move m;
    m.to = to;
    m.block = bi;
    m.frame = uint32_t(out_.frames.size() - 1);
    m.kind = kind;
    m.plane = f_plane_;
    m.feed_mm_min = feed_mm_;
    m.known = known;
    m.turns = int16_t(turns);
    m.spindle = spindle_;
    out_.move_of_block[bi] = int32_t(out_.moves.size());
    out_.moves.push_back(m);
    return out_.moves.back();
  }

  void set_frame(const Frame& f) {
    if (f.same_as(frame_)) return;
    frame_ = f;
    out_.frames.push_back(f);
  }

  /// A word's number as the controller reads it: where the dialect counts numbers without
  /// a decimal point in least increments (Fanuc "X1" = 0.001 mm), scaled to program units.
  double number(const Word& w) const {
    if (!d_.decimal_point || w.has_point || w.is_expr) return w.value;
    double inc = frame_.unit_mm == 1.0 ? d_.integer_increment_mm : d_.integer_increment_inch;
    return inc > 0 ? w.value * inc : w.value;
  }

  const Program& p_;
  const Dialect& d_;
  DiagnosticSink& sink_;
  Interpretation out_;
  Frame frame_;
  Plane f_plane_ = Plane::XY;
  AxisValues pos_{};
  uint32_t known_ = 1u << kE;  // bit per axis: position known; E is a counter from 0
  /// Per axis not known: why, and the block that made it so (-1: never set).
  struct Why {
    Unfit reason = Unfit::UnknownAtStart;
    int64_t block = -1;
  };
  Why why_[kAxisCount] = {};
  int64_t cause_block_ = -1;  // of the last unplaced move
  double spindle_ = 0;   // S in force
  int motion_ = 0;       // modal motion G-code ×10; G0 at power-up
  double feed_mm_ = 0;
  bool feed_known_ = false;
};

}  // namespace

Interpretation interpret(const Program& program, DiagnosticSink& sink, const Dialect& dialect) {
  return Interpreter(program, dialect, sink).run();
}

}  // namespace arcpress
