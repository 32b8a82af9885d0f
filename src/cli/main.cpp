// SPDX-License-Identifier: GPL-3.0-or-later
// arcpress command line: the only place that catches exceptions and picks exit codes.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include "arcpress/api/arcpress.hpp"
#include "arcpress/api/compressor.hpp"
#include "arcpress/api/piece.hpp"
#include "arcpress/core/error.hpp"
#include "arcpress/core/utf8_path.hpp"
#include "arcpress/dialect/dialect_loader.hpp"
#include "arcpress/dialect/program_flavor.hpp"
#include "arcpress/lex/foreign_content.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"
#include "arcpress/platform/platform.hpp"
#include "arcpress/verify/diff_plot.hpp"
#include "arcpress/verify/executed_path.hpp"
#include "arcpress_commit.hpp"
#include "compress_file.hpp"
#include "batch.hpp"
#include "console.hpp"
#include "file_io.hpp"
#include "progress.hpp"

namespace {

using namespace arcpress;

constexpr const char* kExitCodesHelp =
    "Exit codes:\n"
    "  0  success\n"
    "  1  verification failed: the output left the tolerance band\n"
    "  2  usage error, or input that cannot be read (see the diagnostics)\n"
    "  3  I/O error: a file could not be read or written\n";

constexpr const char* kDiffExitCodesHelp =
    "Exit codes:\n"
    "  0  SAME: every feed move of both programs was compared, and they agree within the band\n"
    "  1  DIFFERENT: what was compared differs (the worst place and its lines are listed)\n"
    "  2  INCOMPLETE: some feed moves could not be placed, or some of B's feed path had no\n"
    "     counterpart in A to compare its feed with, and were not compared; or a usage error,\n"
    "     or input that cannot be read\n"
    "  3  I/O error: a file could not be read or written\n";

/// A floating option's check: a finite number in `range` (OptionRange, shared with the
/// library's check_options()). The message names the range and what was given.
CLI::Validator finite_in(const OptionRange& range) {
  auto text = [](double v) {  // plain decimals, never an exponent
    std::string t = fmt::format("{:.6f}", v);
    while (t.back() == '0') t.pop_back();
    if (t.back() == '.') t.pop_back();
    return t;
  };
  const std::string described = range.above_lo
                                    ? fmt::format("> {} and <= {} {}", text(range.lo), text(range.hi), range.unit)
                                    : fmt::format("from {} to {} {}", text(range.lo), text(range.hi), range.unit);
  return CLI::Validator(
      [=](std::string& given) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(given.c_str(), &end);
        if (end != given.c_str() && *end == '\0' && range.holds(v)) return {};
        return fmt::format("must be a finite number {}, got '{}'", described, given);
      },
      described, "FINITE");
}

/// Edits (insertions, deletions, substitutions) that turn `a` into `b`.
size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

/// What to do about the arguments `app` did not expect, one line each: the nearest real
/// option for a mistyped one, and for a second program name, that a file is written with -o.
/// `positional` says what the command's own arguments are.
std::string explain_extras(const CLI::App& app, const std::vector<std::string>& extras, const std::string& positional,
                           bool takes_output) {
  std::vector<std::string> names;
  for (const CLI::Option* o : app.get_options()) {
    for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
    for (const std::string& s : o->get_snames()) names.push_back("-" + s);
  }
  std::string out;
  bool after_option = false;  // a word after an unknown option is taken for its value
  for (const std::string& e : extras) {
    if (e.size() > 1 && e[0] == '-') {
      const std::string given = e.substr(0, e.find('='));
      std::string nearest;
      size_t best = std::max<size_t>(2, given.size() / 3) + 1;
      for (const std::string& n : names)
        if (const size_t d = edit_distance(given, n); d < best) best = d, nearest = n;
      out += nearest.empty() ? fmt::format("arcpress: unknown option '{}' (see --help)\n", given)
                             : fmt::format("arcpress: unknown option '{}'; did you mean '{}'?\n", given, nearest);
      after_option = e.find('=') == std::string::npos;
      continue;
    }
    if (!after_option)
      out += takes_output ? fmt::format("arcpress: unexpected argument '{}': {}; to write a file, use -o {}\n", e,
                                        positional, e)
                          : fmt::format("arcpress: unexpected argument '{}': {}\n", e, positional);
    after_option = false;
  }
  return out.empty() ? "arcpress: unexpected arguments (see --help)\n" : out;
}

struct DiffArgs {
  std::string a, b;
  double tolerance_mm = 0.01;
  std::string dialect = "rs274";
  bool dialect_given = false;  ///< --dialect on the command line
  std::string dialect_file;
  bool json = false;
  std::string plot;
  std::string plane = "xy";
  size_t top = 5;
  unsigned threads = 0;
  bool executed = false;  ///< compare the paths the dialect's firmware moves along (arcs as its chords)
  std::string band_side = "both";  ///< measure on which side of A the moves of B lie
  bool ignore_comments = false;    ///< leave comments out of the non-motion blocks compared
  std::string units;               ///< "mm", "inch": both programs' units until their G20 or G21
};

/// `arcpress diff A B`: any two programs, read the same way, compared by path, rapids,
/// non-motion blocks, feed and extrusion. Exit 0 the same within the band, 1 different.
/// `arcpress [IN] [-o OUT]`: one program, its messages on standard error.
int run_compress(const cli::CompressArgs& a) {
  cli::FileReport report;
  int code = 0;
  try {
    code = cli::compress_file(a, report);
  } catch (const Error&) {
    std::fputs(report.log.c_str(), stderr);
    throw;
  }
  std::fputs(report.log.c_str(), stderr);
  return code;
}

int run_diff(const DiffArgs& d) {
  std::string text_a = cli::read_input(d.a), text_b = cli::read_input(d.b);
  // Both programs are read the same way, in the dialect A would be compressed for.
  Dialect dialect = cli::dialect_for(d.dialect, d.dialect_given, d.dialect_file, text_a, d.a == "-" ? "" : d.a);
  cli::set_start_units(dialect, d.units);
  DiagnosticSink sa(d.a), sb(d.b);
  Program pa = lex(d.a, std::move(text_a), sa, lex_rules(dialect));
  Program pb = lex(d.b, std::move(text_b), sb, lex_rules(dialect));
  // Each read with the blocks its jumps enter (JumpTargets), as the compressor reads them.
  for (Program* p : {&pa, &pb}) {
    auto jumps = std::make_shared<JumpTargets>();
    jumps->read(p->text, 1);
    if (jumps->any()) p->jumps = std::move(jumps);
  }
  // Two files that are not programs have no paths to compare: never a SAME.
  for (auto [program, sink] : {std::pair{&pa, &sa}, std::pair{&pb, &sb}})
    if (const std::optional<ForeignContent> foreign = foreign_content(*program, true))
      sink->error(foreign->at, "E-INPUT-NOT-GCODE", fmt::format("does not look like G-code ({})", foreign->why));
  Interpretation ia = interpret(pa, sa, dialect), ib = interpret(pb, sb, dialect);
  const std::string diags = cli::diagnostics_text({&sa, &sb});
  if (!diags.empty()) std::fputs(diags.c_str(), stderr);
  if (sa.error_count() + sb.error_count() > 0) return kExitInput;
  DiffOptions opt;
  opt.tolerance_mm = d.tolerance_mm;
  opt.comments = !d.ignore_comments;
  opt.top = d.top;
  opt.threads = d.threads;
  // The block rate each demands, as written (before any arc is cut into chords).
  const BlockRate rate_a = block_rate(pa, ia, dialect.max_blocks_per_s, dialect.link_bytes_per_s);
  const BlockRate rate_b = block_rate(pb, ib, dialect.max_blocks_per_s, dialect.link_bytes_per_s);
  // The side, as compress() checks it, on the programmed paths: each move of B against the moves of A it replaces.
  std::optional<ProgramDiff::SideMeasure> side;
  if (const BandSide bs = cli::band_side_named(d.band_side); bs != BandSide::Both) {
    CompareOptions co;
    co.tolerance_mm = d.tolerance_mm;
    co.band_side = bs;
    const PathComparison c = compare_paths(pa, ia, pb, ib, co);
    side = ProgramDiff::SideMeasure{bs, c.matched, c.mismatch, c.max_wrong_side_mm,
                                    kBandSideRoundingShare * d.tolerance_mm, c.wrong_side_line_a, c.wrong_side_line_b};
  }
  if (d.executed) {
    cli::require_executed_rule(dialect, "--executed");
    if (has_executed_chords(ia, dialect.executed)) ia = executed_path(ia, dialect.executed);
    if (has_executed_chords(ib, dialect.executed)) ib = executed_path(ib, dialect.executed);
  }
  ProgramDiff r = diff_programs(pa, ia, pb, ib, opt);
  r.band_side = side;
  r.a.rate = rate_a;
  r.b.rate = rate_b;
  DiffNames names{d.a, d.b};
  // The report first: a plot that cannot be written (exit 3) never costs the verdict.
  cli::write_stdout(d.json ? diff_json(r, names, d.tolerance_mm) : diff_text(r, names, d.tolerance_mm));
  if (!d.plot.empty()) {
    Plane pl = d.plane == "zx" ? Plane::ZX : d.plane == "yz" ? Plane::YZ : Plane::XY;
    cli::write_output(d.plot, diff_svg(ia, ib, r, pl, d.tolerance_mm, names));
  }
  switch (r.verdict(d.tolerance_mm)) {
    case ProgramDiff::Verdict::Same: return kExitOk;
    case ProgramDiff::Verdict::Different: return kExitVerifyFailed;
    case ProgramDiff::Verdict::Incomplete: break;
  }
  return kExitInput;  // not all was compared: never a pass
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args = cli::start_process(argc, argv);
  cli::remove_temporary_files_on_signals();
  CLI::App app{
      "arcpress: replaces runs of short G1 moves in a G-code program with the fewest\n"
      "tangent-continuous lines and arcs (G2/G3) that stay within --tolerance of the\n"
      "original path. Everything that is not a G1 run passes through unchanged.\n\n"
      "  arcpress in.nc -o out.nc --tolerance 0.01\n"
      "  cat in.gcode | arcpress > out.gcode\n"
      "  arcpress *.gcode --in-place        arcpress jobs/ -o compressed/\n",
      "arcpress"};
  app.footer(kExitCodesHelp);
  // An argument such as C:\parts or /tmp/x.nc is a file, never an option, on every system.
  app.allow_windows_style_options(false);
  app.set_version_flag("--version", std::string("arcpress ") + kVersion + " (commit " + ARCPRESS_COMMIT +
                                        ")\nLicense GPL-3.0-or-later: this is free software; there is NO WARRANTY.");

  cli::CompressArgs a;
  cli::BatchArgs batch;
  app.add_option("input", batch.inputs,
                 "Input program; '-' or absent: standard input. Several programs, or a folder (searched "
                 "recursively), are compressed at once, with --in-place or -o FOLDER")
      ->type_name("FILE|FOLDER");
  app.add_option("-o,--output", a.output, "Output file; absent: standard output. For several programs or a "
                                          "folder: the folder they go to, under the same relative names");
  app.add_flag("--in-place", a.in_place, "Rewrite the input file(s) (atomically)");
  app.add_option("--glob", batch.glob, "A folder's files to compress: those whose name matches this pattern (* and "
                                       "?); default: G-code extensions (.gcode, .gco, .g, .nc, .ngc, .tap, .cnc, ...)")
      ->type_name("PATTERN");
  app.add_flag("--json", batch.json, "For several programs: the summary as JSON on standard output");
  app.add_option("--tolerance", a.opt.fit.tolerance_mm,
                 "Max distance in mm between output and input path, both ways")
      ->check(finite_in(kToleranceRange))->capture_default_str();
  CLI::Option* dialect_option =
      app.add_option("--dialect", a.dialect,
                     "Target controller dialect (see 'arcpress dialects'); absent: the one the program names for "
                     "itself (a slicer's gcode_flavor or FLAVOR line, a Heidenhain ISO program's %NAME G71 * block, a "
                     "Sinumerik program file's %_N_NAME_MPF line or .mpf/.spf extension), else rs274")
          ->type_name("NAME");
  app.add_option("--dialect-file", a.dialect_file, "Load the dialect from this TOML file instead");
  app.add_option("--arc-format", a.arc_format, "ijk: centre words; r: radius words where the dialect reads them "
                                                "(default: the dialect's choice)")
      ->check(CLI::IsMember({"ijk", "r"}));
  app.add_option("--method", a.method,
                 "keep: leave every G1 as it is; arcs: fit lines and arcs, fewest blocks; "
                 "global: as arcs, plus a wider search that finds fewer blocks on long smooth curves, slower; "
                 "greedy: fit lines and arcs one at a time, faster; stream: arcs through both end points grown "
                 "move by move in a bounded window, joints made tangent afterwards where the band allows (seed "
                 "method); lowe: lines found by recursive splitting rated by significance, then arcs over runs "
                 "of them, joints made tangent afterwards where the band allows (seed method)")
      ->check(CLI::IsMember({"keep", "arcs", "global", "greedy", "stream", "lowe"}))->capture_default_str();
  app.add_option("--g1-angle", a.opt.fit.g1_angle_deg, "Max tangent change in degrees at smooth joints")
      ->check(finite_in(kG1AngleRange))->capture_default_str();
  app.add_option("--corner-angle", a.opt.fit.corner_angle_deg,
                 "Input turns sharper than this (degrees) are corners, kept sharp")
      ->check(finite_in(kCornerAngleRange))->capture_default_str();
  app.add_flag("--spikes", a.opt.fit.spikes,
               "Treat a lone sharp jag within half the band of its neighbours' chord as noise, not a corner");
  app.add_option("--min-radius", a.opt.fit.min_radius_mm, "Arcs with a smaller radius (mm) become lines")
      ->check(finite_in(kMinRadiusRange))->capture_default_str();
  app.add_option("--max-radius", a.opt.fit.max_radius_mm, "Arcs with a larger radius (mm) become lines")
      ->check(finite_in(kMaxRadiusRange))->capture_default_str();
  app.add_option("--max-sweep", a.opt.fit.max_sweep_deg, "Max degrees one arc block may sweep")
      ->check(finite_in(kMaxSweepRange))->capture_default_str();
  app.add_option("--min-arc-length", a.opt.fit.min_arc_length_mm, "Shorter arcs (mm) become lines")
      ->check(finite_in(kMinArcLengthRange))->capture_default_str();
  app.add_option("--extrusion-variance", a.opt.fit.extrusion_variance,
                 "How much the E per mm of each move an arc or line replaces may differ from the arc's or line's own, "
                 "as a share of the larger rate (0.05: 5 %); extrusion starting or stopping always ends one")
      ->check(finite_in(kExtrusionVarianceRange))->capture_default_str();
  app.add_option("--band-side", a.band_side,
                 "left or right: every point of the output lies on that side of the input path (relative to the "
                 "direction of travel in the plane), or on it, within --tolerance; both: either side")
      ->check(CLI::IsMember({"left", "right", "both"}))->capture_default_str();
  app.add_option("--band", a.band,
                 "program: hold the band on the programmed path (arcs as circles); executed: on the chords the "
                 "dialect's firmware cuts each arc into (its [arcs.executed] rule); absent: executed where the "
                 "dialect names a rule")
      ->check(CLI::IsMember({"program", "executed"}));
  app.add_option("--units", a.units,
                 "The units a program is in until its first G20 or G21 (the controller's own setting at power-up); absent: "
                 "the dialect's (printers: mm; CNC controllers: mm, with a warning where a program gives a length "
                 "before G20 or G21)")
      ->check(CLI::IsMember({"mm", "inch"}));
  bool no_header = false;
  app.add_flag("--no-header", no_header,
               "Write no comment naming arcpress, its version and options after the program's first line (written "
               "where that line is a comment, as a slicer's is)");
  bool no_helical = false;
  app.add_flag("--no-helical", no_helical, "Never move the plane's normal axis inside an arc");
  app.add_flag("--passthrough", a.opt.passthrough, "Read and write the program back unchanged");
  app.add_flag("--strict", a.opt.strict, "Refuse (exit 2) any block that cannot be read");
  app.add_option("-j,--threads", a.opt.threads, "Threads fitting runs and verifying at once; 0: one per "
                                                "hardware thread (the output is the same for any count). For "
                                                "several programs: programs at once, each on one thread")
      ->check(CLI::Range(0u, 1024u))->capture_default_str();
  app.add_flag("--stats", a.stats, "Print counts, sizes and the measured deviation to standard error");
  app.add_flag("-q,--quiet", a.quiet, "Show no progress line (errors and warnings are still printed)");
  app.add_flag("--progress", a.progress,
               "Show the progress line on standard error even where it is no terminal (it is shown on a terminal "
               "for inputs over 4 MB)");
  app.add_flag("--stream", a.stream,
               "From a pipe, write output as the input comes instead of reading it to its end first (into a "
               "temporary file): then a jump back past what was read, or one that would run a loop's first moves "
               "in other modes, fails, and subprograms after the program's end are not read");
  bool no_verify = false;
  app.add_flag("--no-verify", no_verify, "Skip reading the output back and measuring it against the input");

  DiffArgs diff;
  CLI::App* diff_cmd = app.add_subcommand(
      "diff",
      "Compare two programs: feed paths (both ways, exactly), rapids, M/T/S/dwell/comment blocks, feed and "
      "extrusion; exit 0 when they agree within the band, 1 when not, 2 when not all could be compared");
  diff_cmd->add_option("A", diff.a, "Reference program")->required();
  diff_cmd->add_option("B", diff.b, "Program to check against A")->required();
  diff_cmd->add_option("--tolerance", diff.tolerance_mm, "Band in mm")
      ->check(finite_in(kToleranceRange))
      ->capture_default_str();
  CLI::Option* diff_dialect_option =
      diff_cmd
          ->add_option("--dialect", diff.dialect,
                       "How both programs are read; absent: the dialect A names for itself (a slicer's flavor "
                       "line, a Heidenhain ISO program's %NAME G71 * block, a Sinumerik program file's %_N_NAME_MPF "
                       "line or .mpf/.spf extension), else rs274")
          ->type_name("NAME");
  diff_cmd->add_option("--dialect-file", diff.dialect_file, "Read both programs with this dialect file");
  diff_cmd->add_option("--units", diff.units,
                       "The units both programs are in until their first G20 or G21; absent: the dialect's")
      ->check(CLI::IsMember({"mm", "inch"}));
  diff_cmd->add_flag("--ignore-comments", diff.ignore_comments,
                     "Compare M, T, S and dwell blocks but not comments (another tool's output, with header "
                     "comments of its own)");
  diff_cmd->add_flag("--executed", diff.executed,
                     "Compare the paths the dialect's firmware really moves along: every arc of both programs cut "
                     "into the chords of its [arcs.executed] rule");
  diff_cmd->add_option("--band-side", diff.band_side,
                       "left or right: also measure how far B lies on the other side of A, move by move (B's "
                       "moves must end on A's vertices, as arcpress writes them; otherwise the verdict is "
                       "INCOMPLETE)")
      ->check(CLI::IsMember({"left", "right", "both"}))->capture_default_str();
  diff_cmd->add_flag("--json", diff.json, "Print one JSON document instead of text");
  diff_cmd->add_option("--plot", diff.plot, "Write an SVG picture of both paths, B coloured by deviation");
  diff_cmd->add_option("--plane", diff.plane, "Plane of the picture")->check(CLI::IsMember({"xy", "zx", "yz"}))
      ->capture_default_str();
  diff_cmd->add_option("--top", diff.top, "How many worst places to list")->check(CLI::Range(1, 1000))
      ->capture_default_str();
  diff_cmd->add_option("-j,--threads", diff.threads, "Threads measuring the two directions at once; 0: as the "
                                                    "machine has (the result is the same for any count)")
      ->check(CLI::Range(0u, 1024u))->capture_default_str();
  diff_cmd->footer(kDiffExitCodesHelp);

  CLI::App* dialects_cmd = app.add_subcommand("dialects", "List the controller dialects, one line each");

  // Help and version go to standard output; a write that fails there is an I/O error.
  auto printed = [](int code) {
    std::cout.flush();
    if (std::cout.good()) return code;
    std::fputs("arcpress: cannot write standard output\n", stderr);
    return int(kExitIo);
  };
  try {
    std::reverse(args.begin(), args.end());  // (CLI11 takes them last first)
    args.pop_back();                          // the program's own name
    app.parse(args);
  } catch (const CLI::CallForHelp& e) {
    return printed(app.exit(e));
  } catch (const CLI::CallForAllHelp& e) {
    return printed(app.exit(e));
  } catch (const CLI::Success& e) {
    return printed(app.exit(e));
  } catch (const CLI::ExtrasError&) {
    const bool in_diff = diff_cmd->parsed();
    std::fputs((in_diff ? explain_extras(*diff_cmd, diff_cmd->remaining(), "diff compares two programs, A and B", false)
                        : explain_extras(app, app.remaining(), "arcpress reads programs", true))
                   .c_str(),
               stderr);
    return kExitInput;
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitInput;
  }
  a.opt.fit.helical = !no_helical;
  a.opt.header = !no_header;
  a.dialect_given = dialect_option->count() > 0;
  diff.dialect_given = diff_dialect_option->count() > 0;
  a.opt.verify = !no_verify;
  try {
    if (*diff_cmd) return run_diff(diff);
    if (*dialects_cmd) {
      auto path = dialect_search_path(cli::exe_dir());
      std::string list;
      for (const Dialect& d : list_dialects(path)) list += fmt::format("{:<16}{}\n", d.name, d.description);
      cli::write_stdout(list);
      return kExitOk;
    }
    // Nothing to read but a terminal: say how to use it rather than wait for typing.
    if (cli::is_batch(batch.inputs)) {
      batch.jobs = a.opt.threads;
      return cli::run_batch(a, batch);
    }
    if (batch.json) throw Error(kExitInput, "--json is for several programs (a summary); see --stats");
    if (!batch.glob.empty()) throw Error(kExitInput, "--glob is for folders");
    a.input = batch.inputs.empty() ? "-" : batch.inputs.front();
    if (a.input == "-" && cli::is_terminal(0)) {
      std::fputs(app.help().c_str(), stderr);
      std::fputs("arcpress: no input: give a program file, or pipe one into standard input\n", stderr);
      return kExitInput;
    }
    return run_compress(a);
  } catch (const Error& e) {
    fmt::print(stderr, "arcpress: {}\n", e.what());
    return e.exit_code();
  } catch (const std::exception& e) {
    fmt::print(stderr, "arcpress: internal error: {}\n", e.what());
    return kExitIo;
  }
}
