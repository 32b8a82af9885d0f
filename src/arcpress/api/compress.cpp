#include "arcpress/api/arcpress.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iterator>
#include <numeric>
#include <optional>

#include <fmt/format.h>

#include "arcpress/core/error.hpp"
#include "arcpress/core/workers.hpp"
#include "arcpress/extract/run.hpp"
#include "arcpress/fit/fitter.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/lex/refusal_scan.hpp"
#include "arcpress/model/interpreter.hpp"

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
  return o;
}

void verify_output(const Program& input, const Interpretation& in, const CompressOptions& opt, CompressResult& r,
                   std::span<const Run> runs) {
  const std::string name = input.name + " (output)";
  DiagnosticSink out_sink(name);
  Program out_prog = lex(name, r.output, out_sink);
  Interpretation out_in = interpret(out_prog, out_sink, opt.dialect);
  CompareOptions co;
  co.tolerance_mm = opt.fit.tolerance_mm;
  co.g1_angle_deg = opt.fit.g1_angle_deg;
  co.corner_angle_deg = opt.fit.corner_angle_deg;
  if (!runs.empty()) {
    co.fitted_plane.reserve(in.moves.size());
    for (const Move& m : in.moves) co.fitted_plane.push_back(m.plane);
    for (const Run& run : runs)
      std::fill_n(co.fitted_plane.begin() + run.first_move, run.move_count, run.plane);
  }
  r.comparison = compare_paths(input, in, out_prog, out_in, co);
  DiffOptions dopt;
  dopt.tolerance_mm = opt.fit.tolerance_mm;
  dopt.top = 1;
  dopt.threads = opt.threads;
  dopt.feed = false;  // compare_paths() pairs the moves and compares their feed exactly
  // compare_paths() measured each output move against the input it replaces, which is no
  // nearer than the nearest input anywhere: the whole-path measure needs to be exact only
  // near that maximum (or the band, below it), where it can confirm or refute it.
  dopt.least_mm = std::max(0.0, std::min(r.comparison.max_deviation_mm, opt.fit.tolerance_mm) * (1 - kReadingShare));
  r.check = diff_programs(input, in, out_prog, out_in, dopt);
  if (out_sink.error_count() > 0)
    r.check.findings.insert(r.check.findings.begin(), "the output does not read back: " + out_sink.format_all());
  // Feed moves that cannot be placed are not measured by either check: they must be the
  // input's own, one for one, as read (kind, end point as far as it is known, why).
  r.unplaced_kept = in.unplaced.size() == out_in.unplaced.size();
  for (size_t k = 0; k < in.unplaced.size() && r.unplaced_kept; ++k) {
    const Move& ma = in.moves[in.unplaced[k].move];
    const Move& mb = out_in.moves[out_in.unplaced[k].move];
    r.unplaced_kept = ma.kind == mb.kind && ma.to == mb.to && ma.unfit == mb.unfit && ma.unknown_axes == mb.unknown_axes;
  }
  if (!r.unplaced_kept)
    r.check.findings.push_back(fmt::format("feed moves whose position is not known: {} in the input, {} in the output, "
                                           "not the same moves",
                                           in.unplaced.size(), out_in.unplaced.size()));
  // Arcs too big to follow within the band, and moves too far from the origin to measure,
  // are as many in the output as in the input (no fit writes one; compare_paths() has
  // measured every output move against the input it replaces, as well as doubles allow).
  if (r.check.a.unmeasured_arcs != r.check.b.unmeasured_arcs || r.check.a.far_moves < r.check.b.far_moves) {
    r.unplaced_kept = false;
    r.check.findings.push_back(fmt::format("moves too big or too far to measure: {} in the input, {} in the output",
                                           r.check.a.unmeasured_arcs + r.check.a.far_moves,
                                           r.check.b.unmeasured_arcs + r.check.b.far_moves));
  }
  r.band_mm = opt.fit.tolerance_mm;
  r.verified = true;
}

namespace {

/// Rounds of writing refused runs as their input before every run is.
constexpr int kFallbackRounds = 4;

/// A run written as its input moves: one line primitive per move.
FitResult kept(const Run& run) {
  FitResult f;
  for (uint32_t v = 1; v <= run.move_count; ++v) f.prims.push_back({v, Primitive::Kind::Line});
  return f;
}
bool is_kept(const FitResult& f, const Run& run) {
  if (f.prims.size() != run.move_count) return false;
  for (uint32_t v = 0; v < run.move_count; ++v)
    if (f.prims[v].end_vertex != v + 1 || f.prims[v].kind != Primitive::Kind::Line) return false;
  return true;
}

/// The run whose output lines (EmitStats::run_lines, in order) hold `line`, if any.
std::optional<size_t> run_at(const std::vector<std::pair<uint32_t, uint32_t>>& run_lines, uint32_t line) {
  const auto after = std::upper_bound(run_lines.begin(), run_lines.end(), line,
                                      [](uint32_t l, const auto& span) { return l < span.first; });
  if (after == run_lines.begin() || line > std::prev(after)->second) return std::nullopt;
  return size_t(std::prev(after) - run_lines.begin());
}

/// The output lines at which the checks of `r` found the output outside the band or off
/// the input's path (0 for a finding that names no place in the output's path).
std::vector<uint32_t> refused_output_lines(const CompressResult& r) {
  std::vector<uint32_t> lines;
  const PathComparison& c = r.comparison;
  if (!c.matched) lines.push_back(c.mismatch_line_b);
  if (c.max_deviation_mm > r.band_mm) lines.push_back(c.worst_line_b);
  for (const DiffPlace& p : r.check.worst)
    if (p.deviation_mm > r.band_mm) lines.push_back(p.line_b);
  if (r.check.max_rapid_mm > r.band_mm) lines.push_back(r.check.worst_rapid.line_b);
  if (r.check.max_entry_mm > r.band_mm) lines.push_back(r.check.worst_entry.line_b);
  if (!r.check.findings.empty()) lines.push_back(0);
  return lines;
}

/// Fits every run, chain by chain (see chain_runs()), with `opt.threads` threads.
std::vector<FitResult> fit_runs(const Interpretation& in, const std::vector<Run>& runs, const CompressOptions& opt) {
  const std::vector<RunChain> chains = chain_runs(in, runs, opt.fit.tolerance_mm, opt.fit.corner_angle_deg);
  std::vector<FitResult> fits(runs.size());
  auto fit_one = [&](size_t i) {
    const RunChain& c = chains[i];
    auto got = fit_chain(in, c, runs, [&](const Run& r) {
      return fit_options_for(opt.fit, opt.dialect, in.frames[r.frame], r.plane);
    });
    std::move(got.begin(), got.end(), fits.begin() + c.first_run);
  };
  // Each worker takes the next chain not yet taken, longest first, so a few long ones do not
  // hold the rest back at the end; results land in their runs' places, so the order never
  // depends on the timing.
  std::vector<size_t> order(chains.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t x, size_t y) { return chains[x].move_count > chains[y].move_count; });
  std::atomic<size_t> next{0};
  run_workers(worker_count(opt.threads, chains.size()), [&](size_t) {
    try {
      for (size_t i; (i = next.fetch_add(1)) < chains.size();) fit_one(order[i]);
    } catch (...) {  // the fitter does not throw; an allocation can: the others stop too
      next = chains.size();
      throw;
    }
  });
  return fits;
}

}  // namespace

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
}

CompressResult compress(const std::string& name, std::string text, const CompressOptions& opt,
                        DiagnosticSink& sink) {
  check_options(opt.fit);
  sink.set_strict(opt.strict);
  CompressResult r;
  r.bytes_in = text.size();
  Program prog = lex(name, std::move(text), sink);
  r.blocks_in = prog.blocks.size();
  if (opt.arc_format == ArcFormat::Radius && !opt.dialect.radius_word)
    throw Error(kExitInput, opt.dialect.name + " does not read R-form arcs; use I/J/K");
  scan_refusals(prog, opt.dialect, sink);
  Interpretation in = interpret(prog, sink, opt.dialect);
  if (sink.error_count() > 0) return r;
  std::vector<Run> runs;
  std::vector<FitResult> fits;
  if (!opt.passthrough) {
    // A plane's normal axis that wanders by less than the fitter carries along a primitive
    // does not keep a stretch out of that plane.
    FitOptions target = opt.fit;
    target.helical = opt.fit.helical && opt.dialect.helical;
    PlaneChoice choice;
    choice.spread_mm = normal_axis_spread_mm(target);
    choice.band_mm = opt.fit.tolerance_mm;
    choice.corner_angle_deg = opt.fit.corner_angle_deg;
    runs = extract_runs(in, 2, choice);
    fits = fit_runs(in, runs, opt);
  }
  for (const Move& m : in.moves) r.g1_moves += m.kind == MoveKind::Line;
  if (!opt.passthrough) {
    for (const LeftOut& g : left_out_moves(in, runs)) {
      NotFitted n{g.why, g.moves, prog.blocks[in.moves[g.first_move].block].line, 0};
      if (is_position_unknown(g.why)) n.cause_line = g.cause_line;
      r.not_fitted.push_back(n);
    }
    // A program with G1 moves of which none could be fitted is told why, where something
    // kept them from it (not where each is alone already, as in a program fitted before).
    const auto most = std::max_element(r.not_fitted.begin(), r.not_fitted.end(), [](const NotFitted& x, const NotFitted& y) {
      return (x.why == Unfit::None ? 0 : x.moves) < (y.why == Unfit::None ? 0 : y.moves);
    });
    if (r.g1_moves > 0 && runs.empty() && most != r.not_fitted.end() && most->why != Unfit::None) {
      sink.warning({most->first_line, 1}, "W-FIT-NONE",
                   fmt::format("none of the {} G1 moves could be fitted; {} of them: {}{} (see --stats)", r.g1_moves,
                               most->moves, describe(most->why),
                               most->cause_line ? fmt::format(" at line {}", most->cause_line) : std::string()));
    }
  }
  EmitOptions eo;
  eo.band_mm = opt.fit.tolerance_mm;
  eo.dialect = opt.dialect;
  eo.format = opt.arc_format.value_or(opt.dialect.format);
  eo.tangent_slack_deg = 0.05 * opt.fit.g1_angle_deg;
  eo.threads = opt.threads;
  r.output = emit_program(prog, in, runs, fits, eo, &r.stats);
  r.ok = true;
  r.band_mm = opt.fit.tolerance_mm;
  if (opt.verify && !opt.passthrough) {
    verify_output(prog, in, opt, r, runs);
    // A run whose output the check refuses is written as the input's own moves, and the
    // program checked again, so that one odd stretch never costs the whole program: the runs
    // at the places the checks name, for a few rounds; then, or where a finding names no
    // place in a run, every run (the input itself, which reads as itself).
    for (int round = 0; !r.within_band() && round < kFallbackRounds; ++round) {
      // A place in no run, or in one written as its input already, has no fit to blame.
      bool everything = round + 1 == kFallbackRounds;
      std::vector<size_t> blamed;
      for (uint32_t line : refused_output_lines(r)) {
        const std::optional<size_t> k = run_at(r.stats.run_lines, line);
        if (!k || is_kept(fits[*k], runs[*k])) everything = true;
        else blamed.push_back(*k);
      }
      if (everything) {
        blamed.resize(runs.size());
        std::iota(blamed.begin(), blamed.end(), size_t(0));
      }
      for (size_t k : blamed)
        if (!is_kept(fits[k], runs[k])) fits[k] = kept(runs[k]), ++r.runs_kept_as_input;
      r.stats = EmitStats{};
      r.output = emit_program(prog, in, runs, fits, eo, &r.stats);
      verify_output(prog, in, opt, r, runs);
      if (everything) break;
    }
  }
  for (size_t k = 0; k < runs.size(); ++k)
    for (uint32_t v : fits[k].forced_at)
      r.forced_kink_lines.push_back(prog.blocks[in.moves[in.joint_move(runs[k].first_move + v)].block].line);
  // Joints beside blocks the dialect's rules changed (an arc whose printed centre could not
  // keep its end tangents, a primitive written back as its input moves) are forced by the
  // digits: those that turn too far as read back, or all where the output was not read back.
  std::vector<uint32_t> loose;
  for (uint32_t m : r.stats.rule_joints)
    if (m < in.moves.size()) loose.push_back(prog.blocks[in.moves[in.joint_move(m)].block].line);
  std::sort(loose.begin(), loose.end());
  if (r.verified) {
    std::vector<uint32_t> turned;
    std::set_intersection(loose.begin(), loose.end(), r.comparison.kink_lines.begin(), r.comparison.kink_lines.end(),
                          std::back_inserter(turned));
    loose.swap(turned);
  }
  // In order, each once (a joint between two runs may be reported by both).
  auto& forced = r.forced_kink_lines;
  forced.insert(forced.end(), loose.begin(), loose.end());
  std::sort(forced.begin(), forced.end());
  forced.erase(std::unique(forced.begin(), forced.end()), forced.end());
  r.forced_kinks = forced.size();
  return r;
}

}  // namespace arcpress
