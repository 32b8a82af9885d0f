#include "arcpress/emit/emitter.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "arcpress/emit/number_format.hpp"

namespace arcpress {
namespace {

bool is_motion_gcode(double v) {
  int g = int(std::lround(v * 10));
  return g == 0 || g == 10 || g == 20 || g == 30 || (g >= 50 && g <= 53) || g == 330 || g == 331 ||
         (g >= 382 && g <= 385) || g == 730 || g == 760 || (g >= 800 && g <= 890 && g % 10 == 0);
}

bool moves_axis(char letter) {
  return std::string_view("XYZABCUVWE").find(letter) != std::string_view::npos;
}

/// How the input writes its blocks, so new blocks look like their neighbours.
struct BlockStyle {
  bool lower = false;
  bool spaced = true;
  bool padded = false;  ///< G01 rather than G1
  bool keep_point = false;

  std::string letter(char c) const { return std::string(1, lower ? char(c + 32) : c); }
  std::string motion(int g) const { return fmt::format("{}{}{}", letter('G'), padded ? "0" : "", g); }
};

class Emitter {
 public:
  Emitter(const Program& p, const Interpretation& in, double band_mm, EmitStats* stats)
      : p_(p), in_(in), stats_(stats), band_mm_(band_mm) {
    out_.reserve(p.text.size());
    detect_padding();
  }

  std::string run(const std::vector<Run>& runs, const std::vector<FitResult>& fits) {
    size_t r = 0;
    for (size_t bi = 0; bi < p_.blocks.size(); ++bi) {
      if (r < runs.size() && in_.moves[runs[r].first_move].block == bi) {
        emit_run(runs[r], fits[r]);
        bi = in_.moves[runs[r].first_move + runs[r].move_count - 1].block;
        ++r;
        continue;
      }
      copy_block(p_.blocks[bi]);
    }
    return std::move(out_);
  }

 private:
  /// Program-wide habits: G01 or G1, and whole numbers written as "1." or "1".
  void detect_padding() {
    size_t padded = 0, plain = 0, whole_point = 0, whole_bare = 0;
    for (const auto& b : p_.blocks) {
      for (auto* w = p_.words_begin(b); w != p_.words_end(b); ++w)
        if (moves_axis(w->letter) && w->decimals == 0 && !w->is_expr && !w->flag) (w->has_point ? whole_point : whole_bare)++;
    }
    keep_point_ = whole_point > 0 && whole_bare == 0;
    for (const auto& b : p_.blocks) {
      for (auto* w = p_.words_begin(b); w != p_.words_end(b); ++w) {
        if (w->letter != 'G' || w->is_expr || !is_motion_gcode(w->value)) continue;
        auto t = p_.raw(b, *w);
        (t.size() >= 3 && t[1] == '0' && t[2] >= '0' && t[2] <= '3') ? ++padded : ++plain;
      }
      if (padded + plain > 200) break;
    }
    padded_ = padded > plain;
  }

  /// Copies a block as it is, restating the motion word when the output's modal motion
  /// differs from the input's at this point (after a run that ended in G2/G3).
  void copy_block(const Block& b) {
    std::string_view raw = p_.raw(b);
    if (b.kind == BlockKind::Code) {
      int explicit_motion = -1;
      bool axes = false;
      const Word* n_word = nullptr;
      for (auto* w = p_.words_begin(b); w != p_.words_end(b); ++w) {
        if (w->letter == 'G' && !w->is_expr && is_motion_gcode(w->value)) explicit_motion = int(std::lround(w->value * 10));
        if (moves_axis(w->letter)) axes = true;
        if (w->letter == 'N' && w == p_.words_begin(b)) n_word = w;
      }
      if (explicit_motion >= 0) {
        in_motion_ = out_motion_ = explicit_motion;
      } else if (axes && in_motion_ != out_motion_ && in_motion_ >= 0) {
        size_t at = n_word ? n_word->col - 1 + n_word->length : p_.words_begin(b)->col - 1;
        BlockStyle st = style_of(b);
        std::string word = st.motion(in_motion_ / 10);
        out_.append(raw.substr(0, at));
        if (n_word) out_ += st.spaced ? " " : "";
        out_ += word;
        if (!n_word && st.spaced) out_ += ' ';
        out_.append(raw.substr(at));
        out_.append(p_.eol(b));
        out_motion_ = in_motion_;
        if (stats_) ++stats_->motion_words_added;
        return;
      }
    }
    out_.append(raw);
    out_.append(p_.eol(b));
  }

  BlockStyle style_of(const Block& b) const {
    BlockStyle s;
    s.padded = padded_;
    std::string_view raw = p_.raw(b);
    for (char c : raw) {
      if (c >= 'a' && c <= 'z') {
        s.lower = true;
        break;
      }
      if (c >= 'A' && c <= 'Z') break;
    }
    s.spaced = b.word_count < 2 || p_.words_begin(b)[1].col - 1 > p_.words_begin(b)[0].col - 1 + p_.words_begin(b)[0].length;
    s.keep_point = keep_point_;
    for (auto* w = p_.words_begin(b); w != p_.words_end(b); ++w) {
      if (w->letter == 'G' && !w->is_expr && is_motion_gcode(w->value)) {
        auto t = p_.raw(b, *w);
        s.padded = t.size() >= 3 && t[1] == '0';
        break;
      }
    }
    return s;
  }

  void emit_run(const Run& run, const FitResult& fit) {
    if (stats_) {
      ++stats_->runs;
      stats_->moves_in += run.move_count;
    }
    const Frame& fr = in_.frames[run.frame];
    in_motion_ = 10;  // every input block of a run is a G1 move
    uint32_t a = 0;
    for (const Primitive& pr : fit.prims) {
      uint32_t e = pr.end_vertex;
      if (pr.kind == Primitive::Kind::Line && e == a + 1) {
        copy_block(p_.blocks[in_.moves[run.first_move + a].block]);
        if (stats_) ++stats_->lines_out;
      } else {
        new_block(run, fr, a, pr);
      }
      a = e;
    }
  }

  /// Writes one block for primitive `pr` covering run vertices a .. pr.end_vertex.
  void new_block(const Run& run, const Frame& fr, uint32_t a, const Primitive& pr) {
    uint32_t e = pr.end_vertex;
    const Block& last = p_.blocks[in_.moves[run.first_move + e - 1].block];
    BlockStyle st = style_of(p_.blocks[in_.moves[run.first_move + a].block]);
    std::string sep = st.spaced ? " " : "";
    // The last word of each letter in the covered blocks, and the decimals each letter uses.
    const Word* last_word[26] = {};
    const Block* last_block[26] = {};
    int decimals[26] = {};
    for (uint32_t k = a; k < e; ++k) {
      const Block& b = p_.blocks[in_.moves[run.first_move + k].block];
      for (auto* w = p_.words_begin(b); w != p_.words_end(b); ++w) {
        int li = w->letter - 'A';
        last_word[li] = w;
        last_block[li] = &b;
        decimals[li] = std::max<int>(decimals[li], w->decimals);
      }
    }
    std::string s;
    if (const Word* n = p_.find(last, 'N'); n && n == p_.words_begin(last)) {
      s += p_.raw(last, *n);
      s += sep;
    }
    bool arc = pr.kind == Primitive::Kind::Arc;
    int g = arc ? (pr.ccw ? 3 : 2) : 1;
    s += st.motion(g);
    out_motion_ = g * 10;
    const AxisValues& from = run.vertex(in_, a);
    const AxisValues& to = run.vertex(in_, e);
    auto axes = axes_of(run.plane);
    auto put = [&](char letter, const std::string& text) {
      s += sep;
      s += st.letter(letter);
      s += text;
    };
    for (int ax = 0; ax < kAxisCount; ++ax) {
      char L = kAxisLetters[ax];
      if (ax == kE) {
        // Arc centre words come before E and F, as arc-fitting slicers write them.
        if (arc) {
          int cd = 0;
          for (int k = 0; k < 3; ++k) cd = std::max(cd, decimals[kAxisLetters[k] - 'A']);
          // Rounding a centre by half a digit moves the arc by up to 0.71 digit (in mm);
          // keep that under 1.5 % of the band.
          int for_band = int(std::ceil(std::log10(fr.unit_mm * 0.71 / (0.015 * band_mm_))));
          cd = std::clamp(std::max(cd + 1, for_band), fr.unit_mm == 1.0 ? 3 : 4, 8);
          NumberStyle ns{cd, true, st.keep_point};
          Vec2 c = pr.center;
          double cx[3] = {0, 0, 0};
          cx[axes.first] = c.x();
          cx[axes.second] = c.y();
          for (int k = 0; k < 3; ++k) {
            if (k == axes.normal) continue;
            double v = fr.arc_absolute ? fr.to_program(k, cx[k]) : (cx[k] - from[k]) / fr.unit_mm;
            put(char('I' + k), format_number(v, ns));
          }
        }
      }
      bool in_plane = arc && (ax == axes.first || ax == axes.second);
      const Word* w = last_word[L - 'A'];
      if (!w && !in_plane) continue;
      bool relative = ax == kE ? fr.e_relative : !fr.absolute;
      NumberStyle ns{decimals[L - 'A'], true, st.keep_point};
      if (relative) {
        double d = (to[ax] - from[ax]) / (kAxisIsLinear[ax] ? fr.unit_mm : 1.0);
        put(L, format_number(d, ns));
      } else if (w) {
        auto raw = p_.raw(*last_block[L - 'A'], *w);
        s += sep;
        s += raw;  // the input's own text for this value
      } else {
        // Not written in the covered blocks: the value from before, printed exactly.
        put(L, format_number(fr.to_program(ax, to[ax]), NumberStyle{6, true, st.keep_point}));
      }
    }
    if (const Word* f = last_word['F' - 'A']) {
      s += sep;
      s += p_.raw(*last_block['F' - 'A'], *f);
    }
    out_ += s;
    out_.append(p_.eol(last));
    if (stats_) ++(arc ? stats_->arcs_out : stats_->lines_out);
  }

  const Program& p_;
  const Interpretation& in_;
  EmitStats* stats_;
  double band_mm_;
  std::string out_;
  bool padded_ = false;
  bool keep_point_ = false;
  int in_motion_ = 0;   // modal motion (G ×10) as the input program has it here
  int out_motion_ = 0;  // ... and as the output program has it
};

}  // namespace

std::string emit_program(const Program& program, const Interpretation& in, const std::vector<Run>& runs,
                         const std::vector<FitResult>& fits, double band_mm, EmitStats* stats) {
  return Emitter(program, in, band_mm > 0 ? band_mm : 0.01, stats).run(runs, fits);
}

}  // namespace arcpress
