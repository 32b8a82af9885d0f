// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/model/interpreter.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <bitset>
#include <cmath>
#include <optional>

#include "arcpress/lex/o_word.hpp"
#include "arcpress/model/arc_centre.hpp"
#include "arcpress/model/called_programs.hpp"
#include "arcpress/model/jump_entries.hpp"
#include "arcpress/model/o_word_flow.hpp"
#include "arcpress/model/unread_line.hpp"

namespace arcpress {
namespace {

/// Per letter (from 'A'): whether a controller refuses to see it twice in one block (the
/// axes, the centre words, R, F and P).
constexpr auto kOncePerBlock = [] {
  std::array<bool, 32> once{};
  for (char c : std::string_view("XYZABCUVWEIJKRFP")) once[size_t(c - 'A')] = true;
  return once;
}();

constexpr uint32_t kAllAxes = (1u << kAxisCount) - 1;
constexpr uint32_t kXyzMask = (1u << kX) | (1u << kY) | (1u << kZ);

class Interpreter {
 public:
  Interpreter(const Dialect& d, DiagnosticSink& sink, const ModalState& start) : d_(d), sink_(sink), s_(start) {
    for (const CodeReading& c : d.codes) {
      if (c.letter == 'G') own_g_.set(uint32_t(c.code10) % kOwnSlots);
      if (c.letter == 'M') own_m_.set(uint32_t(c.code10) % kOwnSlots);
    }
    for (const TurnReading& t : d.last_turn)  // (and G02/G03, which set the way too)
      for (int code10 : {t.code10, t.cw10, t.ccw10, 20, 30}) own_g_.set(uint32_t(code10) % kOwnSlots);
  }

  void begin(const Program& p, Interpretation& out) {
    p_ = &p, o_ = &out;
    out.frames.assign(1, s_.frame);
    out.start = s_.pos;
    out.start_known = (s_.known & kXyzMask) == kXyzMask;
  }

  void step(uint32_t bi) {
    while (o_->move_of_block.size() <= bi) o_->move_of_block.push_back(-1);
    if (d_.indented_blocks || s_.nesting.depth) [[unlikely]] return nested_step(bi);
    block(bi, p_->blocks[bi]);
    if (end_read_ || call_read_) [[unlikely]] after_block(bi);
  }

  const ModalState& state() const { return s_; }
  void reset(const ModalState& s) { s_ = s; }

 private:
  /// What a code the dialect reads its own way ([codes]) did in a block, bit by bit.
  static constexpr uint32_t kOwnSettings = 1, kOwnFrame = 2, kOwnMachine = 4, kOwnPole = 8, kOwnCycleCalls = 16,
                            kOwnCycleCall = 32, kOwnToolCall = 64, kOwnEndsAnywhere = 128, kOwnInch = 256,
                            kOwnMm = 512, kOwnDiameter = 1024, kOwnRadius = 2048, kOwnArcRadius = 4096;
  /// Reads code `w` of block `bi` as the dialect's `meaning`: what it does that the block's
  /// reading must know goes into `own`; returns the RS274 code it stands for (G20 or G21,
  /// G7 or G8, times ten), or -1. (A function of its own, and the block's state passed as bits: the
  /// block reader's locals stay out of memory, which a lambda taking them by reference costs
  /// on every block.)
  int own_code(CodeMeaning meaning, const Block& b, uint32_t bi, const Word& w, uint32_t& own) {
    switch (meaning) {
      case CodeMeaning::Inch: return 200;
      case CodeMeaning::Mm: return 210;
      case CodeMeaning::Diameter: return 70;
      case CodeMeaning::Radius: return 80;
      case CodeMeaning::Settings: own |= kOwnSettings; return -1;
      case CodeMeaning::Mode: return -1;
      case CodeMeaning::Frame:
        own |= kOwnFrame;
        forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterOffset, bi);
        return -1;
      case CodeMeaning::Machine: own |= kOwnMachine; return -1;
      case CodeMeaning::Moves:
        own |= kOwnEndsAnywhere;
        forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterCodeMove, bi);
        return -1;
      case CodeMeaning::Pole: own |= kOwnPole; return -1;
      case CodeMeaning::Polar: note_pole_read(bi); break;
      case CodeMeaning::CycleCalls: own |= kOwnCycleCalls; return -1;
      case CodeMeaning::MacroCalls: own |= kOwnCycleCalls | kOwnSettings; return -1;
      case CodeMeaning::CycleCall: own |= kOwnCycleCall; return -1;
      case CodeMeaning::ArcRadius: own |= kOwnArcRadius; return -1;
      case CodeMeaning::Loop:  // (M808 L marks a loop's start, entered from its end; M808 alone goes back there)
        if (p_->find(b, 'L')) enter(bi, false);
        own |= kOwnSettings, join(follow_repeat_marker(s_, p_->find(b, 'L') != nullptr, b.line), bi);
        return -1;
      case CodeMeaning::Unmodelled: break;
    }
    sink_.problem({b.line, w.col}, "E-MODEL-GCODE",
                  fmt::format("{} is not modelled under {}; the block is kept and not fitted", p_->raw(b, w), d_.name));
    own |= kOwnEndsAnywhere;
    not_modelled(bi);
    return -1;
  }

  /// The own bit for what RS274 code `g` (own_code(): G20, G21, G7 or G8, times ten, or -1)
  /// sets, where a code that is no G-code (an M-code, a letter, a keyword) is read as it.
  static uint32_t own_setting(int g) {
    return g == 200 ? kOwnInch : g == 210 ? kOwnMm : g == 70 ? kOwnDiameter : g == 80 ? kOwnRadius : 0;
  }

  /// A G0 or G1 block `b` with an R word: it ends where the program does not say (see block()).
  [[gnu::noinline]] void line_with_radius(const Block& b, uint32_t& own) {
    const Word* r = p_->find(b, 'R');
    sink_.warning({b.line, r ? r->col : 1}, "W-MODEL-LINE-R",
                  "R in a G0/G1 block: a saved position's number (RepRapFirmware) or a corner rounding after the "
                  "block (a lathe's direct drawing dimensions); the block is kept, and the position after it is not known");
    own |= kOwnEndsAnywhere;
  }

  /// Reads word `w` of block `bi`, a letter's (D, L) or a keyword's, as the dialect's [codes]
  /// say, if they name it. (Out of the block reader: few programs have such words.)
  [[gnu::noinline]] void own_word(const Block& b, uint32_t bi, const Word& w, uint32_t& own) {
    const CodeMeaning* m = w.letter == kKeywordLetter ? d_.keyword_meaning(p_->keyword_name(b, w)) : d_.meaning_of(w.letter, 0);
    if (!m) return;
    // A modal call's keyword with no call after it (Sinumerik's MCALL alone) ends the calls.
    const CodeMeaning meaning = *m == CodeMeaning::CycleCalls && w.flag ? CodeMeaning::CycleCall : *m;
    if (meaning == CodeMeaning::ArcRadius) own_radius_ = number(w);
    own |= own_setting(own_code(meaning, b, bi, w, own));
  }

  /// After a code arcpress does not model in block `bi`: the position is not known, and the move
  /// before it stays as written. Such a block may go on from the path element before it
  /// (Heidenhain's chamfer G24 between two lines and rounding G25, its tangential arcs G06 and
  /// G16, its departure G27): a primitive of arcpress's ending there would change what it makes.
  void not_modelled(uint32_t bi) {
    forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterUnmodelled, bi);
    keep_last_move();
  }
  void keep_last_move() {
    if (!o_->moves.empty() && o_->moves.back().unfit == Unfit::None) o_->moves.back().unfit = Unfit::BeforeUnmodelled;
  }

  void block(uint32_t bi, const Block& b) {
    switch (b.kind) {
      case BlockKind::Empty: case BlockKind::Percent: return;
      case BlockKind::Code: break;
      case BlockKind::HostCommand:
        if (p_->jumps) read_jump(s_, p_->raw(b), b.line, sink_);  // (Sinumerik's GOTOB N10)
        // Firmware M-codes with a text argument (a message, an object label, a printer check,
        // a file name) move nothing, nor do the extended commands the dialect names
        // (Klipper's EXCLUDE_OBJECT_START, SET_VELOCITY_LIMIT, ...); M32 starts another
        // program, M98 P"file.g" runs a macro file and M291's message box may let the user jog
        // (RepRapFirmware), and other host commands (`$H` homing, `$J=` jogging, firmware
        // macros) may move anything.
        if (const Word* w = b.word_count > 0 ? p_->words_begin(b) : nullptr; w && w->letter == 'M' && !w->is_expr &&
            w->code10() != 320 && w->code10() != 980 && w->code10() != 2910)
          return;
        if (d_.keeps_position(p_->raw(b))) return;
        forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterControl, bi);
        return;
      default:
        // Flow control, macros and unread lines may move anything, and may turn about the
        // centre I/J/K left in force (Heidenhain's polar moves, PR/PA words, are unread lines).
        // A line not understood at all may also go on from the move before it, as a block
        // with a code arcpress does not model may (not_modelled()), and set the modes its G words name.
        if (d_.centre_modal) note_pole_read(bi);
        if (b.kind == BlockKind::Opaque) keep_last_move(), s_.forget_modes(modes_named(p_->raw(b), d_));
        forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterControl, bi);
        if (b.kind == BlockKind::Control || b.kind == BlockKind::Macro) o_word_line(bi, b);
        if (p_->jumps) read_jump(s_, p_->raw(b), b.line, sink_);
        return;
    }
    bool other_words = false;   // words a fitted block could not carry along
    int motion = -1;            // G-code ×10 of a motion word in this block
    bool g92 = false, g92_reset = false, g53 = false, axis_consumer = false, homing = false;
    bool g10 = false, l_seen = false;
    bool probing = false;  // G29: a printer's bed probing, which ends where it likes
    bool skip = false;     // G31: a skip move (Fanuc), which stops where a signal comes
    bool g50 = false;      // G50: a lathe's coordinate setting where it has axis words, else a spindle limit
    uint32_t g11_col = 0;  // column of a G11 the firmware reads as its recovery (0: none)
    // Bit per axis: written with a value, with an expression, as a flag.
    uint32_t words_seen = 0, expr_axis = 0, flag_axis = 0;
    uint32_t length_col = 0;  // column of the block's first length (a linear axis's word)
    double value[kAxisCount] = {};
    double ijk[3] = {0, 0, 0};
    bool ijk_seen[3] = {};
    bool r_seen = false, feed_set = false;
    double r_value = 0, feed = 0;
    int turns = 1;
    // Most blocks change no modal setting: copy the frame only when one is touched.
    std::optional<Frame> fedit;
    auto F = [&]() -> Frame& { return fedit ? *fedit : fedit.emplace(s_.frame); };
    // What the codes the dialect reads its own way ([codes]) did in this block (own_code()).
    uint32_t own = 0;

    bool repeated = false;  // a word the controller refuses to see twice
    uint32_t letters_seen = 0;
    for (const Word *w = p_->words_begin(b), *end = p_->words_end(b); w != end; ++w) {
      char L = w->letter;
      if (kOncePerBlock[uint8_t(L - 'A') & 31] && L >= 'A' && L <= 'Z' && !w->flag) {
        const uint32_t bit = 1u << (L - 'A');
        if (letters_seen & bit) {
          repeated = true;
          sink_.problem({b.line, w->col}, "E-MODEL-REPEATED-WORD",
                        fmt::format("{} appears twice in the block ('{}'); controllers refuse it", L, p_->raw(b, *w)));
        }
        letters_seen |= bit;
      }
      if (int ax = axis_of_letter(L); ax >= 0) {
        if (w->flag) {
          flag_axis |= 1u << ax;
          continue;
        }
        words_seen |= 1u << ax;
        if (kAxisIsLinear[ax] && length_col == 0) length_col = w->col;
        expr_axis = w->is_expr ? expr_axis | 1u << ax : expr_axis & ~(1u << ax);
        value[ax] = ax == kE ? w->value : number(*w);
        continue;
      }
      if (w->is_expr) {
        if (L == 'G' || L == 'M') other_words = true, forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterExpression, bi);
        if (L == 'G') s_.forget_modes(kStatesAll);  // (G#1 may be G18, G91, G20, G2)
        if (L == 'F') s_.feed_known = false;
        if (L == 'S') s_.spindle = ModalState::kSpindleUnknown;
        continue;
      }
      switch (L) {
        case 'G': {
          int g = w->code10();
          if (g != 10) other_words = true;
          // A code the dialect reads its own way is read as RS274's code of that meaning, one
          // that turns as the last arc did as the code for that way.
          if (own_g_[uint32_t(g) % kOwnSlots]) {
            if (turns_) g = read_turn(d_, g, s_.turn, *o_, bi, sink_, {b.line, w->col}, p_->raw(b, *w));
            if (const CodeMeaning* m = d_.meaning_of('G', g)) {
              g = own_code(*m, b, bi, *w, own);
              if (g < 0) break;
            }
          }
          switch (g) {
            case 0: case 10: case 20: case 30: motion = g; break;
            case 50: case 51: case 52: case 53: motion = g; break;  // G5, G5.1, G5.2, G5.3
            case 330: case 331: case 382: case 383: case 384: case 385: case 760:
            case 730: case 810: case 820: case 830: case 840: case 850: case 860: case 870: case 880: case 890:
              motion = g;
              break;
            case 800: motion = 800; break;
            case 40: break;  // dwell
            case 170: s_.plane = Plane::XY, stated(kStatesPlane); break;
            case 180: s_.plane = Plane::ZX, stated(kStatesPlane); break;
            case 190: s_.plane = Plane::YZ, stated(kStatesPlane); break;
            case 200: F().unit_mm = 25.4, s_.units_told = true, stated(kStatesUnits); break;
            case 210: F().unit_mm = 1.0, s_.units_told = true, stated(kStatesUnits); break;
            case 70: F().diameter_mode = true; break;
            case 80: F().diameter_mode = false; break;
            case 900: case 910:
              F().absolute = g == 900, s_.distance_unknown = false, entry_stated(kStatesDistance), extrusion(F(), true, g == 910);
              if (g == 900 && s_.floating) forget(s_.floating, Unfit::UnknownAtEntry, bi);
              break;
            case 901: F().arc_absolute = true, s_.centre_told = true; break;
            case 911: F().arc_absolute = false, s_.centre_told = true; break;
            case 920: g92 = true; axis_consumer = true; break;
            case 921: case 922: g92_reset = true; break;
            case 923: break;
            case 930: F().inverse_time = true; break;
            case 940: case 950: F().inverse_time = false; break;
            case 280: case 300: homing = true; axis_consumer = true; break;
            case 281: case 301: break;
            case 700: case 710: case 720: case 740: case 750:  // lathe turning cycles: run elsewhere
              axis_consumer = true;
              forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterCycle, bi);
              break;
            case 100: g10 = true; axis_consumer = true; break;  // G10: read with the block's other words
            case 530: g53 = true; break;
            case 540: case 550: case 560: case 570: case 580: case 590: case 591: case 592: case 593:
              if (s_.frame.work_offset != g)  // same machine point, new coordinates
                forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterOffset, bi);
              F().work_offset = g;
              break;
            // Read as they are, moving nothing the path depends on.
            case 400: case 410: case 411: case 420: case 421:  // cutter compensation
            case 610: case 611: case 640:                       // path control
            case 980: case 990:                                 // canned-cycle return
            case 960: case 970:                                 // constant surface speed
              break;
            // Tool length: the program's Z now names another point of the tool, so Z is read
            // anew; G43.1 and G43.2 take the offsets themselves as axis words (LinuxCNC).
            case 430: case 490: forget(1u << kZ, Unfit::UnknownAfterOffset, bi); break;
            case 431: case 432:
              axis_consumer = true;
              forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterOffset, bi);
              break;
            case 150: F().polar = false; break;
            case 160: F().polar = true; break;
            case 290: probing = true; axis_consumer = true; break;  // its words are a grid's, not a position
            case 310: skip = true; break;
            case 320: motion = g; break;  // threading (Fanuc G32), synchronised to the spindle, as G33
            case 500: g50 = true; break;  // a lathe's coordinate setting, or a spindle limit
            case 110:  // G11: the firmware's recovery after its retraction, where it retracts
              if (d_.firmware_retraction) {
                g11_col = w->col;
                break;
              }
              [[fallthrough]];
            default:
              if (g == 650) call_read_ = g;  // Fanuc's macro call
              sink_.problem({b.line, w->col}, "E-MODEL-GCODE",
                            fmt::format("{} is not modelled; the block is kept and not fitted",
                                        p_->raw(b, *w)));
              own |= kOwnEndsAnywhere;
              not_modelled(bi);
              break;
          }
          break;
        }
        case 'M': {
          other_words = true;
          const int m = w->code10();
          if (m == 970 || m == 980) call_read_ = m;  // a subprogram's call (after_block())
          if (const CodeMeaning* own_m = own_m_[uint32_t(m) % kOwnSlots] ? d_.meaning_of('M', m) : nullptr) {
            own |= own_setting(own_code(*own_m, b, bi, *w, own));
            break;
          }
          if (m == 820 || m == 830) extrusion(F(), false, m == 830);
          if (m == 20 || m == 300) end_read_ = true;
          if (m == 20 || m == 300 || m == 990) s_.ended = true;
          if (m == 990 && p_->jumps) read_jump(s_, p_->raw(b), b.line, sink_);  // (M99 Pn: a jump)
          if (m == 990) enter(bi, false);  // the blocks after a return run only when a call or jump enters them
          // A tool change may move the tool; the controller goes on from there (LinuxCNC re-reads it after M6).
          if (m == 60) forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterToolChange, bi);
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
          s_.spindle = w->value;
          break;
        case 'N': case kLabelLetter:
          if (const auto key = p_->jumps ? w->target_key() : std::nullopt; key && p_->jumps->enters(*key))
            enter(bi, p_->jumps->only_called(*key), CalledPrograms::key_of(*w), key);
          break;
        case 'T':
          other_words = true;
          if (const CodeMeaning* t = d_.codes.empty() ? nullptr : d_.meaning_of('T', 0); t && *t == CodeMeaning::Moves)
            own |= kOwnToolCall;
          break;
        case 'L':  // G10's table, or a subprogram call (Sinumerik's L10: [codes] L = "moves")
          l_seen = true;
          other_words = true;
          if (!d_.codes.empty()) own_word(b, bi, *w, own);
          break;
        default:
          // (Among them a tool's offsets D, its length compensation too on a Sinumerik, and
          // the dialect's keywords: the lexer reads no others.)
          other_words = true;
          if ((L == 'D' || L == kKeywordLetter) && !d_.codes.empty()) own_word(b, bi, *w, own);
          if (L == 'O' && s_.ended) enter(bi, true, CalledPrograms::key_of(*w));  // another program: a call enters it
          break;
      }
    }
    if (own & kOwnArcRadius) r_seen = true, r_value = own_radius_, other_words = true;
    if (own & (kOwnInch | kOwnMm | kOwnDiameter | kOwnRadius)) {  // codes that are no G-code, read as G20, G21, G7, G8
      if (own & (kOwnInch | kOwnMm)) F().unit_mm = (own & kOwnInch) ? 25.4 : 1.0, s_.units_told = true, stated(kStatesUnits);
      if (own & (kOwnDiameter | kOwnRadius)) F().diameter_mode = (own & kOwnDiameter) != 0;
    }
    if (length_col > 0 && !s_.units_told)  // (said once)
      sink_.warning({b.line, length_col}, "W-MODEL-UNITS", start_units_warning(d_)), s_.units_told = true;
    // Where the firmware retracts (d_.firmware_retraction), G10 without L and without axis
    // words retracts (or sets a tool's temperatures) and G11 recovers: the programmed position
    // stays. Any other G10 sets offsets or tables the program's coordinates may depend on.
    const bool axis_words = words_seen != 0 || flag_axis != 0;
    if (g10 && !(d_.firmware_retraction && !l_seen && !axis_words))
      forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterCycle, bi);
    if (g11_col > 0 && axis_words) {
      sink_.problem({b.line, g11_col}, "E-MODEL-GCODE",
                    "G11 with axis words is not modelled; the block is kept and not fitted");
      forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterUnmodelled, bi);
    }
    // A tool call (the dialect's T word) may move the tool, as M6 may; a T word in a tool's
    // definition or preselection (a code read as settings) calls none.
    bool cycle_here = false;  // a cycle is called at the end of this block's move
    if (own != 0 || s_.cycle_calls) {
      if (own & (kOwnSettings | kOwnFrame)) axis_consumer = true;
      if (own & kOwnSettings) feed_set = false;  // (its F is one of its values: Sinumerik's dwell G4 F2, in seconds)
      if (own & kOwnMachine) g53 = true;
      if ((own & kOwnToolCall) && !(own & kOwnSettings)) forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterToolChange, bi);
      // A cycle called at this block (M89 in force, or a code that calls it) runs at the end
      // of its move, or where the tool is: the cycle's own moves end where the program does
      // not say.
      cycle_here = s_.cycle_calls || (own & (kOwnCycleCalls | kOwnCycleCall));
      if (own & kOwnCycleCalls) s_.cycle_calls = true;
      if (own & kOwnCycleCall) s_.cycle_calls = false;
      if ((own & kOwnCycleCall) && words_seen == 0) forget(kXyzMask, Unfit::UnknownAfterCycle, bi);
    }
    if (probing) {
      forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterHoming, bi);
      feed_set = false;  // (Marlin's G29 F is the grid's front edge)
    }
    // A lathe's G50 X.. Z.. names the present point, as G92 does (Fanuc's G-code system A).
    if (g50 && words_seen != 0) g92 = true, axis_consumer = true;
    const Frame& fnow = fedit ? *fedit : s_.frame;
    if (feed_set) {
      s_.feed_mm = fnow.inverse_time ? feed : feed * fnow.unit_mm;
      s_.feed_known = true;
    }

    // G92 and G92.1 change the offsets; positions in mm stay where they are.
    if (g92_reset) F().offset = AxisValues{};
    if (g92) {
      Frame& f = F();
      for (int ax = 0; ax < kAxisCount; ++ax) {
        if (!((words_seen >> ax) & 1u)) continue;
        if ((expr_axis >> ax) & 1u) {
          forget(1u << ax, Unfit::UnknownAfterExpression, bi);
          continue;
        }
        double scale = kAxisIsLinear[ax] ? f.unit_mm : 1.0;
        f.offset[ax] = s_.pos[ax] - value[ax] * scale;
      }
    }
    if (fedit) set_frame(*fedit);
    if (motion >= 0) s_.motion = motion, entry_stated(kStatesMotion);
    if (d_.centre_modal && (ijk_seen[0] || ijk_seen[1] || ijk_seen[2] || (own & kOwnPole)))
      set_pole(s_, ijk, ijk_seen, own & kOwnPole);

    const bool any_axis = words_seen != 0;
    if (homing) {
      // G28/G30: through an optional point to a stored position we do not know.
      const bool any_flag = flag_axis != 0;
      for (int ax = 0; ax < kE; ++ax)
        if ((((words_seen | flag_axis) >> ax) & 1u) || (!any_axis && !any_flag)) {
          forget(1u << ax, Unfit::UnknownAfterHoming, bi);
          // One stand-in for the home position, whatever came before, so that two programs
          // that home alike hold the same stand-in for an axis they do not set again.
          s_.pos[ax] = 0;
        }
      Move& m = add_move(bi, MoveKind::Other, s_.pos, false, 1);
      m.unknown_axes = uint16_t(kAllAxes & ~s_.known);
      m.end_known = false;
      return;
    }
    if (!any_axis || axis_consumer) {
      // Arc words without axes (a full circle in I/J form) still move along a path; where they
      // set a centre that holds (centre_modal), they only set it.
      if (!(s_.motion == 20 || s_.motion == 30) || !(ijk_seen[0] || ijk_seen[1] || ijk_seen[2]) || axis_consumer ||
          d_.centre_modal)
        return;
    }

    const Frame& fr = s_.frame;
    const bool entered = !fr.absolute && !s_.distance_unknown && (words_seen & ~s_.known & ~(1u << kE)) && float_entry();
    AxisValues target = s_.pos;
    uint32_t known_after = s_.known;
    uint32_t written = 0;  // axes this block writes
    // Why each axis is unknown after the block: as before it, unless the block gives a reason
    // of its own (the copy is made then: most blocks give none).
    Unfit after_why[kAxisCount];
    bool reasons_changed = false;
    auto set_why = [&](int ax, Unfit why) {
      if (!reasons_changed)
        for (int k = 0; k < kAxisCount; ++k) after_why[k] = s_.why[k].reason;
      reasons_changed = true;
      after_why[ax] = why;
    };
    auto why_after = [&](int ax) { return reasons_changed ? after_why[ax] : s_.why[ax].reason; };
    for (uint32_t axes = words_seen; axes != 0; axes &= axes - 1) {
      const int ax = std::countr_zero(axes);
      written |= 1u << ax;
      if ((expr_axis >> ax) & 1u) {
        known_after &= ~(1u << ax);
        set_why(ax, Unfit::UnknownAfterExpression);
        continue;
      }
      double v = value[ax];
      if (ax == kX && fr.diameter_mode) v *= 0.5;
      double scale = kAxisIsLinear[ax] ? fr.unit_mm : 1.0;
      bool relative = ax == kE ? fr.e_relative : !fr.absolute;
      if (g53) {
        known_after &= ~(1u << ax);  // machine coordinates: not in our frame
        set_why(ax, Unfit::UnknownAfterMachine);
        target[ax] = v * scale;
      } else if (relative) {
        target[ax] = s_.pos[ax] + v * scale;
      } else {
        target[ax] = fr.to_mm(ax, v);
        known_after |= (1u << ax);
      }
    }
    // Each word an absolute place or an increment; or in a plane or units not known.
    if (s_.distance_unknown || s_.unstated) [[unlikely]]
      for (uint32_t axes = words_seen & ~(1u << kE); axes != 0; axes &= axes - 1) {
        known_after &= ~(1u << std::countr_zero(axes));
        set_why(std::countr_zero(axes), Unfit::UnknownDistanceMode);
      }

    // In polar coordinates the plane's words are a radius and an angle (about the origin or,
    // under G91, the present point): the point they name is not computed, and both the
    // plane's axes move when either word does.
    const uint32_t plane_axes = (1u << axes_of(s_.plane).first) | (1u << axes_of(s_.plane).second);
    if (fr.polar && (written & plane_axes)) {
      for (int ax : {axes_of(s_.plane).first, axes_of(s_.plane).second}) {
        known_after &= ~(1u << ax);
        set_why(ax, Unfit::UnknownInPolar);
      }
      written |= plane_axes;
    }

    MoveKind kind = MoveKind::Other;
    if (!g53 && !skip) {
      // A dialect whose G18 arcs turn the other way is read back into RS274's sense here.
      bool flip = d_.zx_reversed && s_.plane == Plane::ZX;
      if (s_.motion == 0) kind = MoveKind::Rapid;
      else if (s_.motion == 10) kind = MoveKind::Line;
      else if (s_.motion == 20) kind = flip ? MoveKind::ArcCCW : MoveKind::ArcCW;
      else if (s_.motion == 30) kind = flip ? MoveKind::ArcCW : MoveKind::ArcCCW;
    }
    // An R word in a line's block: RS274 gives it no meaning there, RepRapFirmware moves to
    // a saved position offset by the block's axis words (G1 R1 X0 Y0 Z2), a lathe that takes
    // direct drawing dimensions rounds the corner after it: where the block ends is not known.
    if (r_seen && (kind == MoveKind::Line || kind == MoveKind::Rapid)) line_with_radius(b, own);
    // The axes the move moves: those it writes, and an arc's two plane axes, which it
    // moves around the centre whether it writes them or not. An axis it does not move
    // stays where it is, known or not (a 2-D program never sets Z; a lathe never sets Y),
    // so the move is placed where every axis it moves is known at both ends.
    uint32_t moved = written;
    if (is_arc(kind)) moved |= (1u << axes_of(s_.plane).first) | (1u << axes_of(s_.plane).second);
    const uint32_t unknown_moved = moved & ~(s_.known & known_after);
    bool known = unknown_moved == 0;
    Unfit unplaced_why = Unfit::None;
    for (int ax = 0; ax < kAxisCount && !known; ++ax)
      if ((unknown_moved >> ax) & 1u) {
        // The axis unknown at the start says why; one this block makes unknown, this block.
        const bool at_start = !((s_.known >> ax) & 1u);
        unplaced_why = at_start ? s_.why[ax].reason : why_after(ax);
        s_.cause_line = at_start ? s_.why[ax].line : b.line;
        break;
      }
    // A code arcpress does not model, or one that moves the tool where the program does not
    // say, may end anywhere whatever axis words its block holds (Haas's engraving G47 starts
    // at its X/Y; Marlin's G26 prints a pattern from its X/Y).
    if (own & kOwnEndsAnywhere) {
      for (int ax = 0; ax < kAxisCount; ++ax)
        if (ax != kE && ((known_after >> ax) & 1u)) set_why(ax, s_.why[ax].reason);
      known_after &= 1u << kE;
    }
    if (kind == MoveKind::Other && (s_.motion != 0 || skip)) {  // cycles, skip moves and motions not known
      for (int ax : {kX, kY, kZ})
        if ((known_after >> ax) & 1u) set_why(ax, s_.motion < 0 ? Unfit::UnknownDistanceMode : Unfit::UnknownAfterCycle);
      known_after &= ~kXyzMask;
    }
    if (is_arc(kind) && !r_seen && !s_.centre_told && d_.centre == CentreReading::Incremental && known) {
      Frame f = s_.frame;
      read_centre_mode(d_, s_, f, target, ijk, ijk_seen, sink_, b.line);
      set_frame(f);
    }
    Move& m = add_move(bi, kind, target, known, turns);
    m.entered = entered;
    m.unknown_axes = uint16_t(kAllAxes & ~(s_.known & known_after));
    m.end_known = known || (moved & ~known_after) == 0;
    if (repeated && m.known) {
      m.known = false;
      unplaced_why = Unfit::RepeatedWord;
      s_.cause_line = b.line;
    }
    if (kind == MoveKind::ArcCW || kind == MoveKind::ArcCCW) {
      bool readable = true;
      m.center = arc_center(b, fr, target, ijk, ijk_seen, r_seen, r_value, kind, readable);
      if (!readable && m.known) {
        m.known = false;
        unplaced_why = Unfit::UnreadableArc;
        s_.cause_line = b.line;
      }
    }
    // A move along X, Y or Z, or one that goes nowhere at all (which the fitter steps over);
    // not one that moves only E or the extra axes (a retraction, a rotary index).
    bool moved_xyz = target[kX] != s_.pos[kX] || target[kY] != s_.pos[kY] || target[kZ] != s_.pos[kZ];
    m.unfit = !m.known                        ? (unplaced_why == Unfit::None ? Unfit::UnknownAfterUnmodelled : unplaced_why)
              : kind != MoveKind::Line        ? Unfit::NotLine
              : b.has_expr                    ? Unfit::Expression
              : b.has_comment                 ? Unfit::Comment
              : b.block_delete                ? Unfit::BlockDelete
              : b.has_checksum                ? Unfit::Checksum
              : other_words                   ? Unfit::OtherWords
              : fr.inverse_time               ? Unfit::InverseTime
              : fr.diameter_mode              ? Unfit::DiameterMode
              : !s_.feed_known                  ? Unfit::FeedUnknown
              : s_.extrusion_unknown && (words_seen >> kE & 1) ? Unfit::ExtrusionModeUnknown
              : !(moved_xyz || target == s_.pos) ? Unfit::NoPathAxis
                                              : Unfit::None;
    if (cycle_here && m.unfit == Unfit::None) m.unfit = Unfit::CycleCall;
    if (s_.entry_pending && any_axis && m.end_known) [[unlikely]]  // (a rapid places the moves after it)
      note_entry_use(s_, !m.known || !is_feed(kind) ? kStatesUnits | kStatesDistance  // (E's mode where it has E)
                                                    : kStatesAll ^ (words_seen >> kE & 1 ? 0 : kStatesExtrusion));
    if (!m.known && is_feed(kind)) o_->unplaced.push_back({uint32_t(o_->moves.size() - 1), s_.cause_line});
    s_.pos = target;
    const bool known_changed = known_after != s_.known;
    s_.known = known_after;
    for (int ax = 0; ax < kAxisCount && (known_changed || reasons_changed); ++ax) {
      if ((s_.known >> ax) & 1u) s_.why[ax] = {Unfit::None, 0};
      else if (why_after(ax) != s_.why[ax].reason) s_.why[ax] = {why_after(ax), b.line};
    }
    if (cycle_here && words_seen != 0) forget(kXyzMask, Unfit::UnknownAfterCycle, bi);
  }

  /// Block `bi` may be entered from elsewhere (JumpTargets, a program number after an end), or
  /// the blocks after it only so (M99): the position and G90 or G91 are not known; where only
  /// calls enter it (`called`, at label `key`), the modes of the calls (enter_called()).
  [[gnu::noinline]] void enter(uint32_t bi, bool called, uint64_t key = CalledPrograms::kNoLabel,
                               std::optional<uint64_t> target = std::nullopt) {
    forget(kAllAxes & ~(1u << kE), Unfit::UnknownAtEntry, bi);
    s_.distance_unknown = true;
    Frame f = s_.frame;
    if (called) enter_called(s_, key, f);
    else if (target) enter_jumped(s_, f, *target, p_->blocks[bi].line);
    set_frame(f);
  }

  /// After block `bi`: a call it made has returned (model/called_programs.hpp), or the program ended.
  [[gnu::noinline]] void after_block(uint32_t bi) {
    if (call_read_) {
      forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterControl, bi);
      Frame f = s_.frame;
      return_from_call(s_, read_call(*p_, p_->blocks[bi], std::exchange(call_read_, 0)), f);
      set_frame(f);
    }
    if (end_read_) program_end(bi);
  }

  /// Block `bi` jumps back to loops' starts, joins the ways out of blocks, or begins a loop (BlockNesting).
  void join(const BlockNesting::Join& j, uint32_t bi) {
    for (uint32_t k = 0; k < j.loops_back_count; ++k) loop_back(s_, j.loops_back[k], p_->blocks[bi].line, sink_);
    if (j.position) forget(kAllAxes & ~(1u << kE), Unfit::UnknownAtEntry, bi);
    s_.forget_modes(uint8_t(j.modes | (j.loop_unfollowed ? kStatesAll : 0)));
    if (j.loop_entered) enter_loop(s_, j.loop_entered, j.loop_line);
  }

  /// Block `bi` inside blocks (BlockNesting), or where blanks open and close them: what it
  /// changes, the blocks around it did; where it closes some, what they changed is not known.
  [[gnu::noinline]] void nested_step(uint32_t bi) {
    const Block& b = p_->blocks[bi];
    const BlockNesting::Modes now = s_.modes();
    const std::string_view raw = p_->raw(b);
    if (d_.indented_blocks) join(s_.nesting.line(raw, b.kind != BlockKind::Code && b.kind != BlockKind::Empty, b.line, now), bi);
    if (b.kind == BlockKind::Control || b.kind == BlockKind::Macro || (b.kind == BlockKind::HostCommand && BlockNesting::leaves_block(raw)))
      s_.nesting.way_out(now);
    const uint32_t known = s_.known;
    const size_t frames = o_->frames.size();
    block(bi, b);
    if (end_read_ || call_read_) after_block(bi);
    if (o_->move_of_block[bi] >= 0 || s_.known != known || o_->frames.size() != frames) s_.nesting.moved();
  }

  void stated(uint8_t mode) { s_.stated |= mode, s_.unstated &= uint8_t(~mode), entry_stated(mode); }
  /// E's mode after G90/G91 (`distance`) or M82/M83 as the firmware reads it; stated where they set it.
  void extrusion(Frame& f, bool distance, bool relative) {
    f.e_relative = extrusion_after(d_.extrusion_distance, distance, relative, distance ? !relative : f.absolute, f.m83);
    if (!distance || d_.extrusion_distance == ExtrusionDistance::WithAxes) s_.extrusion_unknown = false, entry_stated(kStatesExtrusion);
  }
  void entry_stated(uint8_t mode) { s_.entry_pending & mode ? note_entry_stated(s_, mode) : void(); }

  /// LinuxCNC's O-word line `b` (block `bi`), followed as model/o_word_flow.hpp says.
  [[gnu::noinline]] void o_word_line(uint32_t bi, const Block& b) {
    Frame f = s_.frame;
    const OWordFlow flow = follow_o_word(s_, read_o_word(p_->raw(b), !d_.indented_blocks), f, b.line);
    if (flow.enters_body) enter(bi, false), s_.motion = -1;
    if (flow.after_call) forget(kAllAxes & ~(1u << kE), Unfit::UnknownAtEntry, bi);  // one place: G91 floats
    join(flow.join, bi);
    if (!flow.problem.empty()) sink_.error({b.line, 1}, "E-FLOW-SUB-MODES", flow.problem);
    set_frame(f);
  }

  /// After block `bi`, an M2 or M30 (end_program()).
  [[gnu::noinline]] void program_end(uint32_t bi) {
    end_read_ = false;
    if (s_.floating) forget(s_.floating, Unfit::UnknownAtEntry, bi);  // (G90 from here)
    Frame f = s_.frame;
    if (end_program(s_, f)) forget(kAllAxes & ~(1u << kE), Unfit::UnknownAfterOffset, bi);
    set_frame(f);
  }

  /// A G91 move where an entry left axes unknown: they float (ModalState::floating), unless arc
  /// centres are absolute (G90.1, a pole), which a shifted place would misread. Whether any does.
  [[gnu::noinline]] bool float_entry() {
    if (s_.frame.arc_absolute || s_.frame.polar || d_.centre_modal) return false;
    const uint32_t floating = s_.floating;
    for (int ax = 0; ax < kAxisCount; ++ax)
      if (ax != kE && !((s_.known >> ax) & 1u) && s_.why[ax].reason == Unfit::UnknownAtEntry) {
        s_.known |= 1u << ax;
        s_.floating |= 1u << ax;
        s_.why[ax] = {Unfit::None, 0};
      }
    return s_.floating != floating;
  }

  /// Axes in `mask` become unknown, `why`, from block `bi` on (the latest reason is kept).
  void forget(uint32_t mask, Unfit why, uint32_t bi) {
    s_.floating &= ~mask;
    for (int ax = 0; ax < kAxisCount; ++ax)
      if ((mask >> ax) & 1u) s_.why[ax] = {why, p_->blocks[bi].line};
    s_.known &= ~mask;
  }

  Vec3 arc_center(const Block& b, const Frame& fr, const AxisValues& target, const double* ijk,
                  const bool* ijk_seen, bool r_seen, double r_value, MoveKind kind, bool& known) {
    const ArcCentreRead r = read_arc_centre(d_, fr, s_.plane, s_.pos, target, {ijk, ijk_seen, r_seen, r_value},
                                            kind == MoveKind::ArcCCW, s_.pole, s_.pole_known, sink_, b.line);
    if (r.reads_pole) note_pole_read(uint32_t(&b - p_->blocks.data()), true);
    if (!r.known) known = false;
    return r.centre;
  }

  /// Block `bi` reads the centre the dialect's I/J/K left in force (Interpretation::pole_reads).
  void note_pole_read(uint32_t bi, bool arc = false) {
    if (o_->pole_reads.empty() || o_->pole_reads.back().block != bi) o_->pole_reads.push_back(pole_read(s_, bi, arc));
  }

  Move& add_move(uint32_t bi, MoveKind kind, const AxisValues& to, bool known, int turns) {
    Move m;
    m.to = to;
    m.block = bi;
    m.frame = uint32_t(o_->frames.size() - 1);
    m.kind = kind;
    m.plane = s_.plane;
    m.feed_mm_min = s_.feed_mm;
    m.known = known;
    m.turns = int16_t(turns);
    m.spindle = s_.spindle;
    o_->move_of_block[bi] = int32_t(o_->moves.size());
    o_->moves.push_back(m);
    return o_->moves.back();
  }

  void set_frame(const Frame& f) {
    if (f.same_as(s_.frame)) return;
    s_.frame = f;
    o_->frames.push_back(f);
  }

  /// A word's number as the controller reads it: where the dialect counts numbers without
  /// a decimal point in least increments (Fanuc "X1" = 0.001 mm), scaled to program units.
  double number(const Word& w) const {
    if (!d_.decimal_point || w.has_point || w.is_expr) return w.value;
    double inc = s_.frame.unit_mm == 1.0 ? d_.integer_increment_mm : d_.integer_increment_inch;
    return inc > 0 ? w.value * inc : w.value;
  }

  const Dialect& d_;
  bool end_read_ = false;  ///< the block read was a program end (program_end())
  int call_read_ = 0;      ///< the block read made a call: its code times ten (after_block())
  double own_radius_ = 0;  ///< the value of the block's keyword read as the arc's radius (kOwnArcRadius)
  /// The G- and M-codes the dialect reads its own way, and those of Dialect::last_turn, each a
  /// bit at its code (times ten) modulo kOwnSlots: most words are ruled out by one test, not a
  /// search of d_.codes (a table of 64 sent every G1 to the search behind Marlin's G33).
  static constexpr uint32_t kOwnSlots = 1024;
  std::bitset<kOwnSlots> own_g_, own_m_;
  /// The dialect has codes that turn as the last programmed arc did (Dialect::last_turn).
  const bool turns_ = !d_.last_turn.empty();
  DiagnosticSink& sink_;
  ModalState s_;
  const Program* p_ = nullptr;
  Interpretation* o_ = nullptr;
};

}  // namespace

struct ModalInterpreter::Impl : Interpreter {
  using Interpreter::Interpreter;
};

ModalInterpreter::ModalInterpreter(const Dialect& dialect, DiagnosticSink& sink, const ModalState& start)
    : impl_(std::make_unique<Impl>(dialect, sink, start)) {}
ModalInterpreter::~ModalInterpreter() = default;
ModalInterpreter::ModalInterpreter(ModalInterpreter&&) noexcept = default;
void ModalInterpreter::begin(const Program& program, Interpretation& out) { impl_->begin(program, out); }
void ModalInterpreter::step(uint32_t block) { impl_->step(block); }
const ModalState& ModalInterpreter::state() const { return impl_->state(); }
void ModalInterpreter::reset(const ModalState& state) { impl_->reset(state); }

}  // namespace arcpress
