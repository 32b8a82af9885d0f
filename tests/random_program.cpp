// SPDX-License-Identifier: GPL-3.0-or-later
#include "random_program.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <utility>
#include <vector>

#include "arcpress/core/error.hpp"
#include "arcpress/dialect/dialect_loader.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"

namespace arcpress::test {

RandomCase random_case(std::span<const uint8_t> bytes) {
  RandomCase c;
  const uint8_t o = bytes.size() > 0 ? bytes[0] : 0, form = bytes.size() > 1 ? bytes[1] : 0;
  FitOptions& f = c.opt.fit;
  const double tolerances_mm[] = {0.01, 0.001, 0.05, 0.002};
  f.tolerance_mm = tolerances_mm[o & 3];
  const FitOptions::Method methods[] = {FitOptions::Method::Arcs,   FitOptions::Method::Global,
                                        FitOptions::Method::Greedy, FitOptions::Method::Stream,
                                        FitOptions::Method::Lowe,   FitOptions::Method::Arcs};
  f.method = methods[((o >> 2) & 7) % 6];
  f.helical = (o >> 5) & 1;
  f.min_radius_mm = (o >> 6) & 1 ? 0.0 : 0.05;
  f.spikes = (o >> 7) & 1;
  c.opt.threads = 1;
  // The third byte: the controller (every shipped dialect, or the built-in RS274), and
  // R-form arcs where it reads them.
  const uint8_t target = bytes.size() > 2 ? bytes[2] : 0;
  static const std::vector<Dialect> dialects = list_dialects(dialect_search_path(""));
  if (const size_t pick = target % (dialects.size() + 1); pick > 0) c.opt.dialect = dialects[pick - 1];
  if ((target & 0x80) && c.opt.dialect.radius_word) c.opt.arc_format = ArcFormat::Radius;

  const char* planes[] = {"G17", "G18", "G19", "G17"};
  const double steps_mm[] = {0.01, 0.1, 1.0, 0.003};  // the size of one step
  const double step_mm = steps_mm[form & 3];
  const int decimals = (form >> 2) & 1 ? 3 : 4;
  const bool smooth = (form >> 5) & 1, flat = (form >> 6) & 1, extrudes = (form >> 7) & 1;
  // A flat path whose height wanders by up to 0.35 of the band either way, as a rotated
  // frame or a digitiser prints it: sometimes within what a helical arc carries, sometimes not.
  const bool wander = flat && (target & 0x40);
  std::string& s = c.text;
  s = fmt::format("G21 G90 {}{}\nG0 X0 Y0 Z0\nG1 F1000\n", planes[(form >> 3) & 3], extrudes ? " M83" : "");
  // For Heidenhain ISO, as its programs are written: the units in a program name block, every
  // block numbered and ended with '*', numbers signed (X+1.5).
  const bool tnc = c.opt.dialect.name == "heidenhain-iso";
  if (tnc)
    s = fmt::format("%RANDOM G71 *\nN1 G90 {} *\nN2 G00 X+0 Y+0 Z+0 *\nN3 G01 F1000 *\n", planes[(form >> 3) & 3]);
  double x = 0, y = 0, z = 0, hx = 1, hy = 0;
  double e_per_mm = 0.05;  // relative extrusion (M83), its rate changing now and then
  double last_x = 0, last_y = 0;  // the last printed point, for the extrusion of a move
  bool rotary = false;             // moves carry an A word
  long numbered = 0;               // the number of the last move written with one (0: none)
  std::string indent;              // of the moves in an `if` block
  long sub_label = 0;              // of the subroutine being defined (0: none)
  const char* loop_end = nullptr;  // the line that ends the loop of blocks open (none: null)
  for (size_t i = 3; i + 2 < bytes.size(); i += 3) {
    const auto a = static_cast<int8_t>(bytes[i]), b = static_cast<int8_t>(bytes[i + 1]),
               h = static_cast<int8_t>(bytes[i + 2]);
    if (smooth) {  // the heading turns by up to 0.3 rad, the step keeps its scale
      const double t = a / 128.0 * 0.3;
      const double nx = hx * std::cos(t) - hy * std::sin(t), ny = hx * std::sin(t) + hy * std::cos(t);
      hx = nx;
      hy = ny;
      const double len = (static_cast<uint8_t>(b) / 255.0 + 0.05) * step_mm * 10;
      x += hx * len;
      y += hy * len;
      if (!flat) z += h / 128.0 * step_mm * 0.1;
    } else {
      x += a / 128.0 * step_mm * 10;
      y += b / 128.0 * step_mm * 10;
      if (!flat) z += h / 128.0 * step_mm;
    }
    if (wander) z = ((h & 7) - 3.5) / 3.5 * 0.35 * f.tolerance_mm;
    // Now and then a block that is no move: runs end there, and are fitted as one chain.
    if ((h & 0x3f) == 0x21) s += "(note)\n";
    if ((h & 0x3f) == 0x22) s += fmt::format("G1 F{}\n", 500 + (i % 7) * 100);
    // A printer's own macro: the position is unknown until the next move sets every axis,
    // and that move's E is the sum of the relative E words before it.
    if ((h & 0x3f) == 0x27) s += "CLEAN_NOZZLE\n";
    // From here on a rotary axis turns with the path, faster and slower (a 4th-axis wrap).
    if ((h & 0x3f) == 0x28) rotary = true;
    // A tool change, a tool length offset, a move in polar coordinates: each leaves the
    // position to be read anew from the next move, which sets every axis.
    if ((h & 0x3f) == 0x29) s += "T2 M6\n";
    if ((h & 0x3f) == 0x2a) s += "G43 H2\n";
    if ((h & 0x3f) == 0x2b) s += fmt::format("G16\nG1 X{:.3f} Y{:.1f}\nG15\n", std::hypot(x, y), 30.0 + i % 90);
    // Heidenhain ISO in G17: an arc of the program's (half a circle about an absolute centre,
    // which sets the way G05 turns), or a G05 (a quarter circle of radius R, turning that way).
    if (tnc && ((form >> 3) & 3) % 3 == 0 && ((h & 0x3f) == 0x2c || (h & 0x3f) == 0x2d)) {
      const double r = step_mm * 5;
      if ((h & 0x3f) == 0x2c)
        s += fmt::format("N{} G0{} X{:+.{}f} Y{:+.{}f} I{:+.{}f} J{:+.{}f} *\n", i, a < 0 ? 2 : 3, last_x + 2 * r,
                         decimals, last_y, decimals, last_x + r, decimals, last_y, decimals);
      else
        s += fmt::format("N{} G05 X{:+.{}f} Y{:+.{}f} R{:+.{}f} *\n", i, last_x + 2 * r, decimals, last_y + 2 * r,
                         decimals, 2 * r, decimals);
    }
    // The Sinumerik language: a line of path settings (keywords, read as words of their
    // block), and a tangential arc CT, which goes on from the move before it.
    if (c.opt.dialect.name == "sinumerik" && (h & 0x3f) == 0x2e) s += "G642 SOFT FFWON ADIS=0.05\n";
    if (c.opt.dialect.name == "sinumerik" && (h & 0x3f) == 0x2f)
      s += fmt::format("CT X{:.3f} Y{:.3f}\n", last_x + step_mm * 5, last_y - step_mm * 3);
    // A jump back to a numbered move (a loop), whose block must stay one, and G90 stated
    // again, after which the moves are placed again.
    // (After a call of O9000 where it leaves G18 or is not in the file, or after a LinuxCNC
    // call, whose body a dialect that reads no O-words does not read, the lines after the
    // number run again in another plane than they were read in, or one not known: they are
    // then written as they are, W-FLOW-LOOP-MODES.)
    if (!tnc && (h & 0x3f) == 0x31 && numbered > 0)
      s += a < 0 ? fmt::format("IF [#1 LT 2] GOTO {}\n", numbered) : fmt::format("M99 P{}\n", numbered);
    if (!tnc && (h & 0x3f) == 0x32) s += extrudes ? "G90 M83\n" : "G90\n";  // (G90 alone makes E absolute)
    // An `if` whose moves are indented below it (RepRapFirmware's blocks) and the line that
    // ends it; a LinuxCNC subroutine's definition around some moves, and its call.
    if (!tnc && (h & 0x3f) == 0x33) {
      if (indent.empty()) s += "if true\n";
      indent = indent.empty() ? "  " : "";
    }
    if (!tnc && (h & 0x3f) == 0x34 && !sub_label && !loop_end) s += fmt::format("o{} sub\n", sub_label = long(i));
    if (!tnc && (h & 0x3f) == 0x35 && sub_label)
      s += fmt::format("o{0} endsub\no{0} call\n", std::exchange(sub_label, 0));
    // A loop of blocks around some moves (Fanuc's WHILE .. DO1 .. END1, LinuxCNC's do ..
    // while), whose end may leave other modes than its first moves were read in: they are
    // then written as they are (W-FLOW-LOOP-MODES).
    if (!tnc && (h & 0x3f) == 0x37 && !sub_label) {
      if (loop_end) s += std::exchange(loop_end, nullptr);
      else s += a < 0 ? "WHILE [#1 LT 2] DO1\n" : "o9 do\n", loop_end = a < 0 ? "END1\n" : "o9 while [#1 LT 2]\n";
    }
    // A call of a subprogram written after the program's end (or stored in the control): the
    // moves after it are read in the modes it leaves.
    if (!tnc && (h & 0x3f) == 0x36) s += a < 0 ? "M98 P9000 L2\n" : "M98 P9000\n";
    const bool number_it = !tnc && (h & 0x3f) == 0x30;
    if (number_it) numbered = long(i);
    const double px = std::stod(fmt::format("{:.{}f}", x, decimals)), py = std::stod(fmt::format("{:.{}f}", y, decimals));
    s += indent;
    if (number_it) s += fmt::format("N{} ", i);
    if (tnc)
      s += fmt::format("N{} G01 X{:+.{}f} Y{:+.{}f} Z{:+.{}f}", i + 1, x, decimals, y, decimals, z, decimals);
    else
      s += fmt::format("G1 X{:.{}f} Y{:.{}f} Z{:.{}f}", x, decimals, y, decimals, z, decimals);
    if (rotary) s += fmt::format(" A{:.3f}", 10 * x + 3 * std::sin(y));
    if (extrudes && !tnc) {
      if ((h & 0x3f) == 0x23) e_per_mm *= 1.5;
      s += fmt::format(" E{:.5f}", e_per_mm * std::hypot(px - last_x, py - last_y));
    }
    s += tnc ? " *\n" : "\n";
    last_x = px;
    last_y = py;
  }
  if (sub_label) s += fmt::format("o{} endsub\n", sub_label);
  if (loop_end) s += loop_end;
  s += tnc ? fmt::format("N{} M2 *\nN99999999 %RANDOM G71 *\n", bytes.size() + 3) : "M2\n";
  // O9000 leaves G90, G91 or G18 where it returns, or is not in the file.
  const char* bodies[] = {"O9000\nG91 G1 X0.5\nG90\nM99\n", "O9000\nG91 G1 X0.5\nM99\n", "O9000\nG18 G1 Z0.5\nM99\n", ""};
  if (!tnc) s += bodies[uint8_t(o + form) % 4];
  return c;
}

std::string broken_promise(const CompressResult& r) {
  if (!r.ok) return "the program was refused";
  if (!r.verified) return "the output was not verified";
  if (!r.comparison.matched) return "the output leaves the input path: " + r.comparison.mismatch;
  if (!r.within_band())
    return fmt::format("the output differs from the input (max deviation {} mm, band {} mm): {}",
                       r.comparison.max_deviation_mm, r.band_mm, fmt::join(r.check.findings, "; "));
  // The fallback keeps the program within the band; that it was needed is a fault of the fit.
  if (r.runs_kept_as_input > 0)
    return fmt::format("the check refused {} fitted runs, written back as their input", r.runs_kept_as_input);
  std::vector<uint32_t> unreported;
  std::set_difference(r.comparison.kink_lines.begin(), r.comparison.kink_lines.end(), r.forced_kink_lines.begin(),
                      r.forced_kink_lines.end(), std::back_inserter(unreported));
  if (!unreported.empty())
    return fmt::format("tangent breaks at smooth joints not reported as forced, at input lines {}",
                       fmt::join(unreported, " "));
  return {};
}

std::string text_promise(const std::string& text) {
  // Read as RS274, as a controller whose keywords, assignments and labels are words of a
  // block (the Sinumerik's), and as one with numbered labels (Heidenhain ISO's).
  static const Dialect sinumerik = find_dialect("sinumerik", dialect_search_path(""));
  static const Dialect heidenhain = find_dialect("heidenhain-iso", dialect_search_path(""));
  for (const Dialect& d : {Dialect{}, sinumerik, heidenhain})
    if (std::string broken = text_promise(text, d); !broken.empty()) return d.name + ": " + broken;
  return {};
}

std::string text_promise(const std::string& text, const Dialect& dialect) {
  CompressOptions opt;
  opt.threads = 1;
  opt.dialect = dialect;
  {
    DiagnosticSink sink("fuzz.nc");
    CompressOptions keep = opt;
    keep.passthrough = true;
    const CompressResult r = compress("fuzz.nc", text, keep, sink);
    if (r.ok && r.output != text) return "passed through, the program came back changed";
  }
  DiagnosticSink sink("fuzz.nc");
  CompressResult r;
  try {
    r = compress("fuzz.nc", text, opt, sink);
  } catch (const Error&) {
    return {};  // a clear refusal (a measure past its budget) is a kept promise
  }
  if (r.ok) {
    if (!r.verified) return "the output was not verified";
    if (!r.within_band())
      return fmt::format("the output was refused by its own check: {}; {}", r.comparison.mismatch,
                         fmt::join(r.check.findings, "; "));
  }
  DiagnosticSink sa("a.nc"), sb("b.nc");
  const Program pa = lex("a.nc", text, sa, lex_rules(dialect)), pb = lex("b.nc", text, sb, lex_rules(dialect));
  const Interpretation ia = interpret(pa, sa, dialect), ib = interpret(pb, sb, dialect);
  DiffOptions dopt;
  dopt.threads = 1;
  ProgramDiff d;
  try {
    d = diff_programs(pa, ia, pb, ib, dopt);
  } catch (const Error&) {
    return {};  // a clear refusal (a measure past its budget) is a kept promise
  }
  if (d.verdict(dopt.tolerance_mm) == ProgramDiff::Verdict::Different)
    return fmt::format("the program differs from itself: max deviation {} mm; {}", d.max_deviation_mm,
                       fmt::join(d.findings, "; "));
  return {};
}

}  // namespace arcpress::test
