// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/emit/emitter.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <optional>

#include "arcpress/core/deviation.hpp"
#include "arcpress/core/workers.hpp"
#include "arcpress/emit/flow_point.hpp"
#include "arcpress/emit/number_format.hpp"
#include "arcpress/emit/output_habits.hpp"

namespace arcpress {
namespace {

/// More decimals than any input number carries: the search for a value's own decimals
/// stops here.
constexpr int kMaxDecimals = 9;
/// Relative difference below which a value printed at some decimals is the value itself
/// (absorbs the unit conversion's rounding, far below any printed digit).
constexpr double kSameValue = 1e-9;

/// The fewest decimals, up to `most`, that print `v` as it is (within kSameValue of it).
int own_decimals(double v, int most) {
  int dec = 0;
  while (dec < most && std::abs(rounded(v, dec) - v) > kSameValue * std::max(1.0, std::abs(v))) ++dec;
  return dec;
}

class Emitter {
 public:
  Emitter(const Program& p, const Interpretation& in, const EmitOptions& opt, EmitStats* stats)
      : p_(p), in_(in), stats_(stats), opt_(opt) {
    out_.reserve(p.text.size());
    const OutputHabits h = opt.start.habits ? *opt.start.habits : output_habits(p);
    habits_ = h;
    pole_moved_ = opt.start.pole_maybe_moved ? 0b111u : 0u;
    turn_moved_ = opt.start.turn_maybe_moved;
    for (const CodeReading& c : d().codes)
      if (c.letter == 'G' && is_motion_gcode(c.code10 / 10.0) && !d().turn_reading(c.code10)) own_motion_.push_back(c.code10);
    block_end_ = h.block_end;
    in_motion_ = opt.start.in_motion;
    out_motion_ = opt.start.out_motion;
    header_done_ = opt.start.header_done;
    // Where the controller's own setting decides how I/J/K read, what the output has said of
    // it: nothing at the program's start (the setting holds), else what the program said, or
    // what an earlier piece may have said.
    if (d().start_centres == StartCentres::Machine) {
      out_centres_ = opt.start.centres_maybe_said ? CentresOut::Unknown : CentresOut::Setting;
      // Once the program has said it, every mode word written since matched the reading then.
      if (opt.start.header_done && !in_.frames.empty())
        out_centres_ = in_.frames.front().arc_absolute ? CentresOut::Absolute : CentresOut::Incremental;
    }
  }

  std::string run(const std::vector<Run>& runs, const std::vector<FitResult>& fits) {
    compose_all(runs, fits);
    size_t r = 0;
    std::vector<std::pair<size_t, size_t>> spans;  // per run, its bytes in out_
    for (size_t bi = 0; bi < p_.blocks.size(); ++bi) {
      if (r < runs.size() && in_.moves[runs[r].first_move].block == bi) {
        const size_t from = out_.size();
        emit_run(runs[r], fits[r], composed_[r]);
        spans.emplace_back(from, out_.size());
        bi = in_.moves[runs[r].first_move + runs[r].move_count - 1].block;
        ++r;
        continue;
      }
      copy_block(p_.blocks[bi]);
    }
    if (stats_) {  // bytes to lines, in one pass
      size_t line = 1, at = 0;
      auto line_of = [&](size_t offset) {
        const char* const to = out_.data() + std::min(offset, out_.size());
        for (const char* p = out_.data() + at; p < to; ++p, ++line)
          if (!(p = static_cast<const char*>(std::memchr(p, '\n', size_t(to - p))))) break;
        at = std::max(at, size_t(to - out_.data()));
        return uint32_t(line);
      };
      for (const auto& [from, to] : spans) {
        const uint32_t first = line_of(from);
        stats_->run_lines.emplace_back(first, to > from ? line_of(to - 1) : first);
      }
    }
    return std::move(out_);
  }

 private:
  /// Copies a block as it is, restating the motion word when the output's modal motion
  /// differs from the input's at this point (after a run that ended in G2/G3), and, where
  /// I/J/K set a centre that holds, the program's centre in an arc that turns about it after
  /// arcpress's own arcs moved it (restate_pole_for_copy()), and, where a code turns as the
  /// last programmed arc did, the program's way in its stead after arcpress's own arcs
  /// (spell_turn_for_copy()).
  void copy_block(const Block& b) {
    if (in_motion_ >= 0 && in_motion_ != out_motion_) [[unlikely]] restate_before_flow(b);
    std::string_view raw = p_.raw(b);
    const std::string centre = d().centre_modal ? restate_pole_for_copy(b) : std::string();
    int shift_at = 0, shift = 0;  // columns past shift_at move by shift in the spelled text
    const bool spelled = !d().last_turn.empty() && spell_turn_for_copy(b, spelled_, shift_at);
    if (spelled) {
      shift = int(spelled_.size()) - int(raw.size());
      raw = spelled_;
    }
    auto col_of = [&](const Word& w) { return size_t(int(w.col) + (int(w.col) > shift_at ? shift : 0)); };
    if (b.kind == BlockKind::Code) {
      state_centres_for_copy(b);
      int explicit_motion = -1;
      bool axes = false;
      const Word* n_word = nullptr;
      for (auto* w = p_.words_begin(b); w != p_.words_end(b); ++w) {
        // (A code the dialect reads its own way is no RS274 motion: own_motion_.)
        if (w->letter == 'G' && !w->is_expr && is_motion_gcode(w->value) &&
            (w->value < 3.5 || std::find(own_motion_.begin(), own_motion_.end(), w->code10()) == own_motion_.end()))
          explicit_motion = w->code10();
        if (sets_centre_mode(*w)) {
          header_done_ = true;  // the program sets the centre mode itself
          if (out_centres_ != CentresOut::Fixed)
            out_centres_ = w->code10() == 901 ? CentresOut::Absolute : CentresOut::Incremental;
        }
        if (moves_axis(w->letter)) axes = true;
        if (w->letter == 'N' && w == p_.words_begin(b)) n_word = w;
      }
      if (explicit_motion >= 0) in_motion_ = out_motion_ = explicit_motion;
      const bool motion_word = explicit_motion < 0 && axes && in_motion_ != out_motion_ && in_motion_ >= 0;
      if (motion_word || !centre.empty() || spelled) {
        const BlockStyle st = style_of(b);
        const Word& last = *(p_.words_end(b) - 1);
        const size_t tail = col_of(last) - 1 + last.length;  // just after the block's last word
        size_t from = 0;
        if (motion_word) {
          const size_t at = n_word ? col_of(*n_word) - 1 + n_word->length : col_of(*p_.words_begin(b)) - 1;
          out_.append(raw.substr(0, at));
          if (n_word) out_ += st.spaced ? " " : "";
          out_ += st.motion(in_motion_ / 10);
          if (!n_word && st.spaced) out_ += ' ';
          from = at;
          out_motion_ = in_motion_;
          if (stats_) ++stats_->motion_words_added;
        }
        out_.append(raw.substr(from, tail - from));
        if (!centre.empty()) {
          if (st.spaced) out_ += ' ';
          out_ += centre;
        }
        out_.append(raw.substr(tail));
        out_.append(p_.eol(b));
        return;
      }
    }
    if (stats_) stats_->copied.push_back({out_.size(), uint32_t(&b - p_.blocks.data())});
    out_.append(raw);
    out_.append(p_.eol(b));
  }

  std::string_view indent_of(const Block& b) const { return block_indent(p_, b); }
  BlockStyle style_of(const Block& b) const { return block_style(p_, b, habits_); }

  /// Where flow control may take the program elsewhere (a call, a return, a jump, a loop's end,
  /// the end of an indented block), the input's modal motion, which the output's arcs left
  /// otherwise, is written before block `b`: the blocks the program goes on to read it. (Not
  /// in inverse time, where a G1 needs its own F: the check refuses such runs instead.)
  [[gnu::noinline]] void restate_before_flow(const Block& b) {
    const Block* in_block = d().indented_blocks ? closes_indented(p_, b) : nullptr;
    if (!(b.kind == BlockKind::Control || b.kind == BlockKind::Macro || in_block || jumps_elsewhere(p_, b, d())) ||
        in_.frames[frame_at(uint32_t(&b - p_.blocks.data()))].inverse_time)
      return;
    const Block& before = &b > p_.blocks.data() && (&b - 1)->kind == BlockKind::Code ? *(&b - 1) : b;
    out_ += indent_of(in_block ? *in_block : b);  // (inside the block that ends: a loop runs it each time)
    out_ += style_of(before).motion(in_motion_ / 10);  // (styled as the move before, not as `o100 endsub`)
    end_block(out_);
    out_.append(p_.eol(b));
    out_motion_ = in_motion_;
    if (stats_) ++stats_->motion_words_added;
  }

  /// A new block for one primitive, composed apart from the modal state of the output
  /// before it: its text with the motion word, which is left out where no covered block
  /// states one and the output's modal motion is already the block's.
  struct Composed {
    std::string text;
    uint32_t motion_at = 0, motion_length = 0;  ///< the motion word (with the separator before it)
    int g = 1;                                  ///< 1, 2 or 3
    bool motion_written = false;
    bool loose = false;  ///< an arc whose printed centre could not keep its end tangents (PrintedArc::loose)
    bool centre_words = false;  ///< an arc printed with I/J/K (not R)
    bool with_motion(int out_motion) const { return motion_written || out_motion != g * 10; }
    /// The length of the block's text after output whose modal motion is `out_motion` (G ×10).
    size_t size(int out_motion) const { return text.size() - (with_motion(out_motion) ? 0 : motion_length); }
    void append_to(std::string& out, int out_motion) const {
      if (with_motion(out_motion)) {
        out += text;
        return;
      }
      out.append(text, 0, motion_at);
      out.append(text, motion_at + motion_length);
    }
  };

  /// Composes, on opt_.threads threads, the block of every primitive of every run that is
  /// not a single input move (see emit_run()); nothing where compose() finds none.
  void compose_all(const std::vector<Run>& runs, const std::vector<FitResult>& fits) {
    composed_.assign(runs.size(), {});
    std::atomic<size_t> next{0};
    run_workers(worker_count(opt_.threads, runs.size()), [&](size_t) {
      ArcScratch scratch;
      for (size_t r; (r = next.fetch_add(1)) < runs.size();) {
        const Run& run = runs[r];
        const Frame& fr = in_.frames[run.frame];
        std::vector<std::optional<Composed>>& out = composed_[r];
        out.resize(fits[r].prims.size());
        uint32_t a = 0;
        for (size_t i = 0; i < fits[r].prims.size(); ++i) {
          const Primitive& pr = fits[r].prims[i];
          if (pr.kind == Primitive::Kind::Arc || pr.end_vertex > a + 1) out[i] = compose(run, fr, a, pr, false, scratch);
          a = pr.end_vertex;
        }
      }
    });
  }

  void emit_run(const Run& run, const FitResult& fit, const std::vector<std::optional<Composed>>& composed) {
    if (stats_) {
      ++stats_->runs;
      stats_->moves_in += run.move_count;
    }
    const Frame& fr = in_.frames[run.frame];
    in_motion_ = 10;  // every input block of a run is a G1 move
    // A run fitted in another plane than the program's selects its plane before its first
    // arc and gives the program's back after its last block.
    const Plane own = in_.moves[run.first_move].plane;
    bool plane_selected = false;
    uint32_t a = 0;
    auto rule_joints = [&](uint32_t e) {  // the joints of a block the dialect's rules changed
      if (!stats_) return;
      stats_->rule_joints.push_back(run.first_move + a);
      stats_->rule_joints.push_back(run.first_move + e);
    };
    ArcScratch scratch;
    bool last_number_free = false;  // the last block's number, where its block took its first's (compose())
    for (size_t i = 0; i < fit.prims.size(); ++i) {
      const Primitive& pr = fit.prims[i];
      uint32_t e = pr.end_vertex;
      bool arc = pr.kind == Primitive::Kind::Arc;
      // The block as composed, or composed again without spaces where too long.
      const Composed* text = nullptr;
      std::optional<Composed> narrow;
      if (arc || e > a + 1) {
        const std::optional<Composed>& wide = composed[i];
        if (wide && wide->size(out_motion_) <= d().max_line_length) {
          text = &*wide;
        } else if (wide && (narrow = compose(run, fr, a, pr, true, scratch)) &&
                   narrow->size(out_motion_) <= d().max_line_length) {
          text = &*narrow;
        }
        if (!text && stats_) ++(arc ? stats_->arcs_unprintable : stats_->long_lines_kept);
        if (!text) rule_joints(e);
      }
      if (text) {
        if (arc) state_centres(fr.arc_absolute, in_.moves[run.first_move + a].block);
        if (arc && !header_done_ && !d().arc_header.empty()) {
          out_ += indent_of(p_.blocks[in_.moves[run.first_move + a].block]);
          out_ += d().arc_header;
          end_block(out_);
          out_.append(p_.eol(p_.blocks[in_.moves[run.first_move + a].block]));
          header_done_ = true;
        }
        if (arc && run.plane != own && !plane_selected) {
          write_plane(run, a, run.plane, number_taken(run, a, e) > a);
          plane_selected = true;
        }
        const Block& last = p_.blocks[in_.moves[run.first_move + e - 1].block];
        text->append_to(out_, out_motion_);
        out_.append(p_.eol(last));
        // Where I/J/K set a centre that holds (Heidenhain's pole), this arc's is now in force.
        if (arc && text->centre_words && d().centre_modal)
          pole_moved_ |= (1u << axes_of(run.plane).first) | (1u << axes_of(run.plane).second);
        if (arc) turn_moved_ = true;
        out_motion_ = arc ? (pr.ccw != flip(run.plane) ? 30 : 20) : 10;
        if (stats_) ++(arc ? stats_->arcs_out : stats_->lines_out);
        if (arc && text->loose) rule_joints(e);
        last_number_free = number_taken(run, a, e) < e - 1;
      } else {
        last_number_free = false;
        // The input's own blocks: always readable, always on the path.
        for (uint32_t k = a; k < e; ++k) {
          copy_block(p_.blocks[in_.moves[run.first_move + k].block]);
          if (stats_) ++stats_->lines_out;
        }
      }
      a = e;
    }
    if (plane_selected) write_plane(run, run.move_count - 1, own, last_number_free);
  }

  /// The move whose block number the block over moves [a, e) of `run` takes: the last one's;
  /// the one before it for a run's last block in another plane than the program's, whose
  /// last number the block after it that selects the program's plane again takes (write_plane()).
  uint32_t number_taken(const Run& run, uint32_t a, uint32_t e) const {
    return e - a >= 2 && e == run.move_count && run.plane != in_.moves[run.first_move].plane ? e - 2 : e - 1;
  }

  /// A block of its own selecting `plane` (G17/G18/G19), styled and ended like the run's
  /// block of move k, and with its block number where `numbered` (no block written takes it):
  /// a program that numbers its blocks numbers these too (Heidenhain ISO's).
  void write_plane(const Run& run, uint32_t k, Plane plane, bool numbered) {
    const Block& b = p_.blocks[in_.moves[run.first_move + k].block];
    out_ += indent_of(b);
    const BlockStyle st = style_of(b);
    if (const Word* n = p_.find(b, 'N'); numbered && n && n == p_.words_begin(b))
      out_ += p_.raw(b, *n), out_ += st.spaced ? " " : "";
    out_ += st.letter('G');
    out_ += std::to_string(plane_gcode(plane));
    end_block(out_);
    out_.append(p_.eol(b));
    if (stats_) ++stats_->plane_words_added;
  }

  const Dialect& d() const { return opt_.dialect; }
  /// True where the dialect's G2/G3 turn the other way than RS274's in this plane.
  bool flip(Plane pl) const { return d().zx_reversed && pl == Plane::ZX; }

  /// What printing one arc works on: the input points it replaces, its fitted centre.
  struct ArcScratch {
    std::vector<Vec3> pts;
    std::vector<double> e_rates;  // each replaced move's E per mm, where E moves
    double e_mm = 0;              // E over the arc
    Vec2 ideal{0, 0};
    std::vector<Vec3> flat_pts;
    std::vector<Vec2> chord_ends;
  };

  /// What the controller reads from one printed arc, checked against the input points.
  struct PrintedArc {
    std::string words;  ///< "I.. J.." or "R.."
    bool ok = false;
    bool loose = false;  ///< no centre the digits allow keeps the end tangents within the slack
  };

  /// The text of one block for primitive `pr` over run vertices a .. pr.end_vertex, or
  /// nothing when the arc cannot be printed so that the controller reads it inside the band.
  /// `compact`: no spaces between words (for short line limits).
  std::optional<Composed> compose(const Run& run, const Frame& fr, uint32_t a, const Primitive& pr, bool compact,
                                  ArcScratch& scratch) const {
    uint32_t e = pr.end_vertex;
    const Block& numbered = p_.blocks[in_.moves[run.first_move + number_taken(run, a, e)].block];
    BlockStyle st = style_of(p_.blocks[in_.moves[run.first_move + a].block]);
    st.keep_point = st.keep_point || d().decimal_point;
    const std::string sep = st.spaced && !compact ? " " : "";
    const NumberDigits& dig = d().digits(fr.unit_mm != 1.0);
    // The last word of each letter in the covered blocks, the decimals each letter uses,
    // and whether any covered block states its motion word.
    const Word* last_word[26] = {};
    const Block* last_block[26] = {};
    int decimals[26] = {};
    bool motion_written = false;
    for (uint32_t k = a; k < e; ++k) {
      const Block& b = p_.blocks[in_.moves[run.first_move + k].block];
      for (auto* w = p_.words_begin(b); w != p_.words_end(b); ++w) {
        // (A label, `LOOP1:`, or a keyword is no letter's word: the block's number, whether
        // jumps may enter it, is read elsewhere.)
        if (w->letter < 'A' || w->letter > 'Z') continue;
        int li = w->letter - 'A';
        last_word[li] = w;
        last_block[li] = &b;
        decimals[li] = std::max<int>(decimals[li], w->decimals);
        if (w->letter == 'G') motion_written = true;
      }
    }
    bool arc = pr.kind == Primitive::Kind::Arc;
    Composed out;
    out.g = arc ? (pr.ccw != flip(run.plane) ? 3 : 2) : 1;
    // Modal motion is not repeated where the input does not repeat it (see Composed).
    out.motion_written = motion_written;
    std::string& s = out.text;
    const std::string_view indent = indent_of(p_.blocks[in_.moves[run.first_move + a].block]);
    s = indent;
    if (const Word* n = p_.find(numbered, 'N'); n && n == p_.words_begin(numbered)) s += p_.raw(numbered, *n);
    out.motion_at = uint32_t(s.size());
    if (out.motion_at > indent.size()) s += sep;
    s += st.motion(out.g);
    out.motion_length = uint32_t(s.size()) - out.motion_at;
    const AxisValues& from = run.vertex(in_, a);
    const AxisValues& to = run.vertex(in_, e);
    // End point words, and the end point as the controller reads them (mm).
    AxisValues end = to;
    std::string axis_words, e_word;
    auto put_to = [&](std::string& dst, char letter, const std::string& text) {
      dst += sep;
      dst += st.letter(letter);
      dst += text;
    };
    auto axes = axes_of(run.plane);
    for (int ax = 0; ax < kAxisCount; ++ax) {
      char L = kAxisLetters[ax];
      std::string& dst = ax == kE ? e_word : axis_words;
      bool in_plane = arc && (ax == axes.first || ax == axes.second);
      const Word* w = last_word[L - 'A'];
      if (!w && !in_plane) continue;
      // An axis whose position is not known is never printed: the input's lines stay.
      if (!w && (in_.moves[run.first_move + a].unknown_axes >> ax) & 1u) return std::nullopt;
      bool relative = ax == kE ? fr.e_relative : !fr.absolute;
      double scale = kAxisIsLinear[ax] ? fr.unit_mm : 1.0;
      if (relative) {
        // Deltas of the input's own digits sum exactly at those digits: no drift.
        int dec = std::max(decimals[L - 'A'], 0);
        double delta = rounded((to[ax] - from[ax]) / scale, dec);
        put_to(dst, L, format_number(delta, NumberStyle{dec, true, st.keep_point, st.plus}));
        end[ax] = from[ax] + delta * scale;
      } else if (w) {
        dst += sep;
        dst += p_.raw(*last_block[L - 'A'], *w);  // the input's own text
      } else {
        // Not written in the covered blocks: the value from before (read from the input's
        // digits), printed with as many decimals as it has, so the end point stays where the
        // input puts it even where that is finer than the dialect's usual digits.
        double v = fr.to_program(ax, to[ax]);
        const int dec = std::max(own_decimals(v, kMaxDecimals), dig.max);
        v = rounded(v, dec);
        put_to(dst, L, format_number(v, NumberStyle{dec, true, st.keep_point, st.plus}));
        end[ax] = fr.to_mm(ax, v);
      }
    }
    s += axis_words;
    // A block that starts with its motion word leaves it out with the separator after it,
    // so a modal continuation starts with its first word (" X1" would not be the input's style).
    if (out.motion_at == indent.size() && s.size() > out.motion_at + out.motion_length &&
        s.compare(out.motion_at + out.motion_length, sep.size(), sep) == 0)
      out.motion_length += uint32_t(sep.size());
    if (arc) {
      PrintedArc c = print_centre(run, fr, a, pr, end, st, sep, scratch);
      if (!c.ok) return std::nullopt;
      out.loose = c.loose;
      out.centre_words = !c.words.empty() && c.words[0] != 'R' && c.words[0] != 'r';
      s += sep;
      s += c.words;
    }
    s += e_word;  // arc centre words come before E and F, as arc-fitting slicers write them
    // F and S (laser power on a feed move) as the covered blocks last state them: the run
    // holds one of each throughout (see extract_runs()).
    for (char L : {'F', 'S'})
      if (const Word* w = last_word[L - 'A']) {
        s += sep;
        s += p_.raw(*last_block[L - 'A'], *w);
      }
    end_block(s);
    return out;
  }

  /// Prints the centre (I/J/K or R) of arc `pr` from run vertex a to the printed end point
  /// `end` (mm), so that what the controller reads stays within the band and its rules.
  /// Tries the dialect's usual decimals, then more up to its maximum; at each, the rounded
  /// centre, then its grid neighbours nearest the bisector of the printed end points.
  PrintedArc print_centre(const Run& run, const Frame& fr, uint32_t a, const Primitive& pr, const AxisValues& end,
                          const BlockStyle& st, const std::string& sep, ArcScratch& scratch) const {
    PrintedArc out;
    auto axes = axes_of(run.plane);
    const AxisValues& from = run.vertex(in_, a);
    auto plane3 = [&](const AxisValues& v) { return Vec3(v[axes.first], v[axes.second], v[axes.normal]); };
    const Vec3 s3 = plane3(from), e3 = plane3(end);
    const Vec2 s2 = s3.head<2>(), e2 = e3.head<2>();
    const double chord = (e2 - s2).norm();
    if (chord < std::max(d().min_chord_mm, kLengthEpsMm)) return out;
    // The input points the arc replaces, for the band check.
    scratch.pts.clear();
    for (uint32_t k = a; k <= pr.end_vertex; ++k) scratch.pts.push_back(plane3(run.vertex(in_, k)));
    scratch.pts.back() = e3;
    // Their E per mm, where the arc extrudes.
    scratch.e_rates.clear();
    scratch.e_mm = std::abs(run.vertex(in_, pr.end_vertex)[kE] - from[kE]);
    for (uint32_t k = a; k < pr.end_vertex && opt_.extrusion_variance >= 0 && scratch.e_mm > 0; ++k) {
      const AxisValues &p = run.vertex(in_, k), &q = run.vertex(in_, k + 1);
      const double len = (Vec3(q[kX], q[kY], q[kZ]) - Vec3(p[kX], p[kY], p[kZ])).norm();
      if (len > kLengthEpsMm) scratch.e_rates.push_back(std::abs(q[kE] - p[kE]) / len);
    }

    const NumberDigits& dig = d().digits(fr.unit_mm != 1.0);
    const double unit = fr.unit_mm;
    // Where the controller takes I/J/K from: the start, or the program's origin.
    const bool offsets = d().centre == CentreReading::Absolute ? !fr.absolute : !fr.arc_absolute;
    const int first_dec = std::min(std::max(dig.centre, decimals_for_band(unit)), dig.max);
    const Vec2 ideal = pr.center;
    scratch.ideal = ideal;
    const double r_ideal = (s2 - ideal).norm();
    const double sweep_ideal = std::abs(ArcGeom::sweep_of(s3, e3, ideal, pr.ccw));
    bool use_radius = opt_.format == ArcFormat::Radius && d().radius_word &&
                      // R is ambiguous near a half circle and meaningless near a full one
                      std::abs(rad_to_deg(sweep_ideal) - 180.0) > 15.0 && rad_to_deg(sweep_ideal) < 345.0;

    // Program-unit reference point for the centre words.
    const Vec2 ref = offsets ? s2 : Vec2(fr.to_mm(axes.first, 0.0), fr.to_mm(axes.second, 0.0));
    // First only centres that keep the end tangents within the slack; when the digits allow
    // none, the arc is still better than the input's lines (which turn by far more).
    for (bool tangent : {true, false}) {
      for (int dec = first_dec; dec <= dig.max; ++dec) {
        const double step = std::pow(10.0, -dec);
        if (use_radius) {
          double R = rounded(r_ideal / unit, dec);
          for (double dr : {0.0, step, -step}) {
            double Rp = R + dr;
            if (Rp <= 0) continue;
            // The controller's centre from the printed R (as the model stage reads it).
            double h2 = Rp * unit * Rp * unit - chord * chord / 4;
            double h = h2 > 0 ? std::sqrt(h2) : 0.0;
            Vec2 n = left_normal((e2 - s2) / chord);
            bool big = sweep_ideal > kPi;
            double side = (pr.ccw ? 1.0 : -1.0) * (big ? -1.0 : 1.0);
            Vec2 c = (s2 + e2) / 2 + side * h * n;
            if (h2 < 0 || !acceptable(s3, e3, c, pr.ccw, tangent, scratch)) continue;
            std::string t = format_number(big ? -Rp : Rp, NumberStyle{dec, true, st.keep_point, st.plus});
            if (!digits_fit(t)) continue;
            out.words = st.letter('R') + t;
            out.ok = true;
            out.loose = !tangent;
            return out;
          }
          continue;
        }
        // Centre words: the rounded centre and its 8 neighbours on the printed grid.
        Vec2 v = (ideal - ref) / unit;
        Vec2 base(rounded(v.x(), dec), rounded(v.y(), dec));
        struct Cand {
          Vec2 w;
          double dr;
        };
        Cand cands[9];
        int n = 0;
        for (int i = -1; i <= 1; ++i)
          for (int j = -1; j <= 1; ++j) {
            Vec2 w(base.x() + i * step, base.y() + j * step);
            Vec2 c = ref + w * unit;
            cands[n++] = {w, std::abs((s2 - c).norm() - (e2 - c).norm())};
          }
        // The rounded centre first (closest to the fit), then its neighbours nearest the bisector.
        std::swap(cands[0], cands[4]);
        std::sort(cands + 1, cands + n, [](const Cand& x, const Cand& y) { return x.dr < y.dr; });
        for (int q = 0; q < n; ++q) {
          Vec2 c = ref + cands[q].w * unit;
          if (!acceptable(s3, e3, c, pr.ccw, tangent, scratch)) continue;
          std::string t1 = format_number(cands[q].w.x(), NumberStyle{dec, true, st.keep_point, st.plus});
          std::string t2 = format_number(cands[q].w.y(), NumberStyle{dec, true, st.keep_point, st.plus});
          if (!digits_fit(t1) || !digits_fit(t2)) continue;
          out.words = st.letter(char('I' + axes.first)) + t1 + sep + st.letter(char('I' + axes.second)) + t2;
          if (axes.first > axes.second)  // I before J before K, as controllers print them
            out.words = st.letter(char('I' + axes.second)) + t2 + sep + st.letter(char('I' + axes.first)) + t1;
          out.ok = true;
          out.loose = !tangent;
          return out;
        }
      }
    }
    return out;
  }

  /// Decimals for which rounding a centre by half a digit moves the arc by at most 1.5 %
  /// of the band (the fitter keeps 3 % back): 0.71 digit in the worst direction.
  int decimals_for_band(double unit_mm) const {
    return int(std::ceil(std::log10(unit_mm * 0.71 / (0.015 * opt_.band_mm))));
  }

  /// Whether an arc from s to e about c (as the controller reads the printed numbers) is one
  /// the controller runs as meant, inside the band of the input points scratch.pts.
  /// With `tangent`, also whether its end tangents are within the slack of the fitted arc's.
  bool acceptable(const Vec3& s, const Vec3& e, const Vec2& c, bool ccw, bool tangent, ArcScratch& scratch) const {
    double rs = (s.head<2>() - c).norm(), re = (e.head<2>() - c).norm();
    double dr = std::abs(rs - re);
    if (dr > d().radius_allowance_mm(rs)) return false;
    if (rs < d().min_radius_mm || rs > d().max_radius_mm) return false;
    ArcGeom g = ArcGeom::through(s, e, c, ccw);
    double sweep_deg = rad_to_deg(std::abs(g.sweep));
    if (sweep_deg < d().min_sweep_deg || sweep_deg > d().max_sweep_deg + 1e-9) return false;
    if (rs * std::abs(g.sweep) < d().min_arc_length_mm) return false;
    // The moves it replaces keep their E per mm, which the printed arc's length sets.
    if (!scratch.e_rates.empty()) {
      const double len = std::hypot(rs * g.sweep, g.h1 - g.h0);
      const double rate = len > kLengthEpsMm ? scratch.e_mm / len : 0.0;
      for (const double r : scratch.e_rates)
        if (std::abs(r - rate) > opt_.extrusion_variance * std::max(r, rate)) return false;
    }
    // The firmware must be able to count the chords it cuts the arc into.
    if (d().executed.moves_on_chords() && executed_segments(d().executed, rs, g.sweep, g.h1 - g.h0) >= kMaxArcSegments)
      return false;
    // Rounding the centre turns the arc's radii at its ends, and with them its tangents.
    for (const Vec3* p : {&s, &e}) {
      if (!tangent) break;
      Vec2 printed = p->head<2>() - c, fitted = p->head<2>() - scratch.ideal;
      if (std::atan2(std::abs(cross2(printed, fitted)), printed.dot(fitted)) > tangent_slack_rad_) return false;
    }
    // The controller ends on the printed end point: a spiral or a jump of at most dr. (Held
    // inside the band by what reading the program back may misread, kReadingShare.)
    const double band_mm = opt_.band_mm * (1 - kReadingShare);
    Deviation dev = arc_deviation(scratch.pts, g, band_mm - dr);
    if (!dev.ordered || dev.max_mm > band_mm - dr) return false;
    return chords_kept(s, e, c, g, band_mm - dr, scratch);
  }

  /// Where the band is held on the firmware's chords, whether the chords of the printed arc,
  /// cut from the printed numbers as the firmware cuts them, stay within `band_mm` of the
  /// input points in the plane (all counts from it up where it may cut more: ring_deviation()).
  /// Rounding the centre moves the fitted arc's chords and can change their number (two
  /// chords where the fit had three lie twice as far off the circle), and small-angle steps
  /// pull them off the circle by more than the sagitta says: they are measured again.
  bool chords_kept(const Vec3& s, const Vec3& e, const Vec2& c, const ArcGeom& g, double band_mm,
                   ArcScratch& scratch) const {
    if (!opt_.executed.moves_on_chords()) return true;
    const uint32_t chords = executed_segments_read(opt_.executed, s.head<2>(), c, e.head<2>(), g.sweep, g.h1 - g.h0);
    scratch.chord_ends.clear();
    executed_chord_ends(opt_.executed, s.head<2>(), c, e.head<2>(), g.sweep, chords, scratch.chord_ends);
    scratch.flat_pts.assign(scratch.pts.begin(), scratch.pts.end());
    for (Vec3& p : scratch.flat_pts) p.z() = g.h0;
    ArcGeom flat = g;
    flat.h1 = g.h0;
    if (opt_.executed.count_may_grow()) {  // (every count from this one up: the ring about the circle)
      const Deviation d = ring_deviation(opt_.executed, scratch.flat_pts, flat, scratch.chord_ends, band_mm);
      return d.ordered && d.max_mm <= band_mm;
    }
    const std::optional<double> bound = chords_deviation_bound(scratch.flat_pts, flat, scratch.chord_ends, band_mm);
    return bound && *bound <= band_mm;
  }

  /// The dialect's limit on significant digits in one number.
  bool digits_fit(const std::string& t) const {
    if (d().max_significant_digits <= 0) return true;
    int n = 0;
    bool leading = true;
    for (char ch : t) {
      if (ch < '0' || ch > '9') continue;
      if (leading && ch == '0') continue;
      leading = false;
      ++n;
    }
    return n <= d().max_significant_digits;
  }

  const Program& p_;
  const Interpretation& in_;
  EmitStats* stats_;
  const EmitOptions& opt_;
  std::vector<std::vector<std::optional<Composed>>> composed_;  // per run and primitive: compose_all()
  double tangent_slack_rad_ = deg_to_rad(opt_.tangent_slack_deg);
  bool header_done_ = false;  // the dialect's arc header is written, or the program set the mode
  /// What the output has said of the I/J/K mode, where a setting of the controller's decides it
  /// (Dialect::start_centres Machine): nothing (the setting holds), maybe something (an earlier
  /// piece's G91.1), G90.1 or G91.1. Elsewhere the program's words alone say it.
  enum class CentresOut : uint8_t { Fixed, Setting, Unknown, Absolute, Incremental };
  CentresOut out_centres_ = CentresOut::Fixed;

  /// Before an arc the output writes, read with `absolute` I/J/K: the mode word, unless the
  /// output already stands so.
  void state_centres(bool absolute, uint32_t block) {
    if (out_centres_ == CentresOut::Fixed) return;
    const CentresOut need = absolute ? CentresOut::Absolute : CentresOut::Incremental;
    if (out_centres_ == need) return;
    out_ += indent_of(p_.blocks[block]);
    out_ += absolute ? "G90.1" : "G91.1";
    end_block(out_);
    out_.append(p_.eol(p_.blocks[block]));
    out_centres_ = need;
  }
  /// Before the program's own I/J/K arc, copied: where the output said another mode than the
  /// one it is read in, or may have (an earlier piece's), the mode it is read in. Where
  /// nothing was said, the setting holds, which is how it is read.
  void state_centres_for_copy(const Block& b) {
    if (out_centres_ == CentresOut::Fixed || out_centres_ == CentresOut::Setting) return;
    const uint32_t bi = uint32_t(&b - p_.blocks.data());
    const int32_t mi = bi < in_.move_of_block.size() ? in_.move_of_block[bi] : -1;
    if (mi < 0) return;
    const Move& m = in_.moves[size_t(mi)];
    if (!is_arc(m.kind) || !has_centre_words(b)) return;
    const bool absolute = in_.frames[m.frame].arc_absolute;
    // After an earlier piece, only a reading the setting was found to differ from can need it.
    if (out_centres_ == CentresOut::Unknown && !absolute) return;
    state_centres(absolute, bi);
  }
  /// Where I/J/K set a centre that holds (Dialect::centre_modal) and arcs arcpress wrote have
  /// moved it: before a copied block that turns about it, the program's centre stated again.
  /// An arc without centre words takes them itself (returned, for copy_block() to put after
  /// its last word: the block then says what it did); before a polar move, or a line not read
  /// (which may be one), they go in a block of their own. A copied block that sets the centre
  /// makes it the program's again.
  std::string restate_pole_for_copy(const Block& b) {
    const uint32_t bi = uint32_t(&b - p_.blocks.data());
    const auto& reads = in_.pole_reads;
    std::string words;
    while (pole_next_ < reads.size() && reads[pole_next_].block < bi) ++pole_next_;
    if (pole_next_ < reads.size() && reads[pole_next_].block == bi && reads[pole_next_].known) {
      const PoleRead& r = reads[pole_next_];
      const auto a = axes_of(r.plane);
      const uint32_t bits = (1u << a.first) | (1u << a.second);
      if (pole_moved_ & bits) {
        const BlockStyle st = style_of(b);
        const NumberDigits& dig = d().digits(in_.frames[frame_at(bi)].unit_mm != 1.0);
        for (int k : {a.first, a.second}) {
          const int dec = own_decimals(r.words[k], dig.max);  // up to the most the controller reads
          if (!words.empty() && st.spaced) words += ' ';
          words += st.letter(char('I' + k));
          words += format_number(r.words[k], NumberStyle{dec, true, st.keep_point, st.plus});
        }
        pole_moved_ &= ~bits;
        if (stats_) ++stats_->poles_restated;
        if (!r.arc) {
          out_ += indent_of(b);
          out_ += words;
          end_block(out_);
          out_.append(p_.eol(b));
          words.clear();
        }
      }
    }
    for (auto* w = p_.words_begin(b); w != p_.words_end(b); ++w) {
      if ((w->letter == 'I' || w->letter == 'J' || w->letter == 'K') && !w->flag) pole_moved_ &= ~(1u << (w->letter - 'I'));
      if (w->letter == 'G' && !w->is_expr)
        if (const CodeMeaning* m = d().meaning_of('G', w->code10()); m && *m == CodeMeaning::Pole) pole_moved_ = 0;
    }
    return words;
  }
  /// Where a code turns as the last programmed arc did (Dialect::last_turn) and arcpress's
  /// own arcs came between since the program last set the way: block `b`'s text with that
  /// code spelled as the program's way (G05 -> G02 after the program's G02), in `text`, the
  /// code's column in `at`; false where it stays as it is. A block that sets the way makes it
  /// the program's again.
  bool spell_turn_for_copy(const Block& b, std::string& text, int& at) {
    const uint32_t bi = uint32_t(&b - p_.blocks.data());
    const auto& reads = in_.turn_reads;
    while (turn_next_ < reads.size() && reads[turn_next_].block < bi) ++turn_next_;
    bool spelled = false;
    if (turn_moved_ && turn_next_ < reads.size() && reads[turn_next_].block == bi && reads[turn_next_].turn != 0) {
      const std::string_view raw = p_.raw(b);
      for (auto* w = p_.words_begin(b); w != p_.words_end(b); ++w) {
        if (w->letter != 'G' || w->is_expr) continue;
        const TurnReading* t = d().turn_reading(w->code10());
        if (!t) continue;
        // The code as the program writes its own: its letter's case, and as many digits.
        const std::string_view word = raw.substr(w->col - 1, w->length);
        const int code10 = reads[turn_next_].turn == 2 ? t->cw10 : t->ccw10;
        const int digits = int(std::count_if(word.begin(), word.end(), [](char c) { return c >= '0' && c <= '9'; }));
        const std::string code = code10 % 10 ? fmt::format("{}.{}", code10 / 10, code10 % 10)
                                             : fmt::format("{:0{}}", code10 / 10, std::max(1, digits));
        text.assign(raw.substr(0, w->col - 1));
        text += word[0];
        text += code;
        text.append(raw.substr(w->col - 1 + w->length));
        at = int(w->col);
        spelled = true;
        if (stats_) ++stats_->turns_spelled;
        break;
      }
    }
    for (auto* w = p_.words_begin(b); w != p_.words_end(b); ++w)
      if (w->letter == 'G' && !w->is_expr && d().turn_set_by(w->code10())) turn_moved_ = false;
    if (spelled) turn_moved_ = false;
    return spelled;
  }
  /// The frame in force at block `bi`: its move's, else the nearest move's before it.
  uint32_t frame_at(uint32_t bi) const {
    for (uint32_t k = bi + 1; k-- > 0;)
      if (k < in_.move_of_block.size() && in_.move_of_block[k] >= 0) return in_.moves[size_t(in_.move_of_block[k])].frame;
    return 0;
  }
  bool has_centre_words(const Block& b) const {
    for (auto* w = p_.words_begin(b); w != p_.words_end(b); ++w)
      if ((w->letter == 'I' || w->letter == 'J' || w->letter == 'K') && !w->flag) return true;
    return false;
  }
  std::string out_;
  OutputHabits habits_;
  uint32_t pole_moved_ = 0;  ///< axes (X/Y/Z bits) of the centre in force that arcpress's own arcs moved (centre_modal)
  size_t pole_next_ = 0;     ///< the next of in_.pole_reads to reach
  /// arcpress's own arcs may have turned the other way since the program last set the way
  /// that codes of Dialect::last_turn read.
  bool turn_moved_ = false;
  size_t turn_next_ = 0;     ///< the next of in_.turn_reads to reach
  /// RS274's motion codes the dialect reads its own way (Fanuc's G05.1: a setting), which
  /// are no motion word here; not those that turn as the last arc did (Heidenhain's G05).
  /// G0 to G3 are always RS274's.
  std::vector<int> own_motion_;
  std::string spelled_;  ///< a copied block's text with its code spelled (spell_turn_for_copy())
  bool block_end_ = false;  ///< new blocks end with " *"
  /// The end of a block arcpress writes: " *" where the program's blocks end so.
  void end_block(std::string& s) const {
    if (block_end_) s += " *";
  }
  int in_motion_ = 0;   // modal motion (G ×10) as the input program has it here
  int out_motion_ = 0;  // ... and as the output program has it
};

}  // namespace

std::string emit_program(const Program& program, const Interpretation& in, const std::vector<Run>& runs,
                         const std::vector<FitResult>& fits, const EmitOptions& options, EmitStats* stats) {
  return Emitter(program, in, options, stats).run(runs, fits);
}

}  // namespace arcpress
