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
    "  2  INCOMPLETE: some feed moves could not be placed and were not compared; or a usage\n"
    "     error, or input that cannot be read\n"
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
                    std::string_view tail = {}, std::string* why = nullptr) {
  std::string reason = !file.empty() ? "--dialect-file" : name_given ? "--dialect" : "the default";
  std::string picked = name;
  if (file.empty() && !name_given) {
    // `tail`: the end of a program of which `program` is the start (a slicer's config block
    // is at the end); its first line may be cut.
    const size_t nl = tail.find('\n');
    const std::string_view tail_lines = nl == std::string_view::npos ? std::string_view() : tail.substr(nl + 1);
    std::optional<ProgramFlavor> flavor = program_flavor(program);
    const bool at_end = !flavor && (flavor = program_flavor(tail_lines));
    if (flavor) {
      const std::string where = at_end ? fmt::format("the program's '{}' near its end", flavor->evidence)
                                       : fmt::format("the program's '{}' at line {}", flavor->evidence, flavor->line);
      if (flavor->dialect.empty()) {
        reason = fmt::format("the default: {} names no single firmware (pass --dialect {})", where,
                             fmt::join(flavor_dialects(), ", "));
      } else {
        picked = flavor->dialect;
        reason = where;
      }
    }
  }
  if (why) *why = reason;
  return !file.empty() ? load_dialect_file(file) : find_dialect(picked, dialect_search_path(exe_dir()));
}

/// Throws Error(kExitInput), naming `option`, unless `dialect` names the arc segmentation
/// its firmware moves along.
void require_executed_rule(const Dialect& dialect, const char* option) {
  if (!dialect.executed.moves_on_chords())
    throw Error(kExitInput, fmt::format("{}: dialect {} names no arc segmentation ([arcs.executed] rule); its "
                                        "controller moves on the programmed circles",
                                        option, dialect.name));
}

struct CompressArgs {
  std::string input = "-";
  std::string output;
  std::string dialect = "rs274";
  bool dialect_given = false;  ///< --dialect on the command line
  std::string dialect_file;
  std::string arc_format;
  std::string method = "arcs";
  std::string band;  ///< "program", "executed"; empty: the dialect's choice
  bool in_place = false;
  bool stats = false;
  bool quiet = false;
  bool progress = false;
  CompressOptions opt;
};

/// How much of a program is searched for a slicer's flavor line, at its start and its end.
constexpr size_t kFlavorBytes = size_t(1) << 20;
/// ... at the start of a program read from a pipe (Cura names it on its first line).
constexpr size_t kFlavorPipeBytes = size_t(1) << 16;
/// How much of the input is read at once.
constexpr size_t kReadBytes = size_t(1) << 20;

int run_compress(const CompressArgs& a) {
  std::string out_path = a.output;
  if (a.in_place) {
    if (a.input == "-") throw Error(kExitInput, "--in-place needs an input file, not standard input");
    if (!out_path.empty()) throw Error(kExitInput, "--in-place and -o cannot be used together");
    out_path = a.input;
  } else if (out_path.empty()) {
    out_path = "-";
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
  if (a.arc_format == "ijk") opt.arc_format = ArcFormat::Centre;
  if (a.arc_format == "r") opt.arc_format = ArcFormat::Radius;

  auto t0 = std::chrono::steady_clock::now();
  cli::InputFile input(a.input);
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
  opt.dialect = dialect_for(a.dialect, a.dialect_given, a.dialect_file, chunk,
                            head == 0 || chunk.size() < head ? std::string() : input.tail(kFlavorBytes), &why_dialect);
  if (opt.band == CompressOptions::Band::Executed) require_executed_rule(opt.dialect, "--band executed");
  DiagnosticSink sink(name);
  Compressor compressor(name, opt, sink);
  cli::OutputFile out(out_path);
  cli::Progress progress(size, a.quiet, a.progress);
  // Read, compress and write as the input comes: each piece's text is written once it and
  // everything before it are done.
  std::string text;
  for (size_t read = 0; compressor.result().ok;) {
    if (chunk.empty() && input.read(chunk, kReadBytes) == 0) break;
    read += chunk.size();
    compressor.push(chunk);
    chunk.clear();
    text.clear();
    if (compressor.take(text) > 0) out.write(text);
    progress.update(read);
  }
  compressor.finish();
  text.clear();
  if (compressor.take(text) > 0) out.write(text);
  progress.clear();
  const CompressResult& r = compressor.result();
  const std::string diags = diagnostics_text({&sink});
  if (!diags.empty()) std::fputs(diags.c_str(), stderr);
  // Where the output cannot be used, it is taken back: a file is left as it was.
  auto nothing_written = [&] {
    const size_t left = out.discard();
    if (left == 0) fmt::print(stderr, "arcpress: nothing written\n");
    else fmt::print(stderr, "arcpress: {} bytes had been written to '{}' before the failure; do not use them\n", left,
                    out_path == "-" ? "standard output" : out_path);
  };
  if (!r.ok) {
    fmt::print(stderr, "arcpress: {} error(s) in '{}'\n", sink.error_count(), name);
    nothing_written();
    return kExitInput;
  }
  if (!r.within_band()) {
    const ProgramDiff& c = r.check;
    if (!r.comparison.matched) fmt::print(stderr, "arcpress: verification failed: {}\n", r.comparison.mismatch);
    if (c.max_deviation_mm > r.band_mm || r.comparison.max_deviation_mm > r.band_mm) {
      DiffPlace w = c.worst.empty() ? DiffPlace{} : c.worst.front();
      fmt::print(stderr,
                 "arcpress: verification failed: output deviates {:.6f} mm from the input (band {:.6f} mm) at "
                 "X{:.4f} Y{:.4f} Z{:.4f}, input line {}, output line {}\n",
                 std::max(c.max_deviation_mm, r.comparison.max_deviation_mm), r.band_mm, w.at.x(), w.at.y(), w.at.z(),
                 w.line_a, w.line_b);
    }
    if (c.max_rapid_mm > r.band_mm)
      fmt::print(stderr, "arcpress: verification failed: a rapid ends {:.6f} mm away, input line {}, output line {}\n",
                 c.max_rapid_mm, c.worst_rapid.line_a, c.worst_rapid.line_b);
    for (const std::string& f : c.findings) fmt::print(stderr, "arcpress: verification failed: {}\n", f);
    nothing_written();
    return kExitVerifyFailed;
  }
  out.commit();
  if (a.stats) {
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const auto& st = r.stats;
    fmt::print(stderr,
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
    // The G1 moves left as they are, by reason, with the first place of each.
    for (const NotFitted& n : r.not_fitted)
      fmt::print(stderr, "  not fitted     {} G1 move{}: {}{} (first at line {})\n", n.moves, n.moves == 1 ? "" : "s",
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
      fmt::print(stderr,
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
    } else {
      fmt::print(stderr,
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
      fmt::print(stderr, "  forced at      input line{} {}{}\n", at.size() > 1 ? "s" : "", fmt::join(first, ", "),
                 at.size() > kShown ? fmt::format(", ... ({} in all)", at.size()) : std::string());
    }
  }
  return kExitOk;
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
};

/// `arcpress diff A B`: any two programs, read the same way, compared by path, rapids,
/// non-motion blocks, feed and extrusion. Exit 0 the same within the band, 1 different.
int run_diff(const DiffArgs& d) {
  std::string text_a = cli::read_input(d.a), text_b = cli::read_input(d.b);
  // Both programs are read the same way, in the dialect A would be compressed for.
  const Dialect dialect = dialect_for(d.dialect, d.dialect_given, d.dialect_file, text_a);
  DiagnosticSink sa(d.a), sb(d.b);
  Program pa = lex(d.a, std::move(text_a), sa);
  Program pb = lex(d.b, std::move(text_b), sb);
  // Two files that are not programs have no paths to compare: never a SAME.
  for (auto [program, sink] : {std::pair{&pa, &sa}, std::pair{&pb, &sb}})
    if (const std::optional<ForeignContent> foreign = foreign_content(*program, true))
      sink->error(foreign->at, "E-INPUT-NOT-GCODE", fmt::format("does not look like G-code ({})", foreign->why));
  Interpretation ia = interpret(pa, sa, dialect), ib = interpret(pb, sb, dialect);
  const std::string diags = diagnostics_text({&sa, &sb});
  if (!diags.empty()) std::fputs(diags.c_str(), stderr);
  if (sa.error_count() + sb.error_count() > 0) return kExitInput;
  DiffOptions opt;
  opt.tolerance_mm = d.tolerance_mm;
  opt.top = d.top;
  opt.threads = d.threads;
  if (d.executed) {
    require_executed_rule(dialect, "--executed");
    if (has_executed_chords(ia, dialect.executed)) ia = executed_path(ia, dialect.executed);
    if (has_executed_chords(ib, dialect.executed)) ib = executed_path(ib, dialect.executed);
  }
  ProgramDiff r = diff_programs(pa, ia, pb, ib, opt);
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
      "  cat in.gcode | arcpress > out.gcode\n",
      "arcpress"};
  app.footer(kExitCodesHelp);
  // An argument such as C:\parts or /tmp/x.nc is a file, never an option, on every system.
  app.allow_windows_style_options(false);
  app.set_version_flag("--version", std::string("arcpress ") + kVersion + " (commit " + ARCPRESS_COMMIT +
                                        ")\nLicense GPL-3.0-or-later: this is free software; there is NO WARRANTY.");

  CompressArgs a;
  app.add_option("input", a.input, "Input program; '-' or absent: standard input");
  app.add_option("-o,--output", a.output, "Output file; absent: standard output");
  app.add_flag("--in-place", a.in_place, "Rewrite the input file (atomically)");
  app.add_option("--tolerance", a.opt.fit.tolerance_mm,
                 "Max distance in mm between output and input path, both ways")
      ->check(finite_in(kToleranceRange))->capture_default_str();
  CLI::Option* dialect_option =
      app.add_option("--dialect", a.dialect,
                     "Target controller dialect (see 'arcpress dialects'); absent: the one the program names for "
                     "itself (a slicer's gcode_flavor or FLAVOR line), else rs274")
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
                 "How much E per mm may vary between neighbouring moves inside one arc or line, as a share of the "
                 "larger rate (0.05: 5 %); extrusion starting or stopping always ends one")
      ->check(finite_in(kExtrusionVarianceRange))->capture_default_str();
  app.add_option("--band", a.band,
                 "program: hold the band on the programmed path (arcs as circles); executed: on the chords the "
                 "dialect's firmware cuts each arc into (its [arcs.executed] rule); absent: executed where the "
                 "dialect names a rule")
      ->check(CLI::IsMember({"program", "executed"}));
  bool no_header = false;
  app.add_flag("--no-header", no_header,
               "Write no comment naming arcpress, its version and options after the program's first line (written "
               "where that line is a comment, as a slicer's is)");
  bool no_helical = false;
  app.add_flag("--no-helical", no_helical, "Never move the plane's normal axis inside an arc");
  app.add_flag("--passthrough", a.opt.passthrough, "Read and write the program back unchanged");
  app.add_flag("--strict", a.opt.strict, "Refuse (exit 2) any block that cannot be read");
  app.add_option("-j,--threads", a.opt.threads, "Threads fitting runs and verifying at once; 0: one per "
                                                "hardware thread (the output is the same for any count)")
      ->check(CLI::Range(0u, 1024u))->capture_default_str();
  app.add_flag("--stats", a.stats, "Print counts, sizes and the measured deviation to standard error");
  app.add_flag("-q,--quiet", a.quiet, "Show no progress line (errors and warnings are still printed)");
  app.add_flag("--progress", a.progress,
               "Show the progress line on standard error even where it is no terminal (it is shown on a terminal "
               "for inputs over 4 MB)");
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
                       "line), else rs274")
          ->type_name("NAME");
  diff_cmd->add_option("--dialect-file", diff.dialect_file, "Read both programs with this dialect file");
  diff_cmd->add_flag("--executed", diff.executed,
                     "Compare the paths the dialect's firmware really moves along: every arc of both programs cut "
                     "into the chords of its [arcs.executed] rule");
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
                        : explain_extras(app, app.remaining(), "arcpress reads one program", true))
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
      auto path = dialect_search_path(exe_dir());
      std::string list;
      for (const Dialect& d : list_dialects(path)) list += fmt::format("{:<16}{}\n", d.name, d.description);
      cli::write_stdout(list);
      return kExitOk;
    }
    // Nothing to read but a terminal: say how to use it rather than wait for typing.
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
