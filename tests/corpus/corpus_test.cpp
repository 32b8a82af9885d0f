// SPDX-License-Identifier: GPL-3.0-or-later
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include "arcpress/api/arcpress.hpp"
#include "arcpress/dialect/dialect_loader.hpp"
#include "arcpress/dialect/program_flavor.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress_commit.hpp"
#include "support.hpp"

using namespace arcpress;

TEST_CASE("every corpus file passes through byte for byte", "[corpus][passthrough]") {
  ARCPRESS_CORPUS_FILES_OR_SKIP(files)
  for (const auto& f : files) {
    INFO(f.string());
    std::string text = test::read_file(f);
    DiagnosticSink sink(f.string());
    CompressOptions opt;
    opt.passthrough = true;
    auto r = compress(f.string(), text, opt, sink);
    REQUIRE(r.ok);
    CHECK(r.output.size() == text.size());
    CHECK(r.output == text);
  }
}

TEST_CASE("with the keep method every corpus file comes out unchanged through the whole pipeline",
          "[corpus][pipeline]") {
  ARCPRESS_CORPUS_FILES_OR_SKIP(files)
  size_t runs = 0;
  for (const auto& f : files) {
    INFO(f.string());
    std::string text = test::read_file(f);
    DiagnosticSink sink(f.string());
    CompressOptions opt;
    opt.fit.method = FitOptions::Method::Keep;
    opt.header = false;  // (the one line arcpress adds: below)
    auto r = compress(f.string(), text, opt, sink);
    REQUIRE(r.ok);
    CHECK(r.output == text);
    runs += r.stats.runs;
  }
  CHECK(runs > 1000);  // the pipeline found runs to work on
}

TEST_CASE("the header comment naming arcpress goes after a first line that is a comment (a slicer's), once, and "
          "nowhere else",
          "[corpus][pipeline]") {
  ARCPRESS_CORPUS_FILES_OR_SKIP(files)
  size_t headed = 0;
  for (const auto& f : files) {
    INFO(f.string());
    const std::string text = test::read_file(f);
    DiagnosticSink sink(f.string());
    CompressOptions opt;
    opt.fit.method = FitOptions::Method::Keep;
    auto r = compress(f.string(), text, opt, sink);
    REQUIRE(r.ok);
    const size_t eol = text.find('\n');
    const char lead = text[text.find_first_not_of(" \t")];
    const bool slicer = text.find_first_not_of(" \t") < eol && (lead == ';' || lead == '(');
    if (!slicer) {
      CHECK(r.output == text);
      continue;
    }
    ++headed;
    // The input with one line more, after its first: the header, in the first line's comment
    // form, naming arcpress's version and options.
    const size_t header_end = r.output.find('\n', eol + 1);
    const std::string header = r.output.substr(eol + 1, header_end - eol - 1);
    CHECK(is_arcpress_header(header));
    CHECK(header[0] == lead);
    CHECK(header.find(std::string("arcpress ") + kVersion + " commit " + ARCPRESS_COMMIT + " --tolerance 0.01 --dialect ") !=
          std::string::npos);
    CHECK(r.output.substr(0, eol + 1) + r.output.substr(header_end + 1) == text);
    // Run again, it is not repeated.
    auto again = compress(f.string(), r.output, opt, sink);
    CHECK(again.output == r.output);
  }
  CHECK(headed >= 5);  // the slicers' files, and CAM files that open with a comment
}

TEST_CASE("strict mode reads every corpus file but for unexpanded slicer templates",
          "[corpus][lex]") {
  ARCPRESS_CORPUS_FILES_OR_SKIP(files)
  for (const auto& f : files) {
    INFO(f.string());
    DiagnosticSink sink(f.string());
    CompressOptions opt;
    opt.passthrough = true;
    opt.strict = true;
    // A lathe program read as a mill's has arcs no mill can run (X in diameters).
    if (f.filename().string().rfind("haas-lathe", 0) == 0)
      opt.dialect = load_dialect_file(ARCPRESS_SOURCE_DIR "/dialects/haas-lathe.toml");
    // Read in the units their machines start in, where a program never states them (the
    // warning that it does not is true, and no matter of reading): LinuxCNC's engraving
    // sample in inches (its sample configurations' nc_files), printers' in mm.
    const std::string name = f.filename().string();
    if (name.rfind("linuxcnc_systems_ttt", 0) == 0) opt.dialect.start_units = StartUnits::Inch;
    if (f.parent_path().filename() == "printer") opt.dialect.start_units = StartUnits::Mm;
    std::string text = test::read_file(f);
    auto r = compress(f.string(), text, opt, sink);
    INFO(sink.format_all());
    // The only blocks a strict read may refuse are placeholders a slicer left unexpanded,
    // such as Cura's `G1 X0 Y{machine_depth}`.
    for (const auto& d : sink.all()) {
      size_t line_start = 0;
      for (uint32_t l = 1; l < d.at.line; ++l) line_start = text.find('\n', line_start) + 1;
      std::string line = text.substr(line_start, text.find('\n', line_start) - line_start);
      INFO(line);
      CHECK(line.find('{') != std::string::npos);
    }
    CHECK((r.ok || text.find('{') != std::string::npos));
  }
}

TEST_CASE("a corpus file read with the dialect it names for itself gets only true warnings", "[corpus][dialect]") {
  ARCPRESS_CORPUS_FILES_OR_SKIP(files)
  size_t named = 0;
  for (const auto& f : files) {
    const std::string text = test::read_file(f);
    const std::optional<ProgramFlavor> flavor = program_flavor(text);
    if (!flavor || flavor->dialect.empty()) continue;
    ++named;
    INFO(f.string() << " read as " << flavor->dialect);
    DiagnosticSink sink(f.string());
    CompressOptions opt;
    opt.fit.method = FitOptions::Method::Keep;
    opt.dialect = find_dialect(flavor->dialect, {ARCPRESS_SOURCE_DIR "/dialects"});
    REQUIRE(compress(f.string(), text, opt, sink).ok);
    // The slicer wrote for this firmware: the only line it cannot read is a start-code
    // template the slicer left unexpanded ('{machine_depth}'), and that is reported where
    // the brace is.
    std::vector<std::string> lines;
    for (size_t at = 0; at < text.size();) {
      const size_t nl = std::min(text.find('\n', at), text.size());
      lines.push_back(text.substr(at, nl - at));
      at = nl + 1;
    }
    for (const Diagnostic& d : sink.all()) {
      INFO(sink.format(d));
      REQUIRE(d.at.line >= 1);
      REQUIRE(d.at.line <= lines.size());
      REQUIRE(d.at.col >= 1);
      CHECK(d.code == "E-LEX-NUMBER");
      CHECK(lines[d.at.line - 1].substr(d.at.col - 1).find('{') != std::string::npos);
    }
  }
  CHECK(named >= 3);  // the slicers' files that name a firmware
}
