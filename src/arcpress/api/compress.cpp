// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/api/arcpress.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "arcpress/api/compressor.hpp"
#include "arcpress/api/piece.hpp"
#include "arcpress/core/error.hpp"
#include "arcpress/model/called_programs.hpp"

namespace arcpress {

FitOptions fit_options_for(const FitOptions& user, const Dialect& d, const Frame& frame, Plane plane) {
  FitOptions o = user;
  o.arcs = user.arcs && d.arcs && d.plane_allowed(plane) && (d.relative_arcs || frame.absolute);
  o.helical = user.helical && d.helical;
  o.extra_axes = user.extra_axes && d.extra_axes;
  o.max_sweep_deg = std::min(user.max_sweep_deg, d.max_sweep_deg);
  o.min_sweep_deg = std::max(user.min_sweep_deg, d.min_sweep_deg);
  o.min_radius_mm = std::max(user.min_radius_mm, d.min_radius_mm);
  o.max_radius_mm = std::min(user.max_radius_mm, d.max_radius_mm);
  o.min_arc_length_mm = std::max(user.min_arc_length_mm, d.min_arc_length_mm);
  o.min_arc_moves = std::max<uint32_t>(user.min_arc_moves, uint32_t(d.min_arc_moves));
  o.min_chord_mm = std::max(user.min_chord_mm, d.min_chord_mm);
  // (Centres are printed in the frame's unit, to at most the dialect's decimals for it.)
  const double step_mm = std::pow(10.0, -d.digits(frame.unit_mm != 1.0).max) * frame.unit_mm;
  o.centre_step_mm = std::max(user.centre_step_mm, step_mm);
  return o;
}

void verify_output(const Program& input, const Interpretation& in, const CompressOptions& opt, CompressResult& r,
                   std::span<const Run> runs) {
  // The output is read from the state the input was, where it was read whole: with what the
  // subprograms after its end leave, and its loops that run their first moves again in other
  // modes (the output's are the same lines of flow control) read so.
  DiagnosticSink quiet(input.name);
  const ModalState start = whole_program_start(input, opt.dialect, quiet);
  verify_piece_output(input, in, opt, r, runs, start, nullptr, false);
}

void check_options(const FitOptions& o) {
  auto check = [](const char* what, double v, const OptionRange& range) {
    if (range.holds(v)) return;
    throw Error(kExitInput, fmt::format("{} must be a finite number {} {} and <= {} {}, got {}", what,
                                        range.above_lo ? ">" : ">=", range.lo, range.hi, range.unit, v));
  };
  check("the tolerance", o.tolerance_mm, kToleranceRange);
  check("the G1 angle", o.g1_angle_deg, kG1AngleRange);
  check("the corner angle", o.corner_angle_deg, kCornerAngleRange);
  check("the minimum radius", o.min_radius_mm, kMinRadiusRange);
  check("the maximum radius", o.max_radius_mm, kMaxRadiusRange);
  check("the maximum sweep", o.max_sweep_deg, kMaxSweepRange);
  check("the minimum arc length", o.min_arc_length_mm, kMinArcLengthRange);
  check("the extrusion variance", o.extrusion_variance, kExtrusionVarianceRange);
}

CompressResult compress(const std::string& name, std::string text, const CompressOptions& opt,
                        DiagnosticSink& sink) {
  Compressor c(name, opt, sink);
  c.read_jumps(text, 1);  // (the whole program is at hand: its jumps and subprograms are read first)
  c.read_loops(text);
  c.push(text);
  text = {};
  c.finish();
  CompressResult r = c.result();
  c.take(r.output);
  if (!r.ok) r.output.clear();
  return r;
}

}  // namespace arcpress
