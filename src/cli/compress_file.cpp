// SPDX-License-Identifier: GPL-3.0-or-later
#include "compress_file.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iterator>
#include <vector>

#include "arcpress/api/compressor.hpp"
#include "arcpress/api/piece.hpp"
#include "arcpress/core/error.hpp"
#include "arcpress/core/utf8_path.hpp"
#include "arcpress/dialect/dialect_loader.hpp"
#include "arcpress/dialect/program_flavor.hpp"
#include "arcpress/platform/platform.hpp"
#include "file_io.hpp"
#include "progress.hpp"

namespace arcpress::cli {

/// What `sinks` say, for standard error: of a file that is not G-code, only that (its
/// unreadable lines are no news then).
std::string diagnostics_text(std::initializer_list<const DiagnosticSink*> sinks) {
  std::string out;
  for (const DiagnosticSink* sink : sinks) {
    const auto& all = sink->all();
    const auto foreign =
        std::find_if(all.begin(), all.end(), [](const Diagnostic& d) { return d.code == "E-INPUT-NOT-GCODE"; });
    out += foreign != all.end() ? sink->format(*foreign) + "\n" : sink->format_all();
  }
  return out;
}

/// `p` with its links resolved, or empty where it does not exist.
std::string real_path(const std::string& p) {
  std::error_code ec;
  const std::filesystem::path resolved = std::filesystem::canonical(utf8_path(p), ec);
  return ec ? std::string() : utf8_string(resolved);
}

std::string exe_dir() { return platform::program_folder(); }

/// The dialect to read `program` with: the one the command line names (`--dialect-file`,
/// `--dialect` where `name_given`), or else the one the program names for itself (a
/// slicer's flavor line), or else `name` (the default). `why` says which, for --stats.
Dialect dialect_for(const std::string& name, bool name_given, const std::string& file, std::string_view program,
                    std::string_view path, std::string_view tail, std::string* why) {
  std::string reason = !file.empty() ? "--dialect-file" : name_given ? "--dialect" : "the default";
  std::string picked = name;
  bool slicer_program = false;  // a slicer's flavor line: a printer's program, in millimetres
  if (file.empty() && !name_given) {
    // `tail`: the end of a program of which `program` is the start (a slicer's config block
    // is at the end); its first line may be cut.
    const size_t nl = tail.find('\n');
    const std::string_view tail_lines = nl == std::string_view::npos ? std::string_view() : tail.substr(nl + 1);
    std::optional<ProgramFlavor> flavor = program_flavor(program);
    bool at_end = false;
    if (!flavor || flavor->model_only) {  // (a flavor near the end that is not Marlin's outranks a model)
      std::optional<ProgramFlavor> end = program_flavor(tail_lines);
      if (end && (!flavor || (!end->model_only && end->dialect != "marlin"))) flavor = std::move(end), at_end = true;
    }
    if (flavor) {
      slicer_program = flavor->slicer;
      const std::string where = at_end ? fmt::format("the program's '{}' near its end", flavor->evidence)
                                       : fmt::format("the program's '{}' at line {}", flavor->evidence, flavor->line);
      if (flavor->dialect.empty()) {
        reason = fmt::format("the default: {} names no single firmware (pass --dialect {})", where,
                             fmt::join(flavor_dialects(), ", "));
      } else {
        picked = flavor->dialect;
        reason = where;
      }
    } else if (const std::string by_extension = dialect_of_extension(path); !by_extension.empty()) {
      picked = by_extension;
      reason = fmt::format("the file's extension ({})", path.substr(path.find_last_of('.')));
    }
  }
  if (why) *why = reason;
  Dialect d = !file.empty() ? load_dialect_file(file) : find_dialect(picked, dialect_search_path(exe_dir()));
  // Every printer firmware starts in millimetres, whichever the flavor names.
  if (slicer_program) d.start_units = StartUnits::Mm;
  return d;
}

void set_start_units(Dialect& dialect, const std::string& units) {
  if (units == "mm") dialect.start_units = StartUnits::Mm;
  if (units == "inch") dialect.start_units = StartUnits::Inch;
}

BandSide band_side_named(const std::string& word) {
  return word == "left" ? BandSide::Left : word == "right" ? BandSide::Right : BandSide::Both;
}

/// Throws Error(kExitInput), naming `option`, unless `dialect` names the arc segmentation
/// its firmware moves along.
void require_executed_rule(const Dialect& dialect, const char* option) {
  if (!dialect.executed.moves_on_chords())
    throw Error(kExitInput, fmt::format("{}: dialect {} names no arc segmentation ([arcs.executed] rule); its "
                                        "controller moves on the programmed circles",
                                        option, dialect.name));
}


/// How much of a program is searched for a slicer's flavor line, at its start and its end.
constexpr size_t kFlavorBytes = size_t(1) << 20;
/// ... at the start of a program read from a pipe (Cura names it on its first line).
constexpr size_t kFlavorPipeBytes = size_t(1) << 16;
/// How much of the input is read at once.
constexpr size_t kReadBytes = size_t(1) << 20;

/// Reads the jumps of the program in `input`, a regular file (standard input too, where it is
/// one), into `c` before its blocks are pushed (Compressor::read_jumps()): a jump back to a
/// block is then known in time. Reading goes on where it was.
void read_jumps_ahead(const cli::InputFile& input, Compressor& c) {
  std::string text;
  for (size_t at = 0; at < *input.size();) {
    const std::string more = input.read_at(at, kReadBytes);
    if (more.empty()) break;
    at += more.size();
    text += more;
    const size_t last = text.rfind('\n');
    if (last == std::string::npos) continue;  // (a line longer than a read)
    c.read_jumps(std::string_view(text.data(), last + 1), 0);  // (no line is named: none is late)
    text.erase(0, last + 1);
  }
  c.read_jumps(text, 0);
}

int compress_file(const CompressArgs& a, FileReport& report, std::atomic<size_t>* read_counter) {
  std::string& log = report.log;
  report.input = a.input;
  std::string out_path = a.output;
  if (a.in_place) {
    if (a.input == "-") throw Error(kExitInput, "--in-place needs an input file, not standard input");
    if (!out_path.empty()) throw Error(kExitInput, "--in-place and -o cannot be used together");
    out_path = a.input;
  } else if (out_path.empty()) {
    out_path = std::string(1, '-');  // (a string literal here trips GCC 12's -Wrestrict)
  } else if (a.input != "-" && out_path != "-" && !real_path(out_path).empty() &&
             real_path(out_path) == real_path(a.input)) {
    throw Error(kExitInput, fmt::format("output '{}' is the input file; use --in-place to overwrite it", out_path));
  }
  if (a.opt.fit.min_radius_mm > a.opt.fit.max_radius_mm)
    throw Error(kExitInput, fmt::format("--min-radius {} mm is larger than --max-radius {} mm", a.opt.fit.min_radius_mm,
                                        a.opt.fit.max_radius_mm));
  CompressOptions opt = a.opt;
  opt.fit.method = method_named(a.method).value_or(FitOptions::Method::Arcs);  // (CLI11 took only known names)
  if (!a.band.empty()) opt.band = band_named(a.band).value_or(CompressOptions::Band::Dialect);  // (CLI11 took only known names)
  opt.fit.band_side = band_side_named(a.band_side);
  if (a.arc_format == "ijk") opt.arc_format = ArcFormat::Centre;
  if (a.arc_format == "r") opt.arc_format = ArcFormat::Radius;

  auto t0 = std::chrono::steady_clock::now();
  cli::InputFile input(a.input);
  // A pipe is read to its end first, unless asked not to, so that it is read as a file is:
  // its jumps and the subprograms after its end before its blocks, its flavor at its end.
  if (!a.stream) input.spool();
  const std::optional<size_t> size = input.size();
  // The start of the program, where a slicer's flavor line may be, and, of a file, its end,
  // where PrusaSlicer's config block names the flavor.
  // Only where no dialect is named; from a pipe, only as far as a header goes, so that its
  // output is not held back.
  const size_t head = !a.dialect_file.empty() || a.dialect_given ? 0 : size ? kFlavorBytes : kFlavorPipeBytes;
  std::string chunk;
  while (chunk.size() < head && input.read(chunk, head - chunk.size()) > 0) {
  }
  const std::string name = a.input == "-" ? "<stdin>" : a.input;
  std::string why_dialect;
  opt.dialect = dialect_for(a.dialect, a.dialect_given, a.dialect_file, chunk, a.input == "-" ? "" : a.input,
                            head == 0 || chunk.size() < head ? std::string() : input.tail(kFlavorBytes), &why_dialect);
  set_start_units(opt.dialect, a.units);
  if (opt.band == CompressOptions::Band::Executed) require_executed_rule(opt.dialect, "--band executed");
  opt.block_rate = a.stats;
  DiagnosticSink sink(name);
  Compressor compressor(name, opt, sink);
  if (size) read_jumps_ahead(input, compressor);
  // A program that jumps is read once ahead for its loops (Compressor::read_loops()).
  if (size && *size <= Compressor::kLoopsAheadBytes && compressor.has_jumps())
    compressor.read_loops(input.read_at(0, *size));
  cli::OutputFile out(out_path);
  report.output = out_path;
  // In a batch, the batch's progress line counts what is read.
  cli::Progress progress(size, a.quiet || read_counter, a.progress && !read_counter);
  // Read, compress and write as the input comes: each piece's text is written once it and
  // everything before it are done.
  std::string text;
  for (size_t read = 0; compressor.result().ok;) {
    if (chunk.empty() && input.read(chunk, kReadBytes) == 0) break;
    const size_t chunk_size = chunk.size();
    read += chunk_size;
    compressor.push(chunk);
    chunk.clear();
    text.clear();
    if (compressor.take(text) > 0) out.write(text);
    progress.update(read);
    if (read_counter) *read_counter += chunk_size;
  }
  compressor.finish();
  text.clear();
  if (compressor.take(text) > 0) out.write(text);
  progress.clear();
  const CompressResult& r = compressor.result();
  report.bytes_in = r.bytes_in;
  report.blocks_in = r.blocks_in;
  const std::string diags = diagnostics_text({&sink});
  log += diags;
  // Where the output cannot be used, it is taken back: a file is left as it was.
  auto nothing_written = [&] {
    const size_t left = out.discard();
    if (left == 0) fmt::format_to(std::back_inserter(log), "arcpress: nothing written\n");
    else fmt::format_to(std::back_inserter(log), "arcpress: {} bytes had been written to '{}' before the failure; do not use them\n", left,
                    out_path == "-" ? "standard output" : out_path);
  };
  if (!r.ok) {
    fmt::format_to(std::back_inserter(log), "arcpress: {} error(s) in '{}'\n", sink.error_count(), name);
    nothing_written();
    return kExitInput;
  }
  if (!r.within_band()) {
    const ProgramDiff& c = r.check;
    if (!r.comparison.matched) fmt::format_to(std::back_inserter(log), "arcpress: verification failed: {}\n", r.comparison.mismatch);
    if (c.max_deviation_mm > r.band_mm || r.comparison.max_deviation_mm > r.band_mm) {
      DiffPlace w = c.worst.empty() ? DiffPlace{} : c.worst.front();
      fmt::format_to(std::back_inserter(log),
                 "arcpress: verification failed: output deviates {:.6f} mm from the input (band {:.6f} mm) at "
                 "X{:.4f} Y{:.4f} Z{:.4f}, input line {}, output line {}\n",
                 std::max(c.max_deviation_mm, r.comparison.max_deviation_mm), r.band_mm, w.at.x(), w.at.y(), w.at.z(),
                 w.line_a, w.line_b);
    }
    if (r.comparison.max_wrong_side_mm > r.side_allowance_mm)
      fmt::format_to(std::back_inserter(log),
                     "arcpress: verification failed: the output lies {:.6f} mm on the {} side of the input (allowed "
                     "{:.6f} mm), input line {}, output line {}\n",
                     r.comparison.max_wrong_side_mm, a.band_side == "left" ? "right" : "left", r.side_allowance_mm,
                     r.comparison.wrong_side_line_a, r.comparison.wrong_side_line_b);
    if (c.max_rapid_mm > r.band_mm)
      fmt::format_to(std::back_inserter(log), "arcpress: verification failed: a rapid ends {:.6f} mm away, input line {}, output line {}\n",
                 c.max_rapid_mm, c.worst_rapid.line_a, c.worst_rapid.line_b);
    if (const PathComparison& pc = r.comparison; pc.max_extrusion_rate_share > pc.extrusion_allowed_share)
      fmt::format_to(std::back_inserter(log),
                     "arcpress: verification failed: an output block extrudes {:.2f} % off the E per mm of a move it "
                     "replaces (allowed {:.2f} %), input line {}, output line {}\n",
                     100 * pc.max_extrusion_rate_share, 100 * pc.extrusion_allowed_share, pc.extrusion_line_a,
                     pc.extrusion_line_b);
    if (const PathComparison& pc = r.comparison; pc.max_extra_axis > r.band_mm && pc.extra_axis >= 0)
      fmt::format_to(std::back_inserter(log),
                     "arcpress: verification failed: the output carries {} {:.6f} {} away from the input's (band {}), "
                     "input line {}, output line {}\n",
                     kAxisLetters[pc.extra_axis], pc.max_extra_axis, kAxisIsLinear[pc.extra_axis] ? "mm" : "degrees",
                     r.band_mm, pc.extra_axis_line_a, pc.extra_axis_line_b);
    if (c.max_extra_axis > r.band_mm && c.extra_axis >= 0)
      fmt::format_to(std::back_inserter(log),
                     "arcpress: verification failed: {} differs by {:.6f} {}, input line {}, output line {}\n",
                     kAxisLetters[c.extra_axis], c.max_extra_axis, kAxisIsLinear[c.extra_axis] ? "mm" : "degrees",
                     c.worst_extra_axis.line_a, c.worst_extra_axis.line_b);
    for (const std::string& f : c.findings) fmt::format_to(std::back_inserter(log), "arcpress: verification failed: {}\n", f);
    nothing_written();
    return kExitVerifyFailed;
  }
  out.commit();
  report.bytes_out = r.bytes_out;
  report.blocks_out = r.blocks_in - r.stats.moves_in + r.stats.lines_out + r.stats.arcs_out + r.stats.plane_words_added;
  if (r.verified) report.max_deviation_mm = std::max(r.check.max_deviation_mm, r.comparison.max_deviation_mm);
  if (a.stats) {
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const auto& st = r.stats;
    fmt::format_to(std::back_inserter(log),
               "arcpress: {} -> {}\n"
               "  blocks in      {}\n"
               "  bytes in/out   {} / {} ({:.1f} %)\n"
               "  G1 moves       {} in the input, {} in {} runs\n"
               "  dialect        {}, by {}\n"
               "  written        {} G1 + {} G2/G3 ({} blocks for {} moves, {:.1f} %)\n"
               "  kept as input  {} arcs that would not print inside the dialect's rules, {} over-long lines, {} runs "
               "the check refused\n"
               "  planes         {} G17/G18/G19 blocks around runs fitted in another plane\n"
               "  pieces         {} streamed, {} of them cut inside a path\n"
               "  time           {:.3f} s\n",
               name, out_path == "-" ? "<stdout>" : out_path, r.blocks_in, r.bytes_in, r.bytes_out,
               r.bytes_in ? 100.0 * double(r.bytes_out) / double(r.bytes_in) : 100.0, r.g1_moves, st.moves_in, st.runs,
               opt.dialect.source.empty() ? opt.dialect.name : opt.dialect.name + " (" + opt.dialect.source + ")",
               why_dialect,
               st.lines_out, st.arcs_out, st.lines_out + st.arcs_out, st.moves_in,
               st.moves_in ? 100.0 * double(st.lines_out + st.arcs_out) / double(st.moves_in) : 100.0,
               st.arcs_unprintable, st.long_lines_kept, r.runs_kept_as_input, st.plane_words_added,
               compressor.pieces(), compressor.forced_cuts(), s);
    if (r.rate_in && r.rate_out)
      fmt::format_to(std::back_inserter(log),
                     "  block rate     at the programmed feeds, acceleration ignored, over any 1 s of cutting:\n"
                     "                 in:  {}\n"
                     "                 out: {}\n",
                     block_rate_text(*r.rate_in), block_rate_text(*r.rate_out));
    // The G1 moves left as they are, by reason, with the first place of each.
    for (const NotFitted& n : r.not_fitted)
      fmt::format_to(std::back_inserter(log), "  not fitted     {} G1 move{}: {}{} (first at line {})\n", n.moves, n.moves == 1 ? "" : "s",
                 describe(n.why), n.cause_line ? fmt::format(" at line {}", n.cause_line) : std::string(),
                 n.first_line);
    if (r.verified) {
      const auto& c = r.comparison;
      // Where the worst place is, when there is one (a path written back as it was has none).
      std::string where;
      if (!r.check.worst.empty() && r.check.worst.front().line_a > 0)
        where = fmt::format(", input line {}, output line {}", r.check.worst.front().line_a, r.check.worst.front().line_b);
      // The check measures exactly only what is over a twentieth of the band.
      const double floor_mm = kExactShare * r.band_mm;
      if (r.check.max_deviation_mm < floor_mm) where = fmt::format(", under {:.6f} mm everywhere (measured no closer)", floor_mm);
      const std::vector<uint32_t> unforced = r.unforced_kink_lines();
      fmt::format_to(std::back_inserter(log),
                 "  deviation      {:.6f} mm max (band {} mm{}){}\n"
                 "  smooth joints  {} made, max kink {:.3f} deg, {} over {} deg{}\n",
                 r.check.max_deviation_mm, r.band_mm,
                 opt.executed_rule().moves_on_chords()
                     ? fmt::format(", on the path {}'s firmware moves: arcs as its chords",
                                   rule_name(opt.executed_rule().rule))
                     : std::string(", on the programmed path"),
                 where, c.smooth_joints, c.max_smooth_kink_deg, c.smooth_joints_over_g1, a.opt.fit.g1_angle_deg,
                 c.smooth_joints_over_g1 == 0 ? std::string()
                 : unforced.empty()           ? std::string(", each forced by the band or the digits")
                                              : fmt::format(", {} of them not forced (at input line {})", unforced.size(),
                                                            unforced.front()));
      if (c.max_extrusion_rate_share > 0)
        fmt::format_to(std::back_inserter(log),
                       "  extrusion      E per mm at most {:.2f} % off that of a move a block replaces (variance {:.2f} %), "
                       "input line {}, output line {}\n",
                       100 * c.max_extrusion_rate_share, 100 * a.opt.fit.extrusion_variance, c.extrusion_line_a,
                       c.extrusion_line_b);
      if (c.extra_axis >= 0)
        fmt::format_to(std::back_inserter(log),
                       "  extra axes     {} carried at most {:.6f} {} from the input's value at its vertices (band {}), "
                       "input line {}, output line {}\n",
                       kAxisLetters[c.extra_axis], c.max_extra_axis, kAxisIsLinear[c.extra_axis] ? "mm" : "degrees",
                       r.band_mm, c.extra_axis_line_a, c.extra_axis_line_b);
      fmt::format_to(std::back_inserter(log),
                     "  check          {} piece{} move by move, {} of them also as whole paths (where the moves "
                     "could not be paired one for one)\n",
                     r.pieces_checked, r.pieces_checked == 1 ? "" : "s", r.pieces_measured_whole);
      if (opt.fit.band_side != BandSide::Both)
        fmt::format_to(std::back_inserter(log),
                       "  band side      {}: the output lies at most {:.6f} mm on the other side of the input (allowed "
                       "{:.6f} mm, the rounding of printed arc centres){}\n",
                       a.band_side, c.max_wrong_side_mm, r.side_allowance_mm,
                       c.wrong_side_line_b ? fmt::format(", input line {}, output line {}", c.wrong_side_line_a,
                                                         c.wrong_side_line_b)
                                           : std::string());
    } else {
      fmt::format_to(std::back_inserter(log),
                 "  deviation      not measured (--no-verify)\n"
                 "  smooth joints  {} forced by the band or the digits to change tangent (others not measured)\n",
                 r.forced_kinks);
    }
    // Where the tangent had to break: the input lines of the first few such joints; where the
    // output was read back, those of them that turn by more than the G1 angle as read.
    std::vector<uint32_t> at = r.forced_kink_lines;
    if (r.verified) {
      std::vector<uint32_t> over = r.comparison.kink_lines, both;
      std::sort(over.begin(), over.end());
      std::set_intersection(at.begin(), at.end(), over.begin(), over.end(), std::back_inserter(both));
      at.swap(both);
    }
    if (!at.empty()) {
      constexpr size_t kShown = 10;
      const std::vector<uint32_t> first(at.begin(), at.begin() + static_cast<long>(std::min(at.size(), kShown)));
      fmt::format_to(std::back_inserter(log), "  forced at      input line{} {}{}\n", at.size() > 1 ? "s" : "", fmt::join(first, ", "),
                 at.size() > kShown ? fmt::format(", ... ({} in all)", at.size()) : std::string());
    }
  }
  return kExitOk;
}

}  // namespace arcpress::cli
