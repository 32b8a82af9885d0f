// SPDX-License-Identifier: GPL-3.0-or-later
// The fitter's guarantees on every run of every corpus file, measured by reading the
// output back: inside the band, ending on the input path, non-motion lines untouched.
#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <iterator>

#include "arcpress/api/arcpress.hpp"
#include "arcpress/dialect/dialect_loader.hpp"
#include "arcpress/dialect/program_flavor.hpp"
#include "arcpress/lex/lexer.hpp"
#include "support.hpp"

using namespace arcpress;

namespace {

/// The raw text of every block that does not move an axis, in order.
/// The lines of a program that do not move, without the bare G17/G18/G19 blocks (after a
/// block number at most; counted in `plane_lines`), which arcpress writes around runs it fits
/// in another plane, and without its header comment (after a slicer's first line).
std::vector<std::string> non_motion_lines(const std::string& text, size_t& plane_lines) {
  DiagnosticSink sink;
  Program p = lex("x", text, sink);
  std::vector<std::string> out;
  plane_lines = 0;
  for (const auto& b : p.blocks) {
    bool moves = false;
    for (auto* w = p.words_begin(b); w != p.words_end(b); ++w)
      moves |= std::string_view("XYZABCUVWEIJKR").find(w->letter) != std::string_view::npos && !w->flag;
    std::string_view raw = p.raw(b);
    if (is_arcpress_header(raw)) continue;
    const Word* g = b.word_count == 2 && p.words_begin(b)->letter == 'N' ? p.words_begin(b) + 1 : p.words_begin(b);
    if (!b.has_comment && (b.word_count == 1 || g != p.words_begin(b)) && g->letter == 'G' && !g->is_expr &&
        (g->value == 17 || g->value == 18 || g->value == 19)) {
      ++plane_lines;
      continue;
    }
    if (!moves || b.kind != BlockKind::Code) out.emplace_back(raw);
  }
  return out;
}

/// `text` (corpus file `f`) compressed for `dialect` at `band_mm`, inside the band.
CompressResult compressed(const std::filesystem::path& f, const std::string& text, const Dialect& dialect,
                          double band_mm) {
  DiagnosticSink sink(f.string());
  CompressOptions opt;
  opt.dialect = dialect;
  opt.fit.tolerance_mm = band_mm;
  CompressResult r = compress(f.string(), text, opt, sink);
  REQUIRE(r.within_band());
  return r;
}

/// `text` (corpus file `f`) compressed for `dialect` at `band_mm` stays inside the band, and
/// arcpress diff finds it the same as the input there, the feed included.
void compressed_agrees_with_diff(const std::filesystem::path& f, const std::string& text, const Dialect& dialect,
                                 double band_mm) {
  const CompressResult r = compressed(f, text, dialect, band_mm);
  DiffOptions dopt;
  dopt.tolerance_mm = band_mm;
  const ProgramDiff d = test::diff_texts(text, r.output, dopt, dialect);
  INFO(fmt::format("{}", fmt::join(d.findings, "; ")));
  CHECK(d.agrees(band_mm));
  CHECK(d.max_feed_difference_pct == 0.0);
  CHECK(d.feed_unpaired_mm == 0);  // every piece within the band found its counterpart
}

/// The dialect a program names for itself (a slicer's flavor line), else rs274, as the
/// command picks it.
Dialect own_dialect(const std::string& text) {
  const std::optional<ProgramFlavor> flavor = program_flavor(text);
  return find_dialect(flavor && !flavor->dialect.empty() ? flavor->dialect : "rs274", {ARCPRESS_SOURCE_DIR "/dialects"});
}

/// compressed_agrees_with_diff() for every corpus file, in the dialect it names.
void every_corpus_file_agrees_with_diff(double band_mm) {
  ARCPRESS_CORPUS_FILES_OR_SKIP(files)
  for (const auto& f : files) {
    const std::string text = test::read_file(f);
    INFO(f.string());
    compressed_agrees_with_diff(f, text, own_dialect(text), band_mm);
  }
}

/// Over every corpus file: compressed with `candidate`, it keeps the band, and has no more
/// forced kinks than with `reference`, and with as many, no more blocks. The files where it
/// has fewer of either.
size_t files_better(const std::vector<std::filesystem::path>& files, const CompressOptions& candidate,
                    const CompressOptions& reference) {
  size_t better = 0;
  for (const auto& f : files) {
    INFO(f.string());
    const std::string text = test::read_file(f);
    DiagnosticSink sink(f.string());
    const CompressResult c = compress(f.string(), text, candidate, sink), r = compress(f.string(), text, reference, sink);
    INFO(c.comparison.mismatch);
    REQUIRE(c.ok);
    REQUIRE(c.verified);
    REQUIRE(c.within_band());
    const size_t blocks_c = c.stats.lines_out + c.stats.arcs_out, blocks_r = r.stats.lines_out + r.stats.arcs_out;
    CHECK(c.forced_kinks <= r.forced_kinks);
    if (c.forced_kinks == r.forced_kinks) CHECK(blocks_c <= blocks_r);
    better += c.forced_kinks < r.forced_kinks || blocks_c < blocks_r;
  }
  return better;
}

}  // namespace

TEST_CASE("every corpus file compresses inside the band with its non-motion lines untouched, and every "
          "smooth joint that turns by more than the G1 angle is one the fitter reports as forced by the band",
          "[corpus][fit]") {
  ARCPRESS_CORPUS_FILES_OR_SKIP(files)
  size_t moves_in = 0, blocks_out = 0, arcs = 0;
  for (double tol : {0.01, 0.002}) {
    for (const auto& f : files) {
      INFO(fmt::format("{} at tolerance {} mm", f.string(), tol));
      std::string text = test::read_file(f);
      DiagnosticSink sink(f.string());
      CompressOptions opt;
      opt.fit.tolerance_mm = tol;
      auto r = compress(f.string(), text, opt, sink);
      REQUIRE(r.ok);
      REQUIRE(r.verified);
      INFO(r.comparison.mismatch);
      CHECK(r.comparison.matched);
      CHECK(r.comparison.max_deviation_mm <= tol);
      size_t planes_in = 0, planes_out = 0;
      CHECK(non_motion_lines(r.output, planes_out) == non_motion_lines(text, planes_in));
      CHECK(planes_out == planes_in + r.stats.plane_words_added);
      // Joints as the output reads back (after rounding), against the fitter's own account;
      // joints between runs, and between a run and a lone move, count as much as any.
      const std::vector<uint32_t> unreported = r.unforced_kink_lines();
      INFO(fmt::format("kinks over {} deg at input lines {} that the fitter did not report as forced",
                       opt.fit.g1_angle_deg, fmt::join(unreported.begin(), unreported.begin() + std::min<size_t>(unreported.size(), 20), " ")));
      CHECK(unreported.empty());
      if (tol == 0.01) {
        moves_in += r.stats.moves_in;
        blocks_out += r.stats.lines_out + r.stats.arcs_out;
        arcs += r.stats.arcs_out;
      }
    }
  }
  // The corpus has long smooth runs: the fitter must actually compress them.
  CHECK(arcs > 10000);
  CHECK(double(blocks_out) < 0.8 * double(moves_in));
}

TEST_CASE("the global method keeps the band on every corpus file and is never worse than the default: "
          "no more forced kinks, and with as many, no more blocks",
          "[corpus][fit][global]") {
  ARCPRESS_CORPUS_FILES_OR_SKIP(files)
  CompressOptions global;
  global.fit.method = FitOptions::Method::Global;
  CHECK(files_better(files, global, CompressOptions{}) > 0);
}

TEST_CASE("the default's first search, for a chain of as few primitives as a chain with a corner at every joint "
          "needs, costs no corpus file a forced kink or a block, and saves blocks on some",
          "[corpus][fit][search]") {
  ARCPRESS_CORPUS_FILES_OR_SKIP(files)
  CompressOptions with, without;
  with.fit.tolerance_mm = without.fit.tolerance_mm = 0.05;
  without.fit.bound_search = false;
  CHECK(files_better(files, with, without) > 0);
}

TEST_CASE("runs fitted, and their blocks composed, on several threads give the same program as on one thread",
          "[corpus][fit][emit][threads]") {
  ARCPRESS_CORPUS_FILES_OR_SKIP(files)
  size_t runs = 0;
  for (const auto& f : files) {
    INFO(f.string());
    std::string text = test::read_file(f);
    DiagnosticSink sink(f.string());
    CompressOptions one, many;
    one.verify = many.verify = false;
    one.threads = 1;
    many.threads = 4;  // more than the runs of the smallest files, fewer than those of the largest
    auto a = compress(f.string(), text, one, sink);
    auto b = compress(f.string(), text, many, sink);
    REQUIRE(a.ok);
    REQUIRE(b.ok);
    CHECK(b.output == a.output);
    CHECK(b.forced_kinks == a.forced_kinks);
    CHECK(b.stats.rule_joints == a.stats.rule_joints);
    runs += a.stats.runs;
  }
  CHECK(runs > 1000);  // threads had runs to share
}

TEST_CASE("arcpress diff finds every printer corpus file the same as its output in a wide band, read as a "
          "controller that takes I and J for the absolute centre or for the offset",
          "[corpus][diff]") {
  // In a band of 0.05 mm an arc written over one short move of a slicer's perimeter heads
  // far off that move, and the wipe that retraces the perimeter passes within the band:
  // the feed is still compared with the perimeter's own move.
  ARCPRESS_CORPUS_FILES_OR_SKIP(files)
  for (const char* name : {"heidenhain-iso", "fanuc"}) {
    const Dialect dialect = load_dialect_file(ARCPRESS_SOURCE_DIR "/dialects/" + std::string(name) + ".toml");
    for (const auto& f : files) {
      if (f.parent_path().filename() != "printer") continue;
      INFO(fmt::format("{} read as {}", f.string(), name));
      compressed_agrees_with_diff(f, test::read_file(f), dialect, 0.05);
    }
  }
}

TEST_CASE("arcpress diff finds every corpus file the same as its output in a band as wide as a printed line",
          "[corpus][diff]") {
  // At 0.2 mm the band reaches the neighbouring lines of a print and the travels that
  // cross them: a printed move is compared with a printed one, a travel with a travel.
  every_corpus_file_agrees_with_diff(0.2);
}

TEST_CASE("arcpress diff finds every corpus file the same as its output in a band five printed layers deep",
          "[corpus][diff]") {
  // At 1 mm the band reaches the lines printed a layer or a pass later, at other feeds, and
  // an arc that rounds a corner of short moves heads far off each of them: a piece is paired
  // with the moves as far along the input as it is along the output, and where moves are
  // shorter than the band, a feed change a few moves away leaves the feed there ambiguous.
  every_corpus_file_agrees_with_diff(1.0);
}

TEST_CASE("a feed set 10 % lower on one block of the output is found at that block's line, in a band up to five "
          "printed layers deep",
          "[corpus][diff]") {
  // Three places in each printer file's output: the block's feed goes down, and the next
  // block's is set back. (A block within a band's width, along the path, of a change of the
  // input's own feed would be ambiguous, and not compared: PrusaSlicer 2.7, ps271, changes
  // the feed every few moves; these places lie farther from one.)
  ARCPRESS_CORPUS_FILES_OR_SKIP(files)
  auto starts_motion = [](std::string_view l) {
    return l.size() > 3 && l[0] == 'G' && l[1] >= '1' && l[1] <= '3' && l[2] == ' ';
  };
  for (const auto& f : files) {
    if (f.parent_path().filename() != "printer") continue;
    const std::string text = test::read_file(f);
    const Dialect dialect = own_dialect(text);
    for (double band_mm : {0.05, 1.0}) {
      const CompressResult r = compressed(f, text, dialect, band_mm);
      std::vector<std::string> lines;
      for (size_t at = 0, end; at < r.output.size(); at = end + 1) {
        end = std::min(r.output.find('\n', at), r.output.size());
        lines.emplace_back(r.output.substr(at, end - at));
      }
      // Blocks that move along X or Y at the feed set before them, followed by another such.
      std::vector<std::pair<size_t, double>> places;
      double feed = 0;
      for (size_t i = 0; i + 1 < lines.size(); ++i) {
        const std::string& l = lines[i];
        if (const size_t at = l.find('F'); at != std::string::npos && l[0] == 'G' && l.find(';') > at)
          feed = std::stod(l.substr(at + 1));
        if (feed > 0 && starts_motion(l) && starts_motion(lines[i + 1]) && l.find('F') == std::string::npos &&
            lines[i + 1].find('F') == std::string::npos && l.find_first_of("XY") != std::string::npos)
          places.emplace_back(i, feed);
      }
      REQUIRE(places.size() > 10);
      for (double share : {0.3, 0.5, 0.7}) {
        const auto [i, was] = places[size_t(share * double(places.size()))];
        std::vector<std::string> changed = lines;
        changed[i] += fmt::format(" F{:.3f}", 0.9 * was);
        changed[i + 1] += fmt::format(" F{:.3f}", was);
        INFO(fmt::format("{} at {} mm, line {}: {}", f.string(), band_mm, i + 1, changed[i]));
        DiffOptions dopt;
        dopt.tolerance_mm = band_mm;
        const ProgramDiff d = test::diff_texts(text, fmt::format("{}", fmt::join(changed, "\n")), dopt, dialect);
        CHECK(d.verdict(band_mm) == ProgramDiff::Verdict::Different);
        CHECK(d.max_feed_difference_pct == Approx(10.0).epsilon(1e-3));
        CHECK(d.worst_feed.line_b == i + 1);
      }
    }
  }
}
