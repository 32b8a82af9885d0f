// SPDX-License-Identifier: GPL-3.0-or-later
// A program's jumps (GOTO n, M99 Pn, M97 Pn) enter the blocks they name from wherever they
// were made: such a block stays as written, with its number, and nothing after it is fitted
// from the position its neighbour in the text leaves. The blocks after a program's end run
// only when a call enters them.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "arcpress/api/compressor.hpp"
#include "arcpress/arcpress.hpp"
#include "arcpress/dialect/dialect_loader.hpp"
#include "arcpress/lex/jump_targets.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"
#include "support.hpp"

using namespace arcpress;
using namespace arcpress::test;

namespace {

JumpTargets jumps_of(std::string_view text) {
  JumpTargets j;
  j.read(text, 1);
  return j;
}

/// 31 moves along a quarter circle of radius 20 mm about (-20, 0), printed to 4 decimals,
/// the one at index `numbered` (when >= 0) written as block N100.
std::string quarter(int numbered = -1) {
  std::string t;
  for (int i = 0; i <= 30; ++i) {
    const double a = M_PI * i / 60;
    t += fmt::format("{}G1 X{:.4f} Y{:.4f}\n", i == numbered ? "N100 " : "", 20 * std::cos(a) - 20, 20 * std::sin(a));
  }
  return t;
}

}  // namespace

TEST_CASE("a jump read late is told at its own line, where a line holds two jumps too", "[jumps]") {
  // GOTO's place is noted first, M99's at the line's start: both are line 3.
  PassedNumbers passed;
  passed.pass(20);
  JumpTargets j;
  j.read("N20 G1 X1\nG1 X2\nIF [#1 LT 2] GOTO 10 M99 P20\nG1 X3\n", 1, &passed);
  REQUIRE(j.late());
  CHECK(j.late()->line == 3);
  CHECK(j.late()->number == 20);
}

TEST_CASE("the blocks a program's jumps name are read from its text, comments and quoted text left out", "[jumps]") {
  const JumpTargets j = jumps_of(
      "GOTO 100\nIF [#1 LT 3] GOTO200\nM99 P300\nP400 M99\nM97 P500 L2\nM099 P600\nGOTOB N700\nGOTOF 800.\n"
      "M98 P2000 Q900\n"
      "(GOTO 11) G1 X0 ; GOTO 12\nMSG(\"GOTO 13\")\nM990 P14\nM98 P15\nM99 P16.5\nGOTOF LABEL1\nXGOTO 17\n");
  for (double n : {100, 200, 300, 400, 500, 600, 700, 800, 900}) CHECK(j.enters(n));
  for (double n : {11, 12, 13, 14, 15, 16, 17, 1, 2000}) CHECK_FALSE(j.enters(n));
  CHECK_FALSE(jumps_of("G1 X10 Y10 M3\nM99\nM30\n").any());
  // Sinumerik's jumps to a label name it, in any case; a label no jump names is no target.
  CHECK(j.enters(kLabelKey | label_hash("label1")));
  CHECK_FALSE(j.enters(kLabelKey | label_hash("LABEL2")));
  CHECK_FALSE(j.enters(kLabelKey | label_hash("LABEL")));
  // A number the program computes may be any block's.
  CHECK(jumps_of("GOTO #1\n").enters(12345));
  CHECK(jumps_of("M99 P[#2+10]\n").enters(7));
}

TEST_CASE("a jump's target stays a block of its own, and the moves after it are not fitted from before it", "[jumps]") {
  const std::string head = "O1000\nG90 G17 G21\nG0 X0 Y0\nG1 F500\n";
  const std::string tail = "#1=#1+1\nIF [#1 LT 3] GOTO 100\nM30\n";
  for (const std::string dialect : {"fanuc", "haas", "rs274"}) {
    INFO(dialect);
    // Without the jump, N100 is one of the moves one arc replaces.
    const CompressResult plain = compress_as(dialect, head + quarter(15) + "M30\n");
    REQUIRE(plain.ok);
    CHECK(plain.output.find("N100") == std::string::npos);
    const CompressResult jumped = compress_as(dialect, head + quarter(15) + tail);
    REQUIRE(jumped.ok);
    CHECK(jumped.within_band());
    // With it, N100 is written as it was, and the moves after it as they were: whether G90
    // or G91 is in force where the jump comes from is not known.
    CHECK(jumped.output.find(fmt::format("N100 G1 X{:.4f} Y{:.4f}\n", 20 * std::cos(M_PI / 4) - 20,
                                         20 * std::sin(M_PI / 4))) != std::string::npos);
    CHECK(count_of(jumped.output, "G1 X") == 16);
    // Once the program states G90 after the target, its moves are fitted again.
    std::string restated = quarter(15);
    restated.insert(restated.find("N100 G1 X") + 5, "G90 ");
    const CompressResult again = compress_as(dialect, head + restated + tail);
    REQUIRE(again.ok);
    CHECK(again.output.find("N100 G90 G1 X") != std::string::npos);
    CHECK(count_of(again.output, "G1 X") <= 2);
  }
}

TEST_CASE("a jump after a run that became an arc states the input's motion first, which the target reads", "[jumps]") {
  // N100 has no motion word: it reads the motion in force where the jump is made, G1 in the input.
  const std::string text = "G90 G17 G21\nG0 X0 Y0\nG1 F500\nN100 G90 X0 Y0\n" + quarter() + "M99 P100\n";
  const CompressResult r = compress_as("fanuc", text);
  REQUIRE(r.ok);
  REQUIRE(count_of(r.output, "G3") == 1);
  CHECK(r.output.find("\nG1\nM99 P100\n") != std::string::npos);
}

TEST_CASE("a subprogram after a program's end runs only when a call enters it, from where the call was made", "[jumps]") {
  // Haas's M97 P1000 calls block N1000 of the same program, placed after M30: its moves go on
  // from the caller's position, in the caller's distance mode, G90 where every call is made in G90.
  const std::string main_part = "O1000\nG90 G17 G21\nG0 X0 Y0\nG1 F500\nM97 P1000\nG0 X50 Y50\nM97 P1000\nM30\n";
  const std::string body = "N1000 G1 X0 Y0\n" + quarter() + "M99\n";
  const CompressResult sub = compress_as("haas", main_part + body);
  REQUIRE(sub.ok);
  CHECK(count_of(sub.output, "G3") == 1);
  CHECK(sub.output.find("N1000 G1 X0 Y0\n") != std::string::npos);  // from where the call was made
  // A call made in G91 may enter it in G91: not fitted, until the body states its mode.
  std::string in_g91 = main_part;
  in_g91.insert(in_g91.find("M97 P1000\nG0 X50"), "G91\n");
  in_g91.insert(in_g91.find("G0 X50"), "G90\n");
  const CompressResult unknown = compress_as("haas", in_g91 + body);
  REQUIRE(unknown.ok);
  CHECK(count_of(unknown.output, "G3") == 0);
  const CompressResult stated = compress_as("haas", in_g91 + "N1000 G90 G1 X0 Y0\n" + quarter() + "M99\n");
  REQUIRE(stated.ok);
  CHECK(count_of(stated.output, "G3") == 1);
  // Mach3's M98 P2000 calls the program O2000 that follows the end (M30, M2 or a subprogram's
  // M99) in the same file; here once in G91.
  const std::string mach3 = "G90 G17 G21\nG0 X0 Y0\nG1 F500\nG91\nM98 P2000\nG90\nG0 X50 Y50\nM98 P2000\nM30\nO2000\n";
  for (const std::string end : {"M30", "M2", "M99"}) {
    std::string t = mach3 + "G1 X0 Y0\n" + quarter() + "M99\n";
    t.replace(t.find("M30"), 3, end);
    const CompressResult r = compress_as("mach3", t);
    REQUIRE(r.ok);
    CHECK(count_of(r.output, "G3") == 0);
    t.insert(t.find("O2000\n") + 6, "G90\n");
    CHECK(count_of(compress_as("mach3", t).output, "G3") == 1);
  }
  // Fanuc's macro call G65 P2000 enters its program so too.
  const std::string fanuc = "G90 G17 G21\nG0 X0 Y0\nG1 F500\nG65 P2000 A1.\nG0 X50 Y50\nM30\nO2000\nG1 X0 Y0\n" +
                            quarter() + "M99\n";
  CHECK(count_of(compress_as("fanuc", fanuc).output, "G3") == 1);
  std::string fanuc_g91 = fanuc;
  fanuc_g91.insert(fanuc_g91.find("G65"), "G91\n");
  CHECK(count_of(compress_as("fanuc", fanuc_g91).output, "G3") == 0);
  // A subprogram that moves in increments (G91, as Autodesk's Fanuc post writes a pattern's):
  // its moves are placed relative to one another from wherever the call was made, and
  // fitted so, in increments; after G90, the first absolute move starts where that was.
  std::string incremental = "G90 G17 G21\nG0 X0 Y0\nG1 F500\nM98 P2000\nG0 X50 Y50\nM98 P2000\nM30\nO2000\nG91\n";
  double px = 0, py = 0;
  for (int i = 1; i <= 30; ++i) {
    const double x = 20 * std::cos(M_PI * i / 60) - 20, y = 20 * std::sin(M_PI * i / 60);
    incremental += fmt::format("G1 X{:.4f} Y{:.4f}\n", x - px, y - py);
    px = x, py = y;
  }
  incremental += "G90\nG1 X5 Y5\nG1 X6 Y5\nM99\n";
  const CompressResult inc = compress_as("fanuc", incremental);
  REQUIRE(inc.ok);
  CHECK(inc.within_band());
  CHECK(inc.output.find("G91\nG3 X-20. Y20. I-19.999 J0.001\nG90\nG1 X5 Y5\n") != std::string::npos);
  // Programs written one after another in a file, each ending in M30 (CamBam's operations),
  // are read on: a sender that streams them runs each after the last.
  const CompressResult joined = compress_as("grbl", "G90 G17 G21\nG0 X5 Y5\nM30\nG0 X0 Y0\nG1 F500\n" + quarter() + "M30\n");
  REQUIRE(joined.ok);
  CHECK(count_of(joined.output, "G3") == 1);
}

TEST_CASE("a LinuxCNC subroutine's body runs in its caller's modes, and its caller goes on in those it leaves", "[jumps][subroutines]") {
  // o100's body moves in the caller's distance mode: not fitted until it states one.
  const std::string body = "G1 X0 Y0\n" + quarter();
  const std::string head = "G21 G17 G90\nG1 F500\n";
  const std::string calls = "G0 X0 Y0\no100 call\nG0 X50 Y0\n";
  const CompressResult unstated = compress_as("linuxcnc", head + "o100 sub\n" + body + "o100 endsub\n" + calls + "M2\n");
  REQUIRE(unstated.ok);
  CHECK(count_of(unstated.output, "G3") == 0);
  const CompressResult stated = compress_as("linuxcnc", head + "o100 sub\nG90\n" + body + "o100 endsub\n" + calls + "M2\n");
  REQUIRE(stated.ok);
  CHECK(count_of(stated.output, "G3") == 1);
  // The definition runs nothing: the moves after it are read in the modes before it, not in
  // the G91 and G18 its body states.
  const std::string after = "G1 X0 Y0\n" + quarter() + "M2\n";
  const CompressResult defined =
      compress_as("linuxcnc", head + "o100 sub\nG91 G18\nG1 X1\no100 endsub\n" + after);
  REQUIRE(defined.ok);
  CHECK(count_of(defined.output, "G3") == 1);
  // After its call they hold (rs274 reads so: tests/oracle/linuxcnc_test.cpp): the same
  // words are read as increments in XZ, and the arc of the absolute reading is not written.
  const CompressResult called =
      compress_as("linuxcnc", head + "o100 sub\nG91 G18\nG1 X1\no100 endsub\no100 call\n" + after);
  REQUIRE(called.ok);
  const std::string arc = defined.output.substr(defined.output.find("G3"));
  CHECK(called.output.find(arc.substr(0, arc.find('\n'))) == std::string::npos);
  // A subroutine in another file (or further on) may leave another distance mode, plane or
  // motion: after its call, nothing is fitted until the program states them. (Its units are
  // taken to be kept, as the program around it, which states them once, takes them.)
  const CompressResult other = compress_as("linuxcnc", head + "o<probe> call\nG90\n" + after);
  REQUIRE(other.ok);
  CHECK(count_of(other.output, "G3") == 0);
  CHECK(count_of(compress_as("linuxcnc", head + "o<probe> call\nG90 G17\n" + after).output, "G3") == 1);
  // A body read in G17 and called in G18 would run another path than the one fitted: refused.
  DiagnosticSink sink;
  CompressOptions opt;
  opt.dialect = shipped_dialect("linuxcnc");
  const CompressResult refused =
      compress("part.ngc", head + "o100 sub\nG90\n" + body + "o100 endsub\nG18\no100 call\nM2\n", opt, sink);
  CHECK_FALSE(refused.ok);
  CHECK(std::any_of(sink.all().begin(), sink.all().end(), [](const Diagnostic& d) { return d.code == "E-FLOW-SUB-MODES"; }));
}

TEST_CASE("a LinuxCNC subroutine's plane and units hold for its calls, and a G18 .. G17 around a run in it leaves them so",
          "[jumps][subroutines][plane]") {
  // Half a circle in XZ, Y fixed: under G17 its Z climbs, so it is fitted in XZ between G18
  // and G17. In a body with two ways out, only one after the pass, that G17 must not count
  // as the body leaving G17 stated (its calls are all made in G17): else, read back, the
  // plane after the call would be unknown where the input's is G17, and the check would
  // refuse the fit.
  std::string pass;
  for (int i = 0; i <= 40; ++i) {
    const double a = M_PI * i / 40;
    pass += fmt::format("G1 X{:.4f} Z{:.4f}\n", 10 - 10 * std::cos(a), 10 * std::sin(a));
  }
  const std::string head = "G21 G17 G90\nG0 X0 Y0 Z0\nG1 F500\n";
  const std::string body = "o100 sub\nG90\no101 if [#1 GT 0]\no100 return\no101 endif\nG1 X0 Y0 Z0\n" + pass + "o100 endsub\n";
  const std::string after = "G0 X0 Y0 Z0\no100 call [1]\nG1 X0 Y0\n" + quarter() + "M2\n";
  const CompressResult r = compress_as("linuxcnc", head + body + after);
  REQUIRE(r.ok);
  CHECK(r.runs_kept_as_input == 0);
  CHECK(r.within_band());
  CHECK(r.stats.plane_words_added == 2);
  CHECK(count_of(r.output, "G3") == 2);  // the pass in XZ, the quarter circle after the call

  // A definition runs nothing: a call of a subroutine not read inside it leaves the plane
  // unknown in the body only, and the moves after `endsub` are fitted.
  const CompressResult unread_inside =
      compress_as("linuxcnc", head + "o100 sub\no<probe> call\no100 endsub\nG1 X0 Y0\n" + quarter() + "M2\n");
  REQUIRE(unread_inside.ok);
  CHECK(count_of(unread_inside.output, "G3") == 1);

  // A body read in G17 may hold arcs fitted in G17: a call where the plane is not known (after
  // a subroutine not read) fails. Defined where the plane is not known, its moves are fitted
  // only once it states one, and any call may run it.
  DiagnosticSink sink;
  CompressOptions opt;
  opt.dialect = shipped_dialect("linuxcnc");
  const std::string known_body = "o100 sub\nG90\nG1 X0 Y0\n" + quarter() + "o100 endsub\n";
  const CompressResult refused = compress("part.ngc", head + known_body + "o<probe> call\no100 call\nM2\n", opt, sink);
  CHECK_FALSE(refused.ok);
  CHECK(std::any_of(sink.all().begin(), sink.all().end(), [](const Diagnostic& d) { return d.code == "E-FLOW-SUB-MODES"; }));
  const CompressResult unknown_body = compress_as("linuxcnc", head + "o<probe> call\n" + known_body + "o100 call\nM2\n");
  REQUIRE(unknown_body.ok);
  CHECK(count_of(unknown_body.output, "G3") == 0);
  CHECK(count_of(compress_as("linuxcnc", head + "o<probe> call\n" + known_body + "G18\no100 call\nM2\n").output, "G3") == 0);
}

TEST_CASE("Marlin's repeat marker is a loop, and the moves after M808 L are entered from its end", "[jumps]") {
  // The loop goes back from M808 to the block after M808 L: where the tool is there, and
  // whether G90 or G91 is in force, the loop's end decides.
  const std::string head = "G90\nM83\nG1 X0 Y0 F1200\n";
  const std::string loop = "M808 L3\n" + quarter() + "G1 X0 Y0\nM808\n";
  CHECK(count_of(compress_as("marlin", head + quarter() + "M808 L3\n").output, "G3") == 1);  // (as a mark alone)
  const CompressResult looped = compress_as("marlin", head + loop);
  REQUIRE(looped.ok);
  CHECK(count_of(looped.output, "G3") == 0);
  CHECK(looped.output.find(quarter()) != std::string::npos);
  std::string stated = loop;
  stated.insert(stated.find('\n') + 1, "G90\n");
  const CompressResult fitted = compress_as("marlin", head + stated);
  REQUIRE(fitted.ok);
  CHECK(count_of(fitted.output, "G3") == 1);
  CHECK(fitted.output.find("M808 L3\nG90\nG1 X0.0000 Y0.0000\n") != std::string::npos);  // its first move as written
  // Run again in the G18 its end leaves, the quarter is no arc fitted in G17: its moves are
  // written as they are, unless the loop states its plane at its start.
  std::string g18 = stated;
  g18.insert(g18.find("M808\n"), "G18\n");
  CHECK(count_of(compress_as("marlin", head + g18).output, "G3") == 0);
  std::string g17 = g18;
  g17.insert(g17.find("G90\n"), "G17 ");
  CHECK(count_of(compress_as("marlin", head + g17).output, "G3") == 1);
}

TEST_CASE("a macro file RepRapFirmware's M98 runs, or a jog M291 allows, may move the tool, and the moves after it start anew", "[jumps]") {
  std::string text = "G90\nG1 X0 Y0 F1200\n" + quarter();
  const size_t mid = text.find("G1 X", text.find("G1 X", 20) + 300);
  text.insert(mid, "M98 P\"park.g\"\n");
  const CompressResult r = compress_as("reprapfirmware", text);
  REQUIRE(r.ok);
  // The move after the call is written as it was (from where the macro left the tool).
  const std::string after = text.substr(mid + 14, text.find('\n', mid + 14) - mid - 13);
  CHECK(r.output.find("M98 P\"park.g\"\n" + after) != std::string::npos);
  // So may the user, where M291's message box lets them jog (Z1).
  std::string jog = text;
  jog.replace(mid, 14, "M291 P\"Set Z\" S3 Z1\n");
  CHECK(compress_as("reprapfirmware", jog).output.find("M291 P\"Set Z\" S3 Z1\n" + after) != std::string::npos);
  // A message (M117 "...") moves nothing: one arc goes on across it.
  std::string message = text;
  message.replace(mid, 14, "M117 \"hello\"\n");
  CHECK(compress_as("reprapfirmware", message).output.find("M117 \"hello\"\n" + after) == std::string::npos);
}

TEST_CASE("a jump back read after its target was read fails a program pushed as it comes, not one whose jumps were read ahead", "[jumps]") {
  std::string text = "G90 G17 G21\nG0 X0 Y0\nG1 F500\n" + quarter(15) + "G1 X1 Y30\nIF [#1 LT 3] GOTO 100\nM30\n";
  std::string dialect = "fanuc";
  SECTION("a block number") {}
  SECTION("a label") {  // (Sinumerik's)
    text.replace(text.find("N100 "), 5, "LOOP1: ");
    text.replace(text.find("IF [#1 LT 3] GOTO 100"), 21, "IF R1<3 GOTOB LOOP1");
    dialect = "sinumerik";
  }
  auto run = [&](bool ahead) {
    DiagnosticSink sink;
    CompressOptions opt;
    opt.dialect = shipped_dialect(dialect);
    opt.fit.tolerance_mm = 0.01;
    Compressor c("part.nc", opt, sink);
    if (ahead) c.read_jumps(text, 1);
    for (size_t at = 0; at < text.size();) {  // a line at a time, as from a slow pipe
      const size_t nl = text.find('\n', at) + 1;
      c.push(std::string_view(text).substr(at, nl - at));
      at = nl;
    }
    c.finish();
    std::string out;
    c.take(out);
    const bool told = std::any_of(sink.all().begin(), sink.all().end(),
                                  [](const Diagnostic& d) { return d.code == "E-FLOW-JUMP-BACK"; });
    return std::pair(c.result().ok, told ? out : std::string("no error") + out);
  };
  const auto [late_ok, late_out] = run(false);
  CHECK_FALSE(late_ok);
  CHECK(late_out.empty());
  const auto [ahead_ok, ahead_out] = run(true);
  CHECK(ahead_ok);
  CHECK(ahead_out.find("no error") == 0);
  CHECK(ahead_out.find(dialect == "fanuc" ? "\nN100 G1 X" : "\nLOOP1: G1 X") != std::string::npos);
}

namespace {

/// A program whose jump back comes more than a read (1 MB) after its target, N100.
std::string far_jump_back() {
  std::string text = "G90 G17 G21\nG0 X0 Y0\nG1 F500\n" + quarter(15);
  for (int k = 0; k < 70000; ++k) text += fmt::format("G1 X{:.3f} Y{:.3f}\n", k * 0.01, 30 + (k % 2) * 0.001);
  return text + "IF [#1 LT 3] GOTO 100\nM30\n";
}

}  // namespace

TEST_CASE("compress_stream() reads the jumps of a stream it can read again before its blocks", "[jumps]") {
  const std::string text = far_jump_back();
  std::istringstream in(text);
  std::ostringstream out;
  DiagnosticSink sink;
  CompressOptions opt;
  opt.dialect = shipped_dialect("fanuc");
  opt.fit.tolerance_mm = 0.01;
  const CompressResult r = compress_stream(in, out, "part.nc", opt, sink);
  CHECK(r.ok);
  CHECK(r.within_band());
  CHECK(out.str().find("\nN100 G1 X") != std::string::npos);
}

TEST_CASE("the command reads a program's jumps before its blocks, from a pipe too unless told to stream it", "[jumps][cli]") {
  const std::string text = far_jump_back();
  const auto dir = temp_dir("jumps");
  write_file(dir / "back.nc", text);
  const Command file = run_arcpress(fmt::format("'{}' -o '{}' --dialect fanuc --tolerance 0.01", (dir / "back.nc").string(),
                                                (dir / "out.nc").string()));
  CHECK(file.exit_code == 0);
  const std::string from_file = read_file(dir / "out.nc");
  CHECK(from_file.find("\nN100 G1 X") != std::string::npos);
  // Standard input that is a regular file is read ahead as the file is.
  const Command redirected = run_shell(fmt::format("\"$ARCPRESS\" --dialect fanuc --tolerance 0.01 < '{}'",
                                                   (dir / "back.nc").string()));
  CHECK(redirected.exit_code == 0);
  CHECK(redirected.out == from_file);
  // A pipe is read to its end first (kept in a temporary file, which is gone afterwards)
  // and comes out as the file does.
  std::filesystem::create_directories(dir / "tmp");
  const Command pipe = run_shell(fmt::format("cat '{}' | TMPDIR='{}' \"$ARCPRESS\" --dialect fanuc --tolerance 0.01",
                                             (dir / "back.nc").string(), (dir / "tmp").string()));
  CHECK(pipe.exit_code == 0);
  CHECK(pipe.out == from_file);
  CHECK(std::filesystem::is_empty(dir / "tmp"));
  // Streamed as it comes, the jump back is read after its block went out.
  const Command streamed = run_shell(fmt::format("cat '{}' | \"$ARCPRESS\" --dialect fanuc --tolerance 0.01 --stream",
                                                 (dir / "back.nc").string()));
  CHECK(streamed.exit_code == 2);
  CHECK(streamed.err.find(":70035:1: error: E-FLOW-JUMP-BACK: a jump back to N100") != std::string::npos);
  // Where the temporary file cannot be made: exit 3, the folder named, nothing written.
  const Command nowhere = run_shell(fmt::format("cat '{}' | TMPDIR='{}' \"$ARCPRESS\" --dialect fanuc",
                                                (dir / "back.nc").string(), (dir / "none").string()));
  CHECK(nowhere.exit_code == 3);
  CHECK(nowhere.out.empty());
  CHECK(nowhere.err.find("cannot keep standard input in a temporary file in '" + (dir / "none").string()) !=
        std::string::npos);
}

TEST_CASE("Heidenhain's repeat runs the lines after its label again, and the lines a call runs return in the modes they leave",
          "[jumps]") {
  // What compress() makes of `text` under heidenhain-iso: the arcs it wrote, and whether it
  // told that a loop runs its first moves in other modes (W-FLOW-LOOP-MODES).
  auto run = [](const std::string& text) {
    DiagnosticSink sink;
    CompressOptions opt;
    opt.dialect = shipped_dialect("heidenhain-iso");
    opt.fit.tolerance_mm = 0.01;
    const CompressResult r = compress("part.h", text, opt, sink);
    CHECK(r.ok);
    CHECK(sink.warning_count("E-LEX-CHAR") == 0);
    return std::pair(count_of(r.output, "G03") + count_of(r.output, "G3 "), sink.warning_count("W-FLOW-LOOP-MODES") > 0);
  };
  const std::string head = "%P G71 *\nN10 G17 G90 *\nN20 G00 X0 Y0 Z0 *\nN25 G01 F500 *\n";
  // `L1,2` after a G18 runs the quarter again in G18: written as it is, and told; with the
  // plane stated after the label, one arc. (A label is entered from elsewhere: the position
  // and G90 or G91 are not known there until stated.)
  const std::string label = "N30 G98 L1 *\nN35 G90 G00 X0 Y0 Z0 *\nN36 G01 *\n";
  CHECK(run(head + label + quarter() + "N900 G18 *\nN910 L1,2 *\nN920 M30 *\n") == std::pair(size_t(0), true));
  CHECK(run(head + label + "N37 G17 *\n" + quarter() + "N900 G18 *\nN910 L1,2 *\nN920 M30 *\n") ==
        std::pair(size_t(1), false));
  CHECK(run(head + label + quarter() + "N900 G18 *\nN905 G17 *\nN910 L1,2 *\nN920 M30 *\n") == std::pair(size_t(1), false));
  // `L5,0` calls the lines after label 5, which leave G18: the quarter after the call is read
  // with the plane not known until the program states it.
  const std::string body = "N920 M30 *\nN930 G98 L5 *\nN940 G18 *\nN950 G98 L0 *\n";
  CHECK(run(head + "N30 L5,0 *\nN35 G00 X0 Y0 Z0 *\nN36 G01 *\n" + quarter() + body).first == 0);
  CHECK(run(head + "N30 L5,0 *\nN35 G17 G90 G71 G00 X0 Y0 Z0 *\nN36 G01 *\n" + quarter() + body).first == 1);
}

TEST_CASE("arcpress diff holds B to the blocks A's jumps enter", "[jumps][cli]") {
  // (The jump's block states G90: the moves after it are placed, so A is SAME as itself.)
  std::string a = "G90 G17 G21\nG0 X0 Y0\nG1 F500\n" + quarter(15) + "IF [#1 LT 3] GOTO 100\nM30\n";
  a.insert(a.find("N100 ") + 5, "G90 ");
  std::string b = a;
  b.erase(b.find("N100 "), 5);  // the same path, the jump's block without its number
  const auto dir = temp_dir("jump-diff");
  write_file(dir / "a.nc", a);
  write_file(dir / "b.nc", b);
  const std::string files = fmt::format("'{}' '{}'", (dir / "a.nc").string(), (dir / "b.nc").string());
  const Command same = run_arcpress(fmt::format("diff '{}' '{}' --tolerance 0.01", (dir / "a.nc").string(),
                                                (dir / "a.nc").string()));
  CHECK(same.exit_code == 0);
  const Command differs = run_arcpress("diff " + files + " --tolerance 0.01");
  CHECK(differs.exit_code == 1);
  CHECK(differs.out.find("block N100 (A line 19), which a jump enters, is not in B") != std::string::npos);
  // So with a label: B without it runs no loop.
  std::string la = a;
  la.replace(la.find("N100 "), 5, "LOOP1: ");
  la.replace(la.find("IF [#1 LT 3] GOTO 100"), 21, "IF R1<3 GOTOB LOOP1");
  write_file(dir / "la.mpf", la);
  write_file(dir / "lb.mpf", b);
  const Command label = run_arcpress(fmt::format("diff '{}' '{}' --tolerance 0.01 --dialect sinumerik",
                                                 (dir / "la.mpf").string(), (dir / "lb.mpf").string()));
  CHECK(label.exit_code == 1);
  CHECK(label.out.find("block LOOP1: (A line 19), which a jump enters, is not in B") != std::string::npos);
}

TEST_CASE("a subprogram's caller goes on in the modes its body leaves, and the body runs in those of its calls", "[jumps][subprograms]") {
  const Dialect fanuc = shipped_dialect("fanuc");
  const std::string head = "G90 G17 G21\nG0 X0 Y0\nG1 F500\n";
  // O2000 states G91 and returns: the caller's words after M98 are increments (Fanuc,
  // Haas), not the quarter circle they would be in G90.
  auto leaving = [&](const std::string& body) { return head + "M98 P2000\n" + quarter() + "G90 G0 Z5\nM30\nO2000\n" + body + "M99\n"; };
  const std::string g91 = leaving("G91 G1 X1.\n");
  const CompressResult kept = compress_as("fanuc", g91);
  REQUIRE(kept.ok);
  CHECK(count_of(kept.output, "G3") == 0);
  CHECK(kept.output == g91);
  // A body that states G90 again before it returns leaves G90.
  CHECK(count_of(compress_as("fanuc", leaving("G91 G1 X1.\nG90\n")).output, "G3") == 1);
  // The check reads them so too: one arc through the quarter's places is another path.
  auto as_arc = [](std::string t) {  // (from the quarter's first place on)
    const size_t from = t.find("G1 X0.0000 Y0.0000\n") + 19;
    return t.replace(from, t.find("G90 G0 Z5") - from, "G3 X-20. Y20. I-20. J0.\n");
  };
  DiffOptions opt;
  opt.tolerance_mm = 0.01;
  CHECK_FALSE(diff_texts(g91, as_arc(g91), opt, fanuc).same(opt.tolerance_mm));
  const std::string g90 = leaving("G91 G1 X1.\nG90\n");
  CHECK(diff_texts(g90, as_arc(g90), opt, fanuc).same(opt.tolerance_mm));

  // A program not in the file (stored in the control, a probing cycle's G65 P9810) may leave
  // another plane, distance mode and motion: nothing after its call is fitted until the
  // program states them again. Its units are taken to be kept.
  const std::string external = head + "M98 P3000\n" + quarter() + "M30\n";
  CHECK(count_of(compress_as("fanuc", external).output, "G3") == 0);
  std::string restated = external;
  restated.insert(restated.find("G1 X0.0000"), "G90 G17\n");
  CHECK(count_of(compress_as("fanuc", restated).output, "G3") == 1);
  // So does a body in the file that calls one not in it, or jumps; the units stay, unless it
  // states them after that.
  for (const std::string inner : {"M98 P3000\n", "IF [#1 GT 2] GOTO 10\nN10\n"}) {
    INFO(inner);
    std::string called = leaving("G21\n" + inner);
    called.insert(called.find("G1 X0.0000"), "G90 G17\n");
    CHECK(count_of(compress_as("fanuc", called).output, "G3") == 1);
    std::string unit_after = called;
    unit_after.insert(unit_after.find("M99\n"), "G21\n");
    CHECK(count_of(compress_as("fanuc", unit_after).output, "G3") == 0);
    unit_after.insert(unit_after.find("G1 X0.0000"), "G21\n");
    CHECK(count_of(compress_as("fanuc", unit_after).output, "G3") == 1);
  }

  // The body runs in the motion, plane and units of its calls: a call made in G0 runs its
  // bare words as rapids; calls in two planes leave its plane unknown until it states one.
  std::string bare;
  for (size_t at = 0, nl; (nl = quarter().find('\n', at)) != std::string::npos; at = nl + 1)
    bare += quarter().substr(at + 3, nl + 1 - at - 3);  // (without "G1 ")
  auto entered = [&](const std::string& calls) { return head + calls + "M30\nO2000\n" + bare + "M99\n"; };
  CHECK(count_of(compress_as("fanuc", entered("M98 P2000\nG0 Z5\nG1 M98 P2000\n")).output, "G3") == 1);
  CHECK(count_of(compress_as("fanuc", entered("G0 Z5\nM98 P2000\n")).output, "G3") == 0);
  CHECK(count_of(compress_as("fanuc", entered("G1 M98 P2000\nG18\nG1 M98 P2000\n")).output, "G3") == 0);
  // Run three times (L3), the body is entered again in the G91 it leaves.
  const std::string once = head + "M98 P2000\nG90 G0 Z5\nM30\nO2000\nG1 X0 Y0\n" + quarter() + "G91 G1 X1.\nM99\n";
  CHECK(count_of(compress_as("fanuc", once).output, "G3") == 1);
  std::string thrice = once;
  thrice.replace(thrice.find("M98 P2000"), 9, "M98 P2000 L3");
  CHECK(count_of(compress_as("fanuc", thrice).output, "G3") == 0);
  // A body's first increment starts where its call left the tool, not where the move before it
  // in the text ends: no joint of the path, tangent or not.
  const CompressResult floated = compress_as("rs274", "G21 G90 G18\nG0 X0 Y0 Z0\nG1 F1000\nG1 X0.077 Y0.003\n"
                                                      "G1 X0.141 Y0.022\nG1 X0.184 Y0.044\nM2\nO9000\nG91 G1 X0.5\nM99\n");
  REQUIRE(floated.ok);
  CHECK(count_of(floated.output, "G3") == 1);
  CHECK(floated.comparison.smooth_joints == 0);
  // A body another body calls is entered in modes not read before it (here O2000's G18, read
  // after it): not fitted until it states them.
  const std::string nested = head + "M98 P2000\nM30\nO3000\n" + bare + "M99\nO2000\nG18 G1 Z-1.\nM98 P3000\nM99\n";
  CHECK(count_of(compress_as("fanuc", nested).output, "G3") == 0);
  std::string nested_stated = nested;
  nested_stated.insert(nested_stated.find("O3000\n") + 6, "G90 G17 G21 G1\n");
  CHECK(count_of(compress_as("fanuc", nested_stated).output, "G3") == 1);
}

TEST_CASE("a program piped in reads the subprograms after its end as a file does", "[jumps][subprograms][cli]") {
  const std::string head = "G90 G17 G21\nG0 X0 Y0\nG1 F500\n";
  const auto dir = temp_dir("piped_subprogram");
  for (const char* body : {"G91 G1 X1.\n", "G91 G1 X1.\nG90\n"}) {
    write_file(dir / "sub.nc", head + "M98 P2000\n" + quarter() + "G90 G0 Z5\nM30\nO2000\n" + body + "M99\n");
    const std::string args = " --dialect fanuc --tolerance 0.01";
    const Command file = run_arcpress("'" + (dir / "sub.nc").string() + "'" + args);
    const Command pipe = run_shell(fmt::format("cat '{}' | \"$ARCPRESS\"{}", (dir / "sub.nc").string(), args));
    REQUIRE(file.exit_code == 0);
    CHECK(pipe.exit_code == 0);
    CHECK(pipe.out == file.out);
    // (After a body that leaves G90 the quarter is one arc; streamed, the body is not read,
    // and nothing after the call is fitted.)
    const bool g90 = std::string(body).find("G90") != std::string::npos;
    CHECK(count_of(pipe.out, "G3") == (g90 ? 1 : 0));
    const Command streamed = run_shell(fmt::format("cat '{}' | \"$ARCPRESS\"{} --stream", (dir / "sub.nc").string(), args));
    CHECK(streamed.exit_code == 0);
    CHECK(count_of(streamed.out, "G3") == 0);
  }
}

TEST_CASE("a jump's target is read in the modes of every way in, and a loop back in other modes is left unfitted", "[jumps]") {
  // Block N10 at the quarter's start, stating `target` (G90 at least: the moves after it
  // are then placed), the quarter's other moves in the motion in force.
  auto from = [](const std::string& target) {
    std::string t = quarter();
    for (size_t at = t.find("G1 "); at != std::string::npos; at = t.find("G1 ", at)) t.erase(at, 3);
    return "N10 " + target + t;
  };
  const std::string head = "G90 G17 G21\nG0 X0 Y0 Z0\nG1 F500\n";
  // What compress() makes of `text`: how many arcs it wrote, and whether it told that a
  // loop runs its first moves in other modes (W-FLOW-LOOP-MODES).
  auto run = [](const std::string& text, const std::string& dialect = "fanuc") {
    DiagnosticSink sink;
    CompressOptions opt;
    opt.dialect = shipped_dialect(dialect);
    opt.fit.tolerance_mm = 0.01;
    const CompressResult r = compress("part.nc", text, opt, sink);
    CHECK(r.ok);
    const bool told = std::any_of(sink.all().begin(), sink.all().end(),
                                  [](const Diagnostic& d) { return d.code == "W-FLOW-LOOP-MODES"; });
    return std::pair(count_of(r.output, "G3"), told);
  };
  // A jump ahead past a G18, a G20 or a G0: N10 is entered in either, so its moves are not
  // placed (the plane, the units) or not read as feed moves (the motion) until the program
  // states it; stated in N10, they are one arc again.
  auto ahead = [&](const std::string& skipped, const std::string& target) {
    return run(head + "IF [#1 EQ 1] GOTO 10\n" + skipped + from(target) + "G0 Z5\nM30\n").first;
  };
  CHECK(ahead("M8\n", "G90 ") == 1);  // (nothing modal passed over)
  CHECK(ahead("G18\n", "G90 ") == 0);
  CHECK(ahead("G18\n", "G17 G90 ") == 1);
  // (In a program in G18, a G17 jumped over: the quarter would be an arc in G17, where the
  // jump's way runs it in G18.)
  std::string in_zx = head;
  in_zx.replace(4, 3, "G18");
  CHECK(run(in_zx + "IF [#1 EQ 1] GOTO 10\nG17\n" + from("G90 ") + "M30\n").first == 0);
  CHECK(run(in_zx + "IF [#1 EQ 1] GOTO 10\nG17\n" + from("G17 G90 ") + "M30\n").first == 1);
  CHECK(ahead("G20\n", "G90 ") == 0);
  CHECK(ahead("G20\n", "G21 G90 ") == 1);
  CHECK(ahead("G0 Z1\n", "G90 ") == 0);
  CHECK(ahead("G0 Z1\n", "G90 G1 ") == 1);
  // A loop back (GOTO, or M99 P10 in the main program) whose last lines leave G18, G20 or
  // G0: the quarter, fitted as an arc in G17, millimetres and G1, would be read in those on
  // the next pass, where the input's own lines run as they are. A first reading of the whole
  // program finds such loops: their moves are written as they are, and a warning says why.
  auto back = [&](const std::string& target, const std::string& last, const std::string& jump) {
    return head + "#1=0\n" + from(target) + last + "#1=#1+1\n" + jump + "\nM30\n";
  };
  const std::string g18 = back("G90 ", "G18\n", "IF [#1 LT 3] GOTO 10");
  CHECK(run(g18) == std::pair(size_t(0), true));
  CHECK(run(back("G90 ", "G18\n", "M99 P10")) == std::pair(size_t(0), true));
  CHECK(run(back("G90 ", "G20\n", "IF [#1 LT 3] GOTO 10")) == std::pair(size_t(0), true));
  CHECK(run(back("G90 ", "G0 Z1\n", "IF [#1 LT 3] GOTO 10")) == std::pair(size_t(0), true));
  // Stated at the loop's start, the modes are the same on every pass: one arc.
  CHECK(run(back("G17 G90 ", "G18\n", "IF [#1 LT 3] GOTO 10")) == std::pair(size_t(1), false));
  CHECK(run(back("G21 G90 ", "G20\n", "IF [#1 LT 3] GOTO 10")) == std::pair(size_t(1), false));
  CHECK(run(back("G90 G1 ", "G0 Z1\n", "IF [#1 LT 3] GOTO 10")) == std::pair(size_t(1), false));
  // A loop that leaves the modes as it found them: one arc.
  CHECK(run(back("G90 ", "G18\nG17\n", "IF [#1 LT 3] GOTO 10")) == std::pair(size_t(1), false));
  // Sinumerik's GOTOB and Okuma's GOTO N10 jump back as well.
  for (const auto& [dialect, jump] : {std::pair{"sinumerik", "GOTOB N10"}, std::pair{"okuma", "GOTO N10"}}) {
    CHECK(run(head + from("G90 ") + "G18\n" + jump + "\nM30\n", dialect) == std::pair(size_t(0), true));
    CHECK(run(head + from("G17 G90 ") + "G18\n" + jump + "\nM30\n", dialect) == std::pair(size_t(1), false));
  }
  // Sinumerik's jumps to a label: back (GOTOB) and ahead (GOTOF), the label alone on its
  // line or before the block's words, after a block number or not.
  auto labelled = [&](const std::string& label, const std::string& target) { return label + from(target).substr(4); };
  for (const std::string label : {"LOOP1: ", "LOOP1:\n", "N5 loop1: "}) {
    INFO(label);
    CHECK(run(head + labelled(label, "G90 ") + "G18\nGOTOB LOOP1\nM30\n", "sinumerik") == std::pair(size_t(0), true));
    CHECK(run(head + labelled(label, "G17 G90 ") + "G18\nGOTOB LOOP1\nM30\n", "sinumerik") == std::pair(size_t(1), false));
    CHECK(run(head + "GOTOF LOOP1\nG18\n" + labelled(label, "G90 ") + "M30\n", "sinumerik").first == 0);
    CHECK(run(head + "GOTOF LOOP1\nG18\n" + labelled(label, "G17 G90 ") + "M30\n", "sinumerik").first == 1);
  }
  // (A jump to another label leaves it a line like any other.)
  CHECK(run(head + labelled("LOOP1: ", "G90 ") + "G18\nGOTOB LOOP2\nM30\n", "sinumerik") == std::pair(size_t(1), false));
  // A jump to a number the program computes (`GOTO #2`) may enter any numbered block: ahead,
  // the blocks after it are read in its modes too; back, it is checked against every target
  // read.
  CHECK(ahead("#2=10\nIF [#1 EQ 1] GOTO #2\nG18\n", "G90 ") == 0);
  CHECK(ahead("#2=10\nIF [#1 EQ 1] GOTO #2\nG18\n", "G17 G90 ") == 1);
  CHECK(run(in_zx + "#2=10\nIF [#1 EQ 1] GOTO #2\nG17\n" + from("G90 ") + "M30\n").first == 0);
  CHECK(run(in_zx + "#2=10\nIF [#1 EQ 1] GOTO #2\nG17\n" + from("G17 G90 ") + "M30\n").first == 1);
  CHECK(run(back("G90 ", "G18\n", "#2=10\nIF [#1 LT 3] GOTO #2")) == std::pair(size_t(0), true));
  CHECK(run(back("G17 G90 ", "G18\n", "#2=10\nIF [#1 LT 3] GOTO #2")) == std::pair(size_t(1), false));
  CHECK(run(back("G90 ", "G18\nG17\n", "#2=10\nIF [#1 LT 3] GOTO #2")) == std::pair(size_t(1), false));
  // (It names a numbered block: a loop of blocks before it is no target of it.)
  const std::string unnumbered = from("G90 ").substr(4);  // (without "N10 ")
  CHECK(run(head + "#1=0\nWHILE [#1 LT 2] DO1\n" + unnumbered + "#1=#1+1\nEND1\nG18\n#2=10\nIF [#1 LT 3] GOTO #2\nM30\n") ==
        std::pair(size_t(1), false));
  // Pushed as it comes, its text not read ahead, such a loop is found only at its jump back,
  // after its moves were written: the program fails (E-FLOW-LOOP-MODES).
  {
    DiagnosticSink sink;
    CompressOptions opt;
    opt.dialect = shipped_dialect("fanuc");
    Compressor c("part.nc", opt, sink);
    c.read_jumps(g18, 1);
    c.push(g18);
    c.finish();
    CHECK_FALSE(c.result().ok);
    CHECK(std::any_of(sink.all().begin(), sink.all().end(), [](const Diagnostic& d) { return d.code == "E-FLOW-LOOP-MODES"; }));
  }
  // Read whole, as arcpress diff reads a program, the same loop is found and told.
  DiagnosticSink sink;
  Program p = lex("part.nc", g18, sink);
  auto jumps = std::make_shared<JumpTargets>();
  jumps->read(p.text, 1);
  p.jumps = jumps;
  const Interpretation in = interpret(p, sink, shipped_dialect("fanuc"));
  CHECK(sink.error_count() == 0);
  CHECK(std::any_of(sink.all().begin(), sink.all().end(), [](const Diagnostic& d) { return d.code == "W-FLOW-LOOP-MODES"; }));
  CHECK(std::none_of(in.moves.begin(), in.moves.end(), [&](const Move& m) { return m.known && m.kind == MoveKind::Line && p.blocks[m.block].line > 7 && p.blocks[m.block].line < 37; }));
}
