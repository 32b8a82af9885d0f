// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/api/piece.hpp"

#include <algorithm>
#include <atomic>
#include <iterator>
#include <numeric>
#include <optional>

#include <fmt/format.h>

#include "arcpress/core/deviation.hpp"
#include "arcpress/core/workers.hpp"
#include "arcpress/extract/run.hpp"
#include "arcpress/fit/fitter.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/verify/executed_path.hpp"

namespace arcpress {

namespace {

/// Whether output move j is a fit's rather than input move i as it was (where the program
/// is relative, to the floating noise of the sums: same_place()).
bool fitted_move(const Interpretation& in, size_t i, const Interpretation& out, size_t j) {
  const Move& a = in.moves[i];
  const Move& b = out.moves[j];
  return a.kind != b.kind || !same_places(a.to, b.to) || !same_places(in.from(i), out.from(j)) ||
         (is_arc(a.kind) && !(same_place(a.center.x(), b.center.x()) && same_place(a.center.y(), b.center.y()) &&
                              same_place(a.center.z(), b.center.z())));
}

/// Whether two moves with the same unknown axes end at the same place on every axis whose
/// position is known (where an axis is relative, as sums of the words before: same_place()).
bool same_known_end(const Move& a, const Move& b) {
  for (int ax = 0; ax < kAxisCount; ++ax)
    if (!((a.unknown_axes >> ax) & 1u) && !same_place(a.to[ax], b.to[ax])) return false;
  return true;
}

/// The ends of a piece's path as the output reads back (see PieceEnd).
void piece_ends(const Program& input, const Interpretation& in, const Interpretation& out, PieceEnd& head,
                PieceEnd& tail) {
  head = tail = PieceEnd{};
  if (in.moves.empty() || out.moves.empty()) return;
  const Move& first = out.moves.front();
  head.feed = is_feed(first.kind) && first.known && is_feed(in.moves.front().kind) && !in.moves.front().entered;
  head.fitted = fitted_move(in, 0, out, 0);
  head.plane = first.plane;
  head.tangent = move_start_tangent(out, 0);
  head.at = in_plane(in.from(0), first.plane);
  if (const auto v = in.vertex_beside(0, +1)) {
    head.beside = in_plane(in.from(*v), first.plane);
    if (const auto w = in.vertex_beside(*v, +1)) head.beside2 = in_plane(in.from(*w), first.plane);
  }
  head.input_line = input.blocks[in.moves.front().block].line;
  const size_t i = in.moves.size() - 1, j = out.moves.size() - 1;
  const Move& last = out.moves.back();
  tail.feed = is_feed(last.kind) && last.known && is_feed(in.moves.back().kind);
  tail.fitted = fitted_move(in, i, out, j);
  tail.plane = last.plane;
  tail.tangent = move_end_tangent(out, j);
  tail.at = in_plane(in.moves.back().to, last.plane);
  if (const auto v = in.vertex_beside(in.moves.size(), -1)) {
    tail.beside = in_plane(in.from(*v), last.plane);
    if (const auto w = in.vertex_beside(*v, -1)) tail.beside2 = in_plane(in.from(*w), last.plane);
  }
  tail.input_line = input.blocks[in.moves.back().block].line;
}

}  // namespace

std::optional<double> joint_turn_deg(const PieceEnd& tail, const PieceEnd& head, double band_mm,
                                     double corner_angle_deg) {
  if (!tail.feed || !head.feed || !(tail.fitted || head.fitted) || tail.plane != head.plane || !tail.beside ||
      !head.beside)
    return std::nullopt;
  // The corner rule as compare_paths() applies it: the vertex itself, and beside a corner.
  const Vec3 &before = *tail.beside, &at = head.at, &after = *head.beside;
  const bool before_corner = tail.beside2 && is_corner(*tail.beside2, before, at, band_mm, corner_angle_deg);
  const bool after_corner = head.beside2 && is_corner(at, after, *head.beside2, band_mm, corner_angle_deg);
  if (is_corner(before, at, after, band_mm, corner_angle_deg) ||
      is_corner_beside_corner(tail.beside2 ? &*tail.beside2 : nullptr, before, at, after,
                              head.beside2 ? &*head.beside2 : nullptr, before_corner, after_corner, band_mm))
    return std::nullopt;
  return turn_deg(tail.tangent, head.tangent);
}

void verify_piece_output(const Program& input, const Interpretation& in, const CompressOptions& opt, CompressResult& r,
                         std::span<const Run> runs, const ModalState& start, const ModalState* end, bool with_motion,
                         PieceEnd* head, PieceEnd* tail, std::vector<TimedBlock>* timed_out, size_t* untimed_out) {
  const std::string name = input.name + " (output)";
  DiagnosticSink out_sink(name);
  // (The lines the emitter copied from the input are compared byte for byte and take over
  // the input's words: lexing them again would make the same.)
  Program out_prog = lex(name, r.output, out_sink, input, r.stats.copied);
  ModalState out_state = start;
  Interpretation out_in = interpret(out_prog, out_sink, opt.dialect, &out_state);
  if (timed_out) {
    timed_out->clear();
    const size_t untimed = timed_blocks(out_prog, out_in, *timed_out);
    if (untimed_out) *untimed_out = untimed;
  }
  CompareOptions co;
  co.tolerance_mm = opt.fit.tolerance_mm;
  co.g1_angle_deg = opt.fit.g1_angle_deg;
  co.corner_angle_deg = opt.fit.corner_angle_deg;
  co.band_side = opt.fit.band_side;
  co.extrusion_variance = opt.fit.extrusion_variance;
  if (!runs.empty()) {
    co.fitted_plane.reserve(in.moves.size());
    for (const Move& m : in.moves) co.fitted_plane.push_back(m.plane);
    for (const Run& run : runs)
      std::fill_n(co.fitted_plane.begin() + run.first_move, run.move_count, run.plane);
  }
  const ArcSegmentation rule = opt.executed_rule();
  co.executed = rule;
  r.comparison = compare_paths(input, in, out_prog, out_in, co);
  const PathComparison& c = r.comparison;
  if (head && tail) piece_ends(input, in, out_in, *head, *tail);
  DiffOptions dopt;
  dopt.tolerance_mm = opt.fit.tolerance_mm;
  dopt.top = 1;
  dopt.threads = opt.threads;
  dopt.feed = false;  // compare_paths() pairs the moves and compares their feed exactly
  // One pass, where it proves the band: compare_paths() paired every output move with the
  // input moves it replaces, one for one, and measured each pair both ways (and its
  // executed chords within the band, where the firmware moves on chords). The pairs cover
  // both paths, so the whole paths lie no farther apart than the largest pair, and the
  // code of `arcpress diff` compares only the rest: rapids, sections, extrusion, non-motion
  // blocks, what could not be compared. Where the pairing does not cover the paths (a
  // mismatch, a move whose chords could not be bounded) or a bound exceeds the band, the
  // whole paths are measured as `arcpress diff` measures them, which decides.
  const double band_mm = opt.fit.tolerance_mm;
  const bool on_chords = rule.moves_on_chords();
  dopt.measure_path = !(c.matched && c.covers_path && c.max_deviation_mm <= band_mm &&
                        (!on_chords || c.max_executed_mm <= band_mm));
  if (!dopt.measure_path) {
    r.check = diff_programs(input, in, out_prog, out_in, dopt);
    r.check.max_deviation_mm = on_chords ? c.max_executed_mm : c.max_deviation_mm;
    if (r.check.max_deviation_mm > 0)
      r.check.worst.push_back(on_chords ? DiffPlace{c.max_executed_mm, c.executed_point, c.executed_line_a, c.executed_line_b}
                                        : DiffPlace{c.max_deviation_mm, c.worst_point, c.worst_line_a, c.worst_line_b});
    r.check.arc_chord_mm = 0;  // exact, or (on chords) an upper bound
  } else if (on_chords) {
    // compare_paths() measured each output move against the input it replaces, which is no
    // nearer than the nearest input anywhere: the whole-path measure needs to be exact only
    // near that maximum (or the band, below it), where it can confirm or refute it. On the
    // executed path, down to a twentieth of the band (the move-by-move maximum there is the
    // programmed path's, no hint for the chords').
    dopt.least_mm = kExactShare * band_mm;
    Interpretation in_chords, out_chords;
    r.check = diff_programs(input, executed_path(in, rule, in_chords), out_prog, executed_path(out_in, rule, out_chords),
                            dopt);
  } else {
    // Below a twentieth of the band no distance matters to the check, or to a user reading
    // its maximum: a piece written back as it was is not measured down to nothing.
    dopt.least_mm = std::max(kExactShare * band_mm, std::min(c.max_deviation_mm, band_mm) * (1 - kReadingShare));
    r.check = diff_programs(input, in, out_prog, out_in, dopt);
  }
  if (out_sink.error_count() > 0)
    r.check.findings.insert(r.check.findings.begin(), "the output does not read back: " + out_sink.format_all());
  // What follows is read by the controller from the state the output leaves: it must be
  // the one the input leaves there.
  if (end && !out_state.reads_as(*end, with_motion))
    r.check.findings.push_back(fmt::format("the output leaves the controller in another state than the input after "
                                           "input line {}",
                                           input.blocks.empty() ? 0 : input.blocks.back().line));
  // Feed moves that cannot be placed are not measured by either check: they must be the
  // input's own, one for one, as read (kind, end point as far as it is known, why).
  r.unplaced_kept = in.unplaced.size() == out_in.unplaced.size();
  for (size_t k = 0; k < in.unplaced.size() && r.unplaced_kept; ++k) {
    const Move& ma = in.moves[in.unplaced[k].move];
    const Move& mb = out_in.moves[out_in.unplaced[k].move];
    r.unplaced_kept = ma.kind == mb.kind && ma.unfit == mb.unfit && ma.unknown_axes == mb.unknown_axes &&
                      same_known_end(ma, mb);
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
  r.pieces_checked = 1;
  r.pieces_measured_whole = dopt.measure_path ? 1 : 0;
  r.band_mm = opt.fit.tolerance_mm;
  r.side_allowance_mm = opt.fit.band_side == BandSide::Both ? 0 : kBandSideRoundingShare * opt.fit.tolerance_mm;
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
  if (c.max_extra_axis > r.band_mm) lines.push_back(c.extra_axis_line_b);
  if (c.max_extrusion_rate_share > c.extrusion_allowed_share) lines.push_back(c.extrusion_line_b);
  if (c.max_wrong_side_mm > r.side_allowance_mm) lines.push_back(c.wrong_side_line_b);
  for (const DiffPlace& p : r.check.worst)
    if (p.deviation_mm > r.band_mm) lines.push_back(p.line_b);
  if (r.check.max_rapid_mm > r.band_mm) lines.push_back(r.check.worst_rapid.line_b);
  if (r.check.max_entry_mm > r.band_mm) lines.push_back(r.check.worst_entry.line_b);
  if (!r.check.findings.empty()) lines.push_back(0);
  return lines;
}

/// `o` (a run's options) with each limit that the user loosened from its default tightened
/// back to it: the G1 angle, the extrusion variance, the arcs' radius, sweep, length and
/// moves, and the band on the firmware's chords where the dialect names them. (The
/// tolerance, the corner angle and the method are the problem asked, not limits on its
/// answer.)
FitOptions tightened(FitOptions o, const CompressOptions& opt, const Interpretation& in, const Run& r) {
  FitOptions asked;  // the defaults, for the problem the user asked
  asked.tolerance_mm = opt.fit.tolerance_mm;
  asked.corner_angle_deg = opt.fit.corner_angle_deg;
  asked.method = opt.fit.method;
  asked.spikes = opt.fit.spikes;
  FitOptions d = fit_options_for(asked, opt.dialect, in.frames[r.frame], r.plane);
  d.executed = opt.dialect.executed;
  o.g1_angle_deg = std::min(o.g1_angle_deg, d.g1_angle_deg);
  o.extrusion_variance = std::min(o.extrusion_variance, d.extrusion_variance);
  o.min_radius_mm = std::max(o.min_radius_mm, d.min_radius_mm);
  o.max_radius_mm = std::min(o.max_radius_mm, d.max_radius_mm);
  o.max_sweep_deg = std::min(o.max_sweep_deg, d.max_sweep_deg);
  o.min_sweep_deg = std::max(o.min_sweep_deg, d.min_sweep_deg);
  o.min_arc_length_mm = std::max(o.min_arc_length_mm, d.min_arc_length_mm);
  o.min_arc_moves = std::max(o.min_arc_moves, d.min_arc_moves);
  if (!o.executed.moves_on_chords()) o.executed = d.executed;
  return o;
}

/// Fits every run of the piece, chain by chain (see chain_runs()), with `threads` threads.
std::vector<FitResult> fit_runs(const Interpretation& in, const std::vector<Run>& runs, const CompressOptions& opt,
                                unsigned threads) {
  const std::vector<RunChain> chains = chain_runs(in, runs, opt.fit.tolerance_mm, opt.fit.corner_angle_deg);
  std::vector<FitResult> fits(runs.size());
  auto fit_one = [&](size_t i) {
    const RunChain& c = chains[i];
    auto options_for = [&](const Run& r) {
      FitOptions o = fit_options_for(opt.fit, opt.dialect, in.frames[r.frame], r.plane);
      o.executed = opt.executed_rule();
      o.arcs = o.arcs && r.first_move >= in.arcless_moves;
      return o;
    };
    auto got = fit_chain(in, c, runs, options_for, [&](const Run& r) { return tightened(options_for(r), opt, in, r); });
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
  run_workers(worker_count(threads, chains.size()), [&](size_t) {
    try {
      for (size_t i; (i = next.fetch_add(1)) < chains.size();) fit_one(order[i]);
    } catch (...) {  // the fitter does not throw; an allocation can: the others stop too
      next = chains.size();
      throw;
    }
  });
  return fits;
}

size_t count_lines(const std::string& text) {
  const size_t n = size_t(std::count(text.begin(), text.end(), '\n'));
  return n + (!text.empty() && text.back() != '\n');
}

}  // namespace

void compress_piece(Piece& piece, const CompressOptions& options) {
  CompressOptions opt = options;
  opt.threads = piece.threads;
  const Program& prog = piece.program;
  // A G1 move the check could not measure (too far from the origin for the band) is kept as
  // it is: nothing is written that was not checked.
  const double farthest_mm = farthest_measurable_mm(opt.fit.tolerance_mm);
  for (size_t i = 0; i < piece.in.moves.size(); ++i) {
    Move& m = piece.in.moves[i];
    const AxisValues& from = piece.in.from(i);
    const double reach_mm = std::max({std::abs(from[kX]), std::abs(from[kY]), std::abs(from[kZ]),
                                      m.xyz().cwiseAbs().maxCoeff()});
    if (m.fittable() && !(reach_mm <= farthest_mm)) m.unfit = Unfit::FarFromOrigin;
  }
  const Interpretation& in = piece.in;
  CompressResult& r = piece.result;
  r.blocks_in = prog.blocks.size();
  r.bytes_in = prog.text.size();
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
    fits = fit_runs(in, runs, opt, opt.threads);
  }
  for (const Move& m : in.moves) r.g1_moves += m.kind == MoveKind::Line;
  if (!opt.passthrough) {
    for (const LeftOut& g : left_out_moves(in, runs)) {
      NotFitted n{g.why, g.moves, prog.blocks[in.moves[g.first_move].block].line, 0};
      if (is_position_unknown(g.why)) n.cause_line = g.cause_line;
      r.not_fitted.push_back(n);
    }
  }
  r.runs_fitted = runs.size();
  EmitOptions eo;
  eo.band_mm = opt.fit.tolerance_mm;
  eo.dialect = opt.dialect;
  eo.format = opt.arc_format.value_or(opt.dialect.format);
  eo.tangent_slack_deg = 0.05 * opt.fit.g1_angle_deg;
  eo.threads = opt.threads;
  eo.executed = opt.executed_rule();
  eo.extrusion_variance = opt.fit.extrusion_variance;
  eo.start = piece.emit;
  r.output = emit_program(prog, in, runs, fits, eo, &r.stats);
  r.ok = true;
  r.band_mm = opt.fit.tolerance_mm;
  auto verify = [&] {
    // (The output as read back is timed here too, where its block rate is asked for.)
    verify_piece_output(prog, in, opt, r, runs, piece.start, piece.last ? nullptr : &piece.end, piece.clean_end,
                        &piece.head, &piece.tail, opt.block_rate ? &piece.timed_out : nullptr, &piece.untimed_out);
  };
  if (opt.verify && !opt.passthrough) {
    verify();
    // A run whose output the check refuses is written as the input's own moves, and the
    // piece checked again, so that one odd stretch never costs the whole program: the runs
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
      verify();
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
  piece.output_lines = count_lines(r.output);
  if (opt.block_rate && r.ok) {
    piece.untimed_in = timed_blocks(prog, in, piece.timed_in);
    if (!r.verified) {  // (else the check timed the output as it read it back)
      DiagnosticSink out_sink(prog.name + " (output)");
      Program out_prog = lex(out_sink.file(), r.output, out_sink, prog.rules);
      out_prog.jumps = prog.jumps;
      ModalState out_state = piece.start;
      piece.timed_out.clear();
      piece.untimed_out = timed_blocks(out_prog, interpret(out_prog, out_sink, opt.dialect, &out_state), piece.timed_out);
    }
  }
}

namespace {

void shift(DiffPlace& p, size_t lines) {
  if (p.line_b > 0) p.line_b += uint32_t(lines);
}

/// `into` and `s` summed: counts add up, the first place of each kind is the earlier one.
void add_summary(ProgramSummary& into, const ProgramSummary& s) {
  into.blocks += s.blocks;
  into.bytes += s.bytes;
  into.feed_moves += s.feed_moves;
  into.rapids += s.rapids;
  into.sections += s.sections;
  into.non_motion += s.non_motion;
  into.path_mm += s.path_mm;
  auto first = [](size_t& n, uint32_t& line, size_t add, uint32_t add_line) {
    if (n == 0) line = add_line;
    n += add;
  };
  if (into.unplaced_feed_moves == 0) into.unplaced_reason = s.unplaced_reason;
  first(into.unplaced_feed_moves, into.first_unplaced_line, s.unplaced_feed_moves, s.first_unplaced_line);
  if (into.entry_moves == 0) into.entry_reason = s.entry_reason;
  first(into.entry_moves, into.first_entry_line, s.entry_moves, s.first_entry_line);
  first(into.unmeasured_arcs, into.first_unmeasured_line, s.unmeasured_arcs, s.first_unmeasured_line);
  first(into.far_moves, into.first_far_line, s.far_moves, s.first_far_line);
}

/// The largest of `into` and `add` (a deviation with its place), the earlier where equal.
template <class T>
void keep_largest(T& into_value, DiffPlace& into_place, T value, const DiffPlace& place) {
  if (value > into_value) into_value = value, into_place = place;
}

/// How many findings a program's check keeps: the first ones say what went wrong.
constexpr size_t kMaxFindings = 20;

void add_diff(ProgramDiff& into, ProgramDiff d, size_t lines_before) {
  for (DiffPlace& p : d.worst) shift(p, lines_before);
  for (DiffPlace* p : {&d.worst_rapid, &d.worst_entry, &d.worst_feed, &d.worst_extra_axis}) shift(*p, lines_before);
  add_summary(into.a, d.a);
  add_summary(into.b, d.b);
  into.max_deviation_mm = std::max(into.max_deviation_mm, d.max_deviation_mm);
  const size_t top = std::max(into.worst.size(), d.worst.size());
  into.worst.insert(into.worst.end(), d.worst.begin(), d.worst.end());
  std::stable_sort(into.worst.begin(), into.worst.end(),
                   [](const DiffPlace& x, const DiffPlace& y) { return x.deviation_mm > y.deviation_mm; });
  if (into.worst.size() > top) into.worst.resize(top);
  keep_largest(into.max_rapid_mm, into.worst_rapid, d.max_rapid_mm, d.worst_rapid);
  keep_largest(into.max_entry_mm, into.worst_entry, d.max_entry_mm, d.worst_entry);
  keep_largest(into.max_feed_difference_pct, into.worst_feed, d.max_feed_difference_pct, d.worst_feed);
  into.extra_axes_compared = into.extra_axes_compared || d.extra_axes_compared;
  if (d.max_extra_axis > into.max_extra_axis) into.extra_axis = d.extra_axis;
  keep_largest(into.max_extra_axis, into.worst_extra_axis, d.max_extra_axis, d.worst_extra_axis);
  into.max_extrusion_difference_mm = std::max(into.max_extrusion_difference_mm, d.max_extrusion_difference_mm);
  into.max_extrusion_per_mm_difference_pct =
      std::max(into.max_extrusion_per_mm_difference_pct, d.max_extrusion_per_mm_difference_pct);
  into.non_motion_differences += d.non_motion_differences;
  for (std::string& f : d.findings)
    if (into.findings.size() < kMaxFindings) into.findings.push_back(std::move(f));
  into.arc_chord_mm = std::max(into.arc_chord_mm, d.arc_chord_mm);
  into.chord_excess_mm = std::max(into.chord_excess_mm, d.chord_excess_mm);
}

void add_comparison(PathComparison& into, const PathComparison& c, size_t lines_before) {
  if (into.matched && !c.matched) {
    into.matched = false;
    into.mismatch = c.mismatch;
    into.mismatch_line_b = c.mismatch_line_b + uint32_t(lines_before);
  }
  if (c.max_deviation_mm > into.max_deviation_mm) {
    into.max_deviation_mm = c.max_deviation_mm;
    into.worst_line_a = c.worst_line_a;
    into.worst_line_b = c.worst_line_b ? c.worst_line_b + uint32_t(lines_before) : 0;
    into.worst_point = c.worst_point;
  }
  into.covers_path = into.covers_path && c.covers_path;
  if (c.max_extrusion_rate_share > into.max_extrusion_rate_share) {
    into.max_extrusion_rate_share = c.max_extrusion_rate_share;
    into.extrusion_line_a = c.extrusion_line_a;
    into.extrusion_line_b = c.extrusion_line_b ? c.extrusion_line_b + uint32_t(lines_before) : 0;
  }
  into.extrusion_allowed_share = std::min(into.extrusion_allowed_share, c.extrusion_allowed_share);
  if (c.max_extra_axis > into.max_extra_axis) {
    into.max_extra_axis = c.max_extra_axis;
    into.extra_axis = c.extra_axis;
    into.extra_axis_line_a = c.extra_axis_line_a;
    into.extra_axis_line_b = c.extra_axis_line_b ? c.extra_axis_line_b + uint32_t(lines_before) : 0;
  }
  if (c.max_executed_mm > into.max_executed_mm) {
    into.max_executed_mm = c.max_executed_mm;
    into.executed_line_a = c.executed_line_a;
    into.executed_line_b = c.executed_line_b ? c.executed_line_b + uint32_t(lines_before) : 0;
    into.executed_point = c.executed_point;
  }
  if (c.max_wrong_side_mm > into.max_wrong_side_mm) {
    into.max_wrong_side_mm = c.max_wrong_side_mm;
    into.wrong_side_line_a = c.wrong_side_line_a;
    into.wrong_side_line_b = c.wrong_side_line_b ? c.wrong_side_line_b + uint32_t(lines_before) : 0;
  }
  into.moves_a += c.moves_a;
  into.moves_b += c.moves_b;
  into.smooth_joints += c.smooth_joints;
  into.smooth_joints_over_g1 += c.smooth_joints_over_g1;
  into.kink_lines.insert(into.kink_lines.end(), c.kink_lines.begin(), c.kink_lines.end());
  into.max_smooth_kink_deg = std::max(into.max_smooth_kink_deg, c.max_smooth_kink_deg);
}

void add_stats(EmitStats& into, const EmitStats& s) {
  into.runs += s.runs;
  into.moves_in += s.moves_in;
  into.lines_out += s.lines_out;
  into.arcs_out += s.arcs_out;
  into.motion_words_added += s.motion_words_added;
  into.plane_words_added += s.plane_words_added;
  into.poles_restated += s.poles_restated;
  into.turns_spelled += s.turns_spelled;
  into.arcs_unprintable += s.arcs_unprintable;
  into.long_lines_kept += s.long_lines_kept;
}

}  // namespace

void add_piece(CompressResult& total, const Piece& piece, size_t lines_before) {
  const CompressResult& r = piece.result;
  total.ok = total.ok && r.ok;
  total.blocks_in += r.blocks_in;
  total.bytes_in += r.bytes_in;
  total.bytes_out += r.output.size();
  add_stats(total.stats, r.stats);
  total.forced_kink_lines.insert(total.forced_kink_lines.end(), r.forced_kink_lines.begin(), r.forced_kink_lines.end());
  total.forced_kinks = total.forced_kink_lines.size();
  total.g1_moves += r.g1_moves;
  total.runs_fitted += r.runs_fitted;
  total.runs_kept_as_input += r.runs_kept_as_input;
  for (const NotFitted& n : r.not_fitted) {
    auto same = std::find_if(total.not_fitted.begin(), total.not_fitted.end(),
                             [&](const NotFitted& t) { return t.why == n.why; });
    if (same == total.not_fitted.end()) total.not_fitted.push_back(n);
    else same->moves += n.moves;
  }
  total.verified = total.verified && r.verified;
  total.unplaced_kept = total.unplaced_kept && r.unplaced_kept;
  if (r.verified) {
    total.pieces_checked += r.pieces_checked;
    total.pieces_measured_whole += r.pieces_measured_whole;
    add_diff(total.check, r.check, lines_before);
    add_comparison(total.comparison, r.comparison, lines_before);
  }
  total.band_mm = r.band_mm;
  total.side_allowance_mm = r.side_allowance_mm;
}

}  // namespace arcpress
