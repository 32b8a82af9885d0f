// SPDX-License-Identifier: GPL-3.0-or-later
// Where a line's leading blanks open and close blocks (RepRapFirmware 3: the lines indented
// below `if`, `else` or `while` are its block), a block written in place of moves stays in
// the block they were in, and a line that ends a block is entered both from the block's end
// and from where it began: nothing after it is fitted from inside the block.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "arcpress/arcpress.hpp"
#include "arcpress/dialect/dialect_loader.hpp"
#include "arcpress/model/block_nesting.hpp"
#include "support.hpp"

using namespace arcpress;
using namespace arcpress::test;

namespace {

/// Moves `from` .. `to` (of 0 .. 30) along a quarter circle of radius 20 mm about (-20, 0),
/// each line beginning with `indent`, extruding (M83).
std::string quarter(int from, int to, const std::string& indent) {
  std::string t;
  for (int i = from; i <= to; ++i) {
    const double a = M_PI * i / 60;
    t += fmt::format("{}G1 X{:.4f} Y{:.4f} E0.05\n", indent, 20 * std::cos(a) - 20, 20 * std::sin(a));
  }
  return t;
}

const std::string kHead = "G90\nM83\nG1 X0 Y0 F1200\n";

}  // namespace

TEST_CASE("a line indented less than the one before it closes blocks, and what they changed is not known there",
          "[nesting]") {
  BlockNesting n;
  CHECK_FALSE(n.line("if move.axes[0].homed", true).position);
  CHECK_FALSE(n.line("  G1 X10", false).position);
  n.changed(true, false);
  // Blank lines and indented comments close nothing; a tab counts to the next multiple of 4.
  CHECK_FALSE(n.line("", false).position);
  CHECK_FALSE(n.line("   ", false).position);
  BlockNesting m = n;
  CHECK_FALSE(m.line(" ; indented comment", false).position);
  CHECK_FALSE(m.line("\tG1 X11", false).position);  // deeper: a block of its own
  CHECK(m.depth == 2);
  const BlockNesting::Join closed = m.line("G1 X12", false);
  CHECK(closed.position);
  CHECK_FALSE(closed.distance);
  CHECK(m.depth == 0);
  // A comment at the left margin closes the block too, as the firmware reads it.
  BlockNesting c = n;
  CHECK(c.line("; comment", false).position);
  // A block in which nothing changed closes with nothing unknown; a G91 in it is.
  BlockNesting q;
  q.line("if true", true);
  q.line("  M117 hello", false);
  q.changed(false, false);
  CHECK_FALSE(q.line("G1 X1", false).position);
  q.line("if true", true);
  q.line("  G91", false);
  q.changed(false, true);
  const BlockNesting::Join j = q.line("G1 X1", false);
  CHECK(j.distance);
  CHECK_FALSE(j.position);
  // Lines indented deeper after a line that is no flow control are a plain block: it runs
  // once, in order, and its end joins nothing.
  BlockNesting plain;
  plain.line("G1 X0 Y0", false);
  plain.line(" X1 Y1", false);
  plain.changed(true, true);
  const BlockNesting::Join none = plain.line("G1 X2", false);
  CHECK_FALSE(none.position);
  CHECK_FALSE(none.distance);
  // Closing two blocks at once tells what either changed.
  BlockNesting deep;
  deep.line("while true", true);
  deep.line("  if x", true);
  deep.line("    G1 X1", false);
  deep.changed(true, false);
  deep.line("    G91", false);
  deep.changed(false, true);
  const BlockNesting::Join both = deep.line("G1 X2", false);
  CHECK(both.position);
  CHECK(both.distance);
}

TEST_CASE("a block written in place of a loop's moves stays in the loop", "[nesting]") {
  const std::string text = kHead + "G1 X0 Y0 E0.05\nwhile iterations < 3\n" + quarter(0, 30, "  ") + "  G1 X0 Y0 E0.05\n" +
                           "M400\n";
  const CompressResult r = compress_as("reprapfirmware", text);
  REQUIRE(r.ok);
  CHECK(r.within_band());
  REQUIRE(count_of(r.output, "G3") == 1);
  // Every line between `while` and the line after the loop is indented as the loop's lines are.
  const size_t body = r.output.find("while iterations < 3\n") + 21, after = r.output.find("M400\n");
  REQUIRE(body < after);
  for (size_t at = body; at < after; at = r.output.find('\n', at) + 1) {
    INFO(r.output.substr(at, r.output.find('\n', at) - at));
    CHECK(r.output.compare(at, 2, "  ") == 0);
  }
  // The controllers without such blocks write the arc as the input's lines begin; unindented
  // input stays unindented.
  CHECK(compress_as("marlin", text).output.find("\n  G3 X") != std::string::npos);
  CHECK(compress_as("reprapfirmware", kHead + quarter(0, 30, "")).output.find("\nG3 X") != std::string::npos);
}

TEST_CASE("a loop whose last move became an arc ends in the input's motion again, inside the loop", "[nesting]") {
  // The loop's first line has no motion word: each time round it reads the motion its last
  // line left, a G1 in the input.
  const std::string text = kHead + "while iterations < 3\n  X0 Y0 E0.05\n" + quarter(1, 30, "  ") + "M400\n";
  const CompressResult r = compress_as("reprapfirmware", text);
  REQUIRE(r.ok);
  REQUIRE(count_of(r.output, "  G3") == 1);
  CHECK(r.output.find("\n  G1\nM400\n") != std::string::npos);
  // Where the loop's last line is the input's own G1, nothing is added.
  const CompressResult kept = compress_as("reprapfirmware", text.substr(0, text.size() - 5) + "  G1 X0 Y0 E0.05\nM400\n");
  REQUIRE(kept.ok);
  CHECK(kept.output.find("\n  G1\n") == std::string::npos);
}

TEST_CASE("the moves after an if block are not fitted from inside it", "[nesting]") {
  // The path goes on past the block, but where the condition fails the block's moves are not
  // made: the line after it starts from before the `if`.
  const std::string text = kHead + "if move.axes[2].homed\n" + quarter(0, 15, "  ") + quarter(16, 30, "") + "M400\n";
  // Read without such blocks, one arc replaces moves of both.
  const CompressResult flat = compress_as("marlin", text);
  REQUIRE(flat.ok);
  CHECK(count_of(flat.output, "G3") == 1);
  CHECK(flat.output.find(quarter(16, 16, "")) == std::string::npos);
  const CompressResult nested = compress_as("reprapfirmware", text);
  REQUIRE(nested.ok);
  CHECK(nested.within_band());
  // The first move after the block is written as it was, and the rest fitted from it.
  CHECK(nested.output.find("\n" + quarter(16, 16, "")) != std::string::npos);
  CHECK(count_of(nested.output, "  G3") == 1);
  CHECK(count_of(nested.output, "\nG3") == 1);
  // A G91 in the block leaves the distance mode after it unknown: nothing is fitted until the
  // program states one.
  const std::string g91 = kHead + "if move.axes[2].homed\n" + quarter(0, 15, "  ") + "  G91\n";
  const CompressResult unknown = compress_as("reprapfirmware", g91 + quarter(16, 30, ""));
  REQUIRE(unknown.ok);
  CHECK(count_of(unknown.output, "\nG3") == 0);
  CHECK(unknown.output.find(quarter(16, 30, "")) != std::string::npos);
  const CompressResult stated = compress_as("reprapfirmware", g91 + "G90\n" + quarter(16, 30, ""));
  REQUIRE(stated.ok);
  CHECK(count_of(stated.output, "\nG3") == 1);
}

TEST_CASE("arcpress diff reads the blocks of indented programs as the compressor does", "[nesting]") {
  const std::string text = kHead + "if move.axes[2].homed\n" + quarter(0, 15, "  ") + quarter(16, 30, "") + "M400\n";
  const CompressResult r = compress_as("reprapfirmware", text);
  REQUIRE(r.ok);
  DiffOptions opt;
  opt.tolerance_mm = 0.01;
  const Dialect rrf = shipped_dialect("reprapfirmware");
  CHECK(diff_texts(text, r.output, opt, rrf).same(opt.tolerance_mm));
  // The arc of the first block moved out of it (its indent taken away) is another program:
  // where the `if` fails, it is made from another place.
  std::string moved = r.output;
  const size_t at = moved.find("  G3");
  REQUIRE(at != std::string::npos);
  moved.erase(at, 2);
  CHECK_FALSE(diff_texts(text, moved, opt, rrf).same(opt.tolerance_mm));
  CHECK(diff_texts(text, moved, opt, shipped_dialect("marlin")).same(opt.tolerance_mm));
}

TEST_CASE("an O-word block closes at its end line, and what its lines changed is not known after it", "[nesting]") {
  BlockNesting n;
  n.open(101, false);  // o101 if
  n.changed(false, true);
  n.open(102, true);  // o102 do
  CHECK(n.in_do(102));
  CHECK_FALSE(n.in_do(101));
  n.changed(true, false);
  const BlockNesting::Join loop = n.close(102);  // o102 while [...]
  CHECK(loop.position);
  CHECK_FALSE(loop.distance);
  CHECK(n.depth == 1);
  const BlockNesting::Join branch = n.close(101);  // o101 endif
  CHECK(branch.position);
  CHECK(branch.distance);
  CHECK(n.depth == 0);
  // A block in which nothing changed; an end with no block open.
  n.open(7, false);
  const BlockNesting::Join quiet = n.close(7);
  CHECK_FALSE(quiet.position);
  CHECK_FALSE(quiet.distance);
  CHECK_FALSE(n.close(7).position);
}

TEST_CASE("a loop that leaves another distance mode than its first moves were read in is refused", "[nesting]") {
  // Run again, the loop's first lines read their words in the G91 its last line left: the
  // quarter circle the first time round, increments after. No single reading of them holds.
  auto rrf = [](const std::string& text) {
    CompressOptions opt;
    opt.dialect = shipped_dialect("reprapfirmware");
    DiagnosticSink sink;
    const CompressResult r = compress("loop.gcode", text, opt, sink);
    const bool refused = std::any_of(sink.all().begin(), sink.all().end(),
                                     [](const Diagnostic& d) { return d.code == "E-FLOW-LOOP-MODES"; });
    return std::pair(r.ok, refused);
  };
  const std::string loop = kHead + "while iterations < 3\n" + quarter(0, 30, "  ") + "  G91\n  G1 Z0.2\nG90\nM400\n";
  CHECK(rrf(loop) == std::pair(false, true));
  // Restated at the loop's start, or back in G90 at its end, the moves read the same each time.
  std::string stated = loop;
  stated.insert(stated.find("while iterations < 3\n") + 21, "  G90\n");
  CHECK(rrf(stated) == std::pair(true, false));
  std::string restored = loop;
  restored.insert(restored.find("G90\nM400"), "  G90\n");
  CHECK(rrf(restored) == std::pair(true, false));
  // An `if` runs once: its lines are read in order.
  std::string branch = loop;
  branch.replace(branch.find("while iterations < 3"), 20, "if iterations < 3");
  CHECK(rrf(branch) == std::pair(true, false));
  // LinuxCNC's loops: `while`, `do`, `repeat`, closed by their O-word lines.
  CompressOptions opt;
  opt.dialect = shipped_dialect("linuxcnc");
  for (const auto& [open, close] : {std::pair("o1 while [#1 LT 3]", "o1 endwhile"), std::pair("o1 do", "o1 while [#1 LT 3]"),
                                    std::pair("o1 repeat [3]", "o1 endrepeat")}) {
    INFO(open);
    DiagnosticSink sink;
    const std::string text = "G21 G17 G90\nG1 X0 Y0 F500\n" + std::string(open) + "\n" + quarter(0, 30, "") + "G91 G1 Z0.2\n" +
                             close + "\nG90\nM2\n";
    CHECK_FALSE(compress("loop.ngc", text, opt, sink).ok);
    DiagnosticSink quiet;
    std::string stated_text = text;
    stated_text.insert(stated_text.find('\n', stated_text.find(open)) + 1, "G90\n");
    CHECK(compress("loop.ngc", stated_text, opt, quiet).ok);
  }
}

TEST_CASE("Fanuc's macro loops are loops too, WHILE DO1 to END1", "[nesting]") {
  const std::string head = "G90 G17 G21\nG0 X0 Y0\nG1 F500\n#1=0\n";
  std::string after;  // the quarter circle again after the loop, its words bare
  for (size_t at = 0, nl; (nl = quarter(0, 30, "").find('\n', at)) != std::string::npos; at = nl + 1)
    after += quarter(0, 30, "").substr(at + 3, nl - at - 9) + "\n";  // (without "G1 " and " E0.05")
  // A loop that steps down in G91 and cuts in G90: after END1, the mode is the loop's end's
  // or, where it ran no more, the one before it; here the same, but not known to be.
  const std::string loop = head + "WHILE [#1 LT 3] DO1\nG91 G1 Z-1.\nG90\n" + quarter(0, 30, "") + "#1=#1+1\nEND1\n";
  const CompressResult inside = compress_as("fanuc", loop + "M30\n");
  REQUIRE(inside.ok);
  CHECK(count_of(inside.output, "G3") == 1);
  CHECK(count_of(compress_as("fanuc", loop + after + "M30\n").output, "G3") == 1);
  CHECK(count_of(compress_as("fanuc", loop + "G90\n" + after + "M30\n").output, "G3") == 2);
  // Moves at the loop's start read in G90, run again in the G91 its end leaves: refused.
  CompressOptions opt;
  opt.dialect = shipped_dialect("fanuc");
  DiagnosticSink sink;
  const std::string refused = head + "N5 WHILE[#1LT3]DO1\n" + quarter(0, 30, "") + "G91 G1 Z-1.\n#1=#1+1\nEND1\nG90\nM30\n";
  CHECK_FALSE(compress("loop.nc", refused, opt, sink).ok);
  CHECK(std::any_of(sink.all().begin(), sink.all().end(), [](const Diagnostic& d) { return d.code == "E-FLOW-LOOP-MODES"; }));
}
