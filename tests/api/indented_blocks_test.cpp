// SPDX-License-Identifier: GPL-3.0-or-later
// Where a line's leading blanks open and close blocks (RepRapFirmware 3: the lines indented
// below `if`, `else` or `while` are its block), a block written in place of moves stays in
// the block they were in, and a line that ends a block is entered both from the block's end
// and from where it began: nothing after it is fitted from inside the block.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "arcpress/arcpress.hpp"
#include "arcpress/dialect/dialect_loader.hpp"
#include "arcpress/model/block_nesting.hpp"
#include "arcpress/model/subroutines.hpp"
#include "arcpress/model/unread_line.hpp"
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
  const BlockNesting::Modes g90{0, 1, 1, 0, 10}, g91{0, 1, 2, 0, 10};
  BlockNesting n;
  CHECK_FALSE(n.line("if move.axes[0].homed", true, 1, g90).position);
  CHECK_FALSE(n.line("  G1 X10", false, 2, g90).position);
  n.moved();
  // Blank lines and indented comments close nothing; a tab counts to the next multiple of 4.
  CHECK_FALSE(n.line("", false, 3, g90).position);
  CHECK_FALSE(n.line("   ", false, 4, g90).position);
  BlockNesting m = n;
  CHECK_FALSE(m.line(" ; indented comment", false, 5, g90).position);
  CHECK_FALSE(m.line("\tG1 X11", false, 6, g90).position);  // deeper: a block of its own
  CHECK(m.depth == 2);
  const BlockNesting::Join closed = m.line("G1 X12", false, 7, g90);
  CHECK(closed.position);
  CHECK(closed.modes == 0);
  CHECK(m.depth == 0);
  // A comment at the left margin closes the block too, as the firmware reads it.
  BlockNesting c = n;
  CHECK(c.line("; comment", false, 5, g90).position);
  // A block in which nothing changed closes with nothing unknown; one that ends in G91 after
  // beginning in G90 leaves G90 or G91 not known.
  BlockNesting q;
  q.line("if true", true, 1, g90);
  q.line("  M117 hello", false, 2, g90);
  CHECK_FALSE(q.line("G1 X1", false, 3, g90).position);
  q.line("if true", true, 4, g90);
  q.line("  G91", false, 5, g90);
  const BlockNesting::Join j = q.line("G1 X1", false, 6, g91);
  CHECK(j.modes == kStatesDistance);
  CHECK_FALSE(j.position);
  // So does a way out in the middle (a `break`) in other modes than where the block began,
  // though its end is back in them.
  BlockNesting b;
  b.line("while true", true, 1, g90);
  b.line("  G91", false, 2, g90);
  b.way_out(g91);  // `  break`
  CHECK(b.line("G90", false, 4, g90).modes == kStatesDistance);
  // Lines indented deeper after a line that is no flow control are a plain block: it runs
  // once, in order, and its end joins nothing.
  BlockNesting plain;
  plain.line("G1 X0 Y0", false, 1, g90);
  plain.line(" X1 Y1", false, 2, g90);
  plain.moved();
  const BlockNesting::Join none = plain.line("G1 X2", false, 3, g91);
  CHECK_FALSE(none.position);
  CHECK(none.modes == 0);
  // Closing two blocks at once tells what either changed; a `while`'s end jumps back to it.
  BlockNesting deep;
  deep.line("while true", true, 1, g90);
  const BlockNesting::Join entered = deep.line("  if x", true, 2, g90);
  CHECK(entered.loop_entered == 1);  // (the program's first loop)
  CHECK(entered.loop_line == 1);
  deep.line("    G1 X1", false, 3, g90);
  deep.moved();
  deep.line("    G91", false, 4, g90);
  const BlockNesting::Join both = deep.line("G1 X2", false, 5, g91);
  CHECK(both.position);
  CHECK(both.modes == kStatesDistance);
  REQUIRE(both.loops_back_count == 1);
  CHECK(both.loops_back[0] == 1);
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
  // So before a `break` or `continue`, after which the firmware reads the lines after the
  // loop, or its first, in the motion left there.
  for (const char* leave : {"break", "continue"}) {
    const std::string left = kHead + "while iterations < 3\n  if iterations == 2\n" + quarter(0, 30, "    ") + "    " +
                             leave + "\n  G1 X0 Y0 E0.05\nX1 Y1 E0.05\nM400\n";
    const CompressResult r = compress_as("reprapfirmware", left);
    REQUIRE(r.ok);
    CHECK(r.runs_kept_as_input == 0);
    CHECK(r.output.find("    G3 X") != std::string::npos);
    CHECK(r.output.find(std::string("\n    G1\n    ") + leave + "\n") != std::string::npos);
  }
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

TEST_CASE("an O-word block closes at its end line, and the modes that differ on its ways out are not known after it", "[nesting]") {
  const BlockNesting::Modes g17{0, 1, 1, 0, 10}, g18{1, 1, 1, 0, 10}, g0{0, 1, 1, 0, 0};
  BlockNesting n;
  n.open(101, false, false, g17);  // o101 if
  CHECK(n.open(102, true, true, g17) == 1);  // o102 do, the program's first loop
  CHECK(n.in_do(102));
  CHECK_FALSE(n.in_do(101));
  CHECK(n.loop_of(0) == 1);
  CHECK(n.loop_of(101) == 0);
  n.moved();
  const BlockNesting::Join loop = n.close(102, g0);  // o102 while [...], after a G0
  CHECK(loop.position);
  CHECK(loop.modes == kStatesMotion);
  REQUIRE(loop.loops_back_count == 1);
  CHECK(loop.loops_back[0] == 1);
  CHECK(n.depth == 1);
  const BlockNesting::Join branch = n.close(101, g18);  // o101 endif, in G18
  CHECK(branch.position);
  CHECK(branch.modes == kStatesPlane);
  CHECK(branch.loops_back_count == 0);
  CHECK(n.depth == 0);
  // A block in which nothing changed; an end with no block open.
  n.open(7, false, false, g17);
  const BlockNesting::Join quiet = n.close(7, g17);
  CHECK_FALSE(quiet.position);
  CHECK(quiet.modes == 0);
  CHECK_FALSE(n.close(7, g18).position);
}

namespace {

/// How `text` fares under `dialect`: read whole (compress(), which reads the loops ahead), and
/// pushed as it comes without reading ahead.
struct LoopRun {
  bool ok = false;            ///< read whole: written
  bool written_as_is = false;  ///< ... with W-FLOW-LOOP-MODES
  size_t arcs = 0;            ///< ... so many G2/G3
  bool within_band = false;   ///< ... and arcpress diff finds no difference
  size_t kept_by_check = 0;   ///< ... runs the check refused (their output read otherwise)
  bool refused_as_it_comes = false;  ///< pushed as it comes: E-FLOW-LOOP-MODES, and nothing written
};

LoopRun run_loop(const std::string& dialect, const std::string& text) {
  CompressOptions opt;
  opt.dialect = shipped_dialect(dialect);
  opt.fit.tolerance_mm = 0.01;
  auto has = [](const DiagnosticSink& sink, const char* code) {
    return std::any_of(sink.all().begin(), sink.all().end(), [&](const Diagnostic& d) { return d.code == code; });
  };
  LoopRun run;
  DiagnosticSink sink;
  const CompressResult r = compress("loop", text, opt, sink);
  run.ok = r.ok;
  run.written_as_is = has(sink, "W-FLOW-LOOP-MODES");
  run.arcs = count_of(r.output, "G2 X") + count_of(r.output, "G3 X");
  run.kept_by_check = r.runs_kept_as_input;
  DiffOptions d;
  d.tolerance_mm = 0.01;
  run.within_band = r.ok && r.within_band() && diff_texts(text, r.output, d, opt.dialect).verdict(0.01) != ProgramDiff::Verdict::Different;
  DiagnosticSink streamed;
  Compressor c("loop", opt, streamed);
  c.push(text);
  c.finish();
  run.refused_as_it_comes = !c.result().ok && has(streamed, "E-FLOW-LOOP-MODES");
  return run;
}

/// `r` was written, `arcs` arcs, and read back as the input; `as_is`: its loop's moves written
/// as they are, and refused where read as they come.
void expect_loop(const LoopRun& r, bool as_is, size_t arcs) {
  CHECK(r.ok);
  CHECK(r.written_as_is == as_is);
  CHECK(r.arcs == arcs);
  CHECK(r.kept_by_check == 0);
  CHECK(r.within_band);
  CHECK(r.refused_as_it_comes == as_is);
}

/// `loop` (a `while` whose end leaves another mode than its start) with `statement` at its
/// start, and with it again before `end`: either way its moves read the same every time.
std::array<std::string, 2> restated(const std::string& loop, const std::string& statement, const std::string& end) {
  std::string stated = loop, restored = loop;
  stated.insert(stated.find("while iterations < 3\n") + 21, "  " + statement + "\n");
  restored.insert(restored.find(end), "  " + statement + "\n");
  return {stated, restored};
}

/// The quarter circle of quarter() with no motion word (and no E): read in the motion in force.
std::string bare_quarter() {
  std::string bare;
  const std::string q = quarter(0, 30, "");
  for (size_t at = 0, nl; (nl = q.find('\n', at)) != std::string::npos; at = nl + 1)
    bare += q.substr(at + 3, nl - at - 9) + "\n";  // (without "G1 " and " E0.05")
  return bare;
}

}  // namespace

TEST_CASE("a loop whose end runs its first moves again in other modes writes them as they are", "[nesting][jumps]") {
  // Run again, the loop's first lines read their words in the G91 its last line left: the
  // quarter circle the first time round, increments after. No single output of them holds
  // both: read whole, they are written as they are; read as they come (their output gone
  // before the loop's end), the run fails.
  const std::string loop = kHead + "while iterations < 3\n" + quarter(0, 30, "  ") + "  G91\n  G1 Z0.2\nG90\nM400\n";
  expect_loop(run_loop("reprapfirmware", loop), true, 0);
  // Restated at the loop's start, or back in G90 at its end, the moves read the same each time.
  const auto [stated, restored] = restated(loop, "G90", "G90\nM400");
  // An `if` runs once: its lines are read in order.
  std::string branch = loop;
  branch.replace(branch.find("while iterations < 3"), 20, "if iterations < 3");
  for (const std::string& text : {stated, restored, branch}) expect_loop(run_loop("reprapfirmware", text), false, 1);
  // A `continue` runs the loop's first lines again from where it stands.
  const std::string skipped = kHead + "while iterations < 3\n" + quarter(0, 30, "  ") +
                              "  if iterations == 1\n    G18\n    continue\n  G17\n  G1 Z0.2\nM400\n";
  expect_loop(run_loop("reprapfirmware", skipped), true, 0);
}

TEST_CASE("LinuxCNC's, Fanuc's and Sinumerik's loops run their first moves again in the plane, units, motion and G90 or G91 their end leaves",
          "[nesting][jumps]") {
  // Each loop's end leaves one mode otherwise than its start was read in.
  const std::string ends[] = {"G91 G1 Z0.2\n", "G18\n", "G20\n", "G0 Z1\n"};
  const std::string bare = bare_quarter();
  struct Loop {
    const char* dialect;
    const char* open;
    const char* close;
  };
  for (const Loop& l : {Loop{"linuxcnc", "o1 while [#1 LT 3]", "o1 endwhile"}, Loop{"linuxcnc", "o1 do", "o1 while [#1 LT 3]"},
                        Loop{"linuxcnc", "o1 repeat [3]", "o1 endrepeat"}, Loop{"fanuc", "WHILE [#1 LT 3] DO1", "END1"},
                        Loop{"fanuc", "DO1", "END1"}, Loop{"sinumerik", "WHILE R1<3", "ENDWHILE"},
                        Loop{"sinumerik", "LOOP", "ENDLOOP"}, Loop{"sinumerik", "FOR R1=0 TO 2", "ENDFOR"},
                        Loop{"sinumerik", "REPEAT", "UNTIL R1>=3"}})
    for (const std::string& end : ends) {
      INFO(l.open << " .. " << end);
      // (A quarter circle before the loop becomes one arc: the output's lines are others than
      // the input's, its loops the same.)
      const std::string head = "G21 G17 G90\nG0 X0 Y0\nG1 X0 Y0 F500\n" + bare + std::string(l.open) + "\nX0 Y0\n";
      const std::string text = head + bare + end + l.close + "\nG21 G17 G90 G1\nM2\n";
      expect_loop(run_loop(l.dialect, text), true, 1);
      // Stated at the loop's start, the moves are fitted, and read alike each time round.
      std::string stated = text;
      stated.insert(stated.find('\n', stated.find(l.open)) + 1, "G21 G17 G90 G1\n");
      expect_loop(run_loop(l.dialect, stated), false, 2);
    }
  // LinuxCNC's `continue` runs the loop's first lines again from where it stands.
  const std::string skipped = "G21 G17 G90\nG0 X0 Y0\nG1 F500\n#1=0\no1 do\nX0 Y0\n" + bare +
                              "o3 if [#1 EQ 1]\nG18\no1 continue\no3 endif\nG17\n#1=[#1+1]\no1 while [#1 LT 3]\nM2\n";
  expect_loop(run_loop("linuxcnc", skipped), true, 0);
  // A rapid before the loop's G90 places the moves after it: run again in G91, it ends
  // elsewhere, and so does the first move the G90 reads after it.
  const std::string rapid = "G21 G17 G90\nG0 X0 Y0\nG1 F500\n#1=0\no1 do\nG0 X5 Y5\nG90 G1\n" + bare +
                            "G91 G1 Z0.2\n#1=[#1+1]\no1 while [#1 LT 3]\nG90\nM2\n";
  expect_loop(run_loop("linuxcnc", rapid), true, 0);
}

TEST_CASE("a loop nested deeper than the blocks arcpress follows reads its first moves in modes not known", "[nesting][jumps]") {
  // Past BlockNesting::kMostLevels blocks, a loop's end is not followed: its first moves wait
  // for the program to state their modes, as a loop found to run them otherwise does.
  std::string opens, closes;
  for (uint32_t k = 1; k <= BlockNesting::kMostLevels; ++k) {
    opens += fmt::format("o{} if [#2 EQ 0]\n", k);
    closes = fmt::format("o{} endif\n", k) + closes;
  }
  const std::string head = "G21 G17 G90\nG0 X0 Y0\nG1 F500\n#1=0\n#2=0\n" + opens + "o20 do\nX0 Y0\n";
  const std::string tail = "#1=[#1+1]\no20 while [#1 LT 3]\n" + closes + "M2\n";
  expect_loop(run_loop("linuxcnc", head + bare_quarter() + "G18\n" + tail), false, 0);
  std::string stated = head + "G21 G17 G90 G1\n" + bare_quarter() + "G18\n" + tail;
  expect_loop(run_loop("linuxcnc", stated), false, 1);
  // One level less, the loop is followed.
  const std::string followed = head.substr(0, head.find("o8 if")) + "o20 do\nX0 Y0\n" + bare_quarter() + "G18\n" +
                               "#1=[#1+1]\no20 while [#1 LT 3]\n" + closes.substr(closes.find("o7 endif")) + "M2\n";
  expect_loop(run_loop("linuxcnc", followed), true, 0);
}

TEST_CASE("E's mode is one a loop runs its first moves again in, and one a block's ways out may leave differently",
          "[nesting][jumps][printer]") {
  // RepRapFirmware: M82 at the loop's end makes the E words of its first moves places the
  // second time round, where they were read as increments: an arc carrying their sum would
  // extrude to that place instead. Written as they are; M83 stated at the loop's start (or
  // M83 again at its end) reads them the same each time.
  const std::string loop = kHead + "while iterations < 3\n" + quarter(0, 30, "  ") + "  M82\n  G92 E0\nM400\n";
  expect_loop(run_loop("reprapfirmware", loop), true, 0);
  for (const std::string& text : restated(loop, "M83", "M400")) expect_loop(run_loop("reprapfirmware", text), false, 1);
  // Marlin reads E's mode with G90: its loops' G90 at the start states it.
  const std::string marlin = "G21\nM83\nG1 X0 Y0 F1200\nM808 L3\nG90\n" + quarter(0, 30, "") + "M82\nG92 E0\nM808\n";
  expect_loop(run_loop("marlin", marlin), false, 1);
  // An `if` that may set M83: after it, moves that extrude are not fitted until the program
  // states E's mode; those that do not are.
  const std::string branch = "G90\nM82\nG92 E0\nG1 X0 Y0 F1200\nif {global.relative}\n  M83\n";
  DiagnosticSink sink;
  CompressOptions opt;
  opt.dialect = shipped_dialect("reprapfirmware");
  const CompressResult unknown = compress("t.gcode", branch + quarter(0, 30, ""), opt, sink);
  REQUIRE(unknown.ok);
  CHECK(count_of(unknown.output, "G3") == 0);
  REQUIRE_FALSE(unknown.not_fitted.empty());
  CHECK(unknown.not_fitted.back().why == Unfit::ExtrusionModeUnknown);
  CHECK(count_of(compress_as("reprapfirmware", branch + "M83\n" + quarter(0, 30, "")).output, "G3") == 1);
  CHECK(count_of(compress_as("reprapfirmware", branch + bare_quarter()).output, "G3") == 1);
  // A line arcpress does not read that says M83 leaves E's mode not known after it.
  CHECK(modes_named("M83 {var.flow}", shipped_dialect("reprapfirmware")) == kStatesExtrusion);
  CHECK(modes_named("G91 {var.z}", shipped_dialect("marlin")) == (kStatesDistance | kStatesExtrusion));
  CHECK(modes_named("G91 {var.z}", shipped_dialect("reprapfirmware")) == kStatesDistance);
  CHECK(modes_named("M117 {depth}", shipped_dialect("marlin")) == 0);
}

TEST_CASE("after a block the modes that differ on its ways out are not known", "[nesting]") {
  const std::string bare = bare_quarter();
  const std::string head = "G21 G17 G90\nG0 X0 Y0\nG1 X0 Y0 F500\n#1=0\n";
  // A branch that leaves G18, G20 or G0 where it may not run: after it, the moves wait for the
  // program to state the mode; the same mode on every way out is known.
  for (const std::string& mode : {"G18", "G20", "G0"}) {
    INFO(mode);
    const std::string text = head + "o1 if [#1 EQ 1]\n" + mode + "\no1 endif\n" + bare + "M2\n";
    CHECK(count_of(compress_as("linuxcnc", text).output, "G3") == 0);
    CHECK(count_of(compress_as("linuxcnc", head + "o1 if [#1 EQ 1]\n" + mode + "\no1 endif\nG21 G17 G1\n" + bare + "M2\n").output, "G3") == 1);
    const std::string back = head + "o1 if [#1 EQ 1]\n" + mode + "\nG21 G17 G1\no1 endif\n" + bare + "M2\n";
    CHECK(count_of(compress_as("linuxcnc", back).output, "G3") == 1);
    // An `else` that states the modes again leaves the other branch's way out as it was.
    const std::string branches = head + "o1 if [#1 EQ 1]\n" + mode + "\no1 else\nG21 G17 G1\no1 endif\n" + bare + "M2\n";
    CHECK(count_of(compress_as("linuxcnc", branches).output, "G3") == 0);
    // ... not where a `break` leaves the loop in it.
    const std::string broken = head + "o2 do\n" + mode + "\no3 if [#1 EQ 1]\no2 break\no3 endif\nG21 G17 G1\no2 while [#1 LT 3]\n" + bare + "M2\n";
    CHECK(count_of(compress_as("linuxcnc", broken).output, "G3") == 0);
  }
  // Sinumerik's IF .. ELSE .. ENDIF, whose branches leave G18 and G17.
  const std::string sinumerik = "G71 G17 G90\nG0 X0 Y0\nG1 X0 Y0 F500\nR1=0\nIF R1==1\nG18\nELSE\nG17\nENDIF\n";
  CHECK(count_of(compress_as("sinumerik", sinumerik + bare + "M30\n").output, "G3") == 0);
  CHECK(count_of(compress_as("sinumerik", sinumerik + "G17\n" + bare + "M30\n").output, "G3") == 1);
}

TEST_CASE("Fanuc's macro loops are loops too, WHILE DO1 to END1", "[nesting]") {
  const std::string head = "G90 G17 G21\nG0 X0 Y0\nG1 F500\n#1=0\n";
  const std::string after = bare_quarter();  // the quarter circle again after the loop, its words bare
  // A loop that steps down in G91 and cuts in G90: after END1, the modes are the loop's end's
  // or, where it ran no more, the ones before it; here the same on both ways out.
  const std::string loop = head + "WHILE [#1 LT 3] DO1\nG91 G1 Z-1.\nG90\n" + quarter(0, 30, "") + "#1=#1+1\nEND1\n";
  const CompressResult inside = compress_as("fanuc", loop + "M30\n");
  REQUIRE(inside.ok);
  CHECK(count_of(inside.output, "G3") == 1);
  CHECK(count_of(compress_as("fanuc", loop + after + "M30\n").output, "G3") == 2);
  // Where the loop ends in G91, the moves after it wait for the program to state G90.
  std::string g91 = loop;
  g91.insert(g91.find("END1"), "G91\n");
  CHECK(count_of(compress_as("fanuc", g91 + after + "M30\n").output, "G3") == 1);
  CHECK(count_of(compress_as("fanuc", g91 + "G90\n" + after + "M30\n").output, "G3") == 2);
}
