// SPDX-License-Identifier: GPL-3.0-or-later
#include <catch2/catch.hpp>

#include "arcpress/extract/run.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"

using namespace arcpress;
using Catch::Matchers::WithinAbs;

namespace {
struct Interpreted {
  Program prog;
  Interpretation in;
  size_t line_r_warnings = 0;  ///< W-MODEL-LINE-R
};
Interpreted run(const std::string& text) {
  DiagnosticSink sink;
  Interpreted r;
  r.prog = lex("t.nc", text, sink);
  r.in = interpret(r.prog, sink);
  r.line_r_warnings = sink.warning_count("W-MODEL-LINE-R");
  return r;
}
}  // namespace

TEST_CASE("absolute and incremental moves give absolute millimetres", "[model]") {
  auto r = run("G21 G90\nG0 X1 Y2 Z3\nG91\nG1 X1 Y1 F100\nG90\nG1 X0\n");
  REQUIRE(r.in.moves.size() == 3);
  CHECK(r.in.moves[1].to[kX] == 2.0);
  CHECK(r.in.moves[1].to[kY] == 3.0);
  CHECK(r.in.moves[1].to[kZ] == 3.0);
  CHECK(r.in.moves[1].kind == MoveKind::Line);
  CHECK(r.in.moves[2].to[kX] == 0.0);
  CHECK(r.in.moves[2].to[kY] == 3.0);
}

TEST_CASE("inch programs are converted to millimetres", "[model]") {
  auto r = run("G20 G90\nG0 X1 Y0 Z0\nG1 X2 F10\n");
  REQUIRE(r.in.moves.size() == 2);
  CHECK_THAT(r.in.moves[1].to[kX], WithinAbs(50.8, 1e-12));
  CHECK_THAT(r.in.moves[1].feed_mm_min, WithinAbs(254.0, 1e-12));
  CHECK(r.in.frames[r.in.moves[1].frame].unit_mm == 25.4);
}

TEST_CASE("G92 shifts the coordinates without moving", "[model]") {
  auto r = run("G0 X10 Y0 Z0\nG92 X0\nG1 X5 F100\nG92.1\nG1 X5\n");
  REQUIRE(r.in.moves.size() == 3);
  CHECK(r.in.moves[1].to[kX] == 15.0);
  CHECK(r.in.moves[2].to[kX] == 5.0);
}

TEST_CASE("modal motion and feed carry over to blocks without them", "[model]") {
  auto r = run("G0 X0 Y0 Z0\nG1 X1 F300\nX2\nY2\n");
  REQUIRE(r.in.moves.size() == 4);
  CHECK(r.in.moves[3].kind == MoveKind::Line);
  CHECK(r.in.moves[3].feed_mm_min == 300.0);
  CHECK(r.in.moves[3].fittable());
}

TEST_CASE("arcs get their centre from I/J, G90.1 absolute centres and R", "[model]") {
  auto r = run("G0 X10 Y0 Z0\nG3 X0 Y10 I-10 J0 F100\nG90.1\nG2 X10 Y0 I0 J0\nG3 X0 Y10 R10\nG91.1\nG18 G0 X0 Y0 Z10\nG2 X10 Z0 I0 K-10\n");
  REQUIRE(r.in.moves.size() == 6);
  CHECK(r.in.moves[1].kind == MoveKind::ArcCCW);
  CHECK(r.in.moves[1].center.isApprox(Vec3(0, 0, 0)));
  CHECK(r.in.moves[2].kind == MoveKind::ArcCW);
  CHECK(r.in.moves[2].center.isApprox(Vec3(0, 0, 0)));
  CHECK_THAT(r.in.moves[3].center.x(), WithinAbs(0, 1e-9));
  CHECK_THAT(r.in.moves[3].center.y(), WithinAbs(0, 1e-9));
  CHECK(r.in.moves[5].plane == Plane::ZX);
  CHECK_THAT(r.in.moves[5].center.z(), WithinAbs(0, 1e-9));
  CHECK_THAT(r.in.moves[5].center.x(), WithinAbs(0, 1e-9));
}

TEST_CASE("M83 makes E relative, M82 absolute, G92 E resets it", "[model]") {
  auto r = run("G0 X0 Y0 Z0\nM83\nG1 X1 E0.5 F1200\nG1 X2 E0.5\nM82\nG92 E0\nG1 X3 E2\n");
  REQUIRE(r.in.moves.size() == 4);
  CHECK(r.in.moves[1].to[kE] == 0.5);
  CHECK(r.in.moves[2].to[kE] == 1.0);
  CHECK(r.in.moves[3].to[kE] == 3.0);  // G92 E0 at E=1, then E2
}

TEST_CASE("what cannot be evaluated makes the position unknown, and an unknown axis that does not move stays put",
          "[model]") {
  auto r = run("G0 X0 Y0 Z0\nG1 X[#1*2] F100\nG1 Y1\nG1 X2 Y1 Z0\nG1 X3\nG53 G0 Z0\nG1 X4\n");
  REQUIRE(r.in.moves.size() == 7);
  CHECK_FALSE(r.in.moves[1].known);
  CHECK(r.in.moves[1].unfit == Unfit::UnknownAfterExpression);
  CHECK(r.in.moves[2].known);        // X unknown, but this move does not move it
  constexpr uint16_t kXYZ = (1u << kX) | (1u << kY) | (1u << kZ);
  CHECK((r.in.moves[2].unknown_axes & kXYZ) == (1u << kX));
  CHECK(r.in.moves[2].unknown_axes & (1u << kA));  // never set by the program either
  CHECK_FALSE(r.in.moves[3].known);  // X unknown at its start
  CHECK(r.in.moves[3].unfit == Unfit::UnknownAfterExpression);
  CHECK(r.in.moves[4].known);
  CHECK(r.in.moves[4].fittable());
  CHECK(r.in.moves[5].kind == MoveKind::Other);
  CHECK(r.in.moves[6].known);  // Z in machine coordinates is not in our frame, and X4 does not move it
  CHECK((r.in.moves[6].unknown_axes & kXYZ) == (1u << kZ));
  // The feed moves that could not be placed, each with the block that made its axis unknown.
  REQUIRE(r.in.unplaced.size() == 2);
  CHECK(r.in.unplaced[0].move == 1);
  CHECK(r.in.unplaced[0].cause_line == 2);
  CHECK(r.in.unplaced[1].move == 3);
  CHECK(r.in.unplaced[1].cause_line == 2);
}

TEST_CASE("axes a program never sets are constant: a 2-D program's moves are placed", "[model]") {
  auto r = run("G21 G90\nG0 X1 Y1\nG1 X2 Y1 F300\nG1 X3 Y2\nG2 X5 Y2 I1 J0\n");
  REQUIRE(r.in.moves.size() == 4);
  CHECK_FALSE(r.in.moves[0].known);  // from where X and Y were never set
  CHECK(r.in.moves[0].unfit == Unfit::UnknownAtStart);
  for (size_t k = 1; k < 4; ++k) {
    CHECK(r.in.moves[k].known);
    CHECK(r.in.moves[k].unknown_axes == (1u << kZ | 1u << kA | 1u << kB | 1u << kC | 1u << kU | 1u << kV | 1u << kW));
  }
  CHECK(r.in.moves[1].fittable());
  CHECK(r.in.unplaced.empty());  // the G0 from nowhere is no feed move
}

TEST_CASE("after homing, a move that moves a homed axis is unplaced until the axis is set again", "[model]") {
  auto r = run("G0 X0 Y0 Z0\nG1 X1 F100\nG28\nG1 X2 Y2\nG1 X3\nG1 Z1\nG1 Z2\n");
  REQUIRE(r.in.moves.size() == 7);
  CHECK(r.in.moves[2].kind == MoveKind::Other);
  CHECK_FALSE(r.in.moves[3].known);  // X and Y from the home position
  CHECK(r.in.moves[3].unfit == Unfit::UnknownAfterHoming);
  CHECK(r.in.moves[4].known);        // X from X2, Y and Z still
  CHECK_FALSE(r.in.moves[5].known);  // Z from the home position
  CHECK(r.in.moves[6].known);
  REQUIRE(r.in.unplaced.size() == 2);
  CHECK(r.in.unplaced[0].cause_line == 3);
}

TEST_CASE("S on a feed move is the power in force along it", "[model]") {
  auto r = run("G0 X0 Y0\nM4 S0\nG1 X1 F1000 S300\nG1 X2\nG1 X3 S500\n");
  REQUIRE(r.in.moves.size() == 4);
  CHECK(r.in.moves[0].spindle == 0);
  CHECK(r.in.moves[1].spindle == 300);
  CHECK(r.in.moves[2].spindle == 300);
  CHECK(r.in.moves[3].spindle == 500);
  CHECK(r.in.moves[1].fittable());
  CHECK(r.in.moves[3].fittable());
}

TEST_CASE("only plain G1 blocks are fittable and runs stop at everything else", "[extract]") {
  auto r = run(
      "G0 X0 Y0 Z0\n"
      "G1 X1 F100\nX2\nX3 (comment)\nX4\nX5\nM3\nX6\nX7\nX8\nG1 X9 F200\nX10\n");
  auto runs = extract_runs(r.in);
  REQUIRE(runs.size() == 4);
  CHECK(runs[3].move_count == 2);  // X9 X10
  CHECK(runs[0].move_count == 2);  // X1 X2; X3 has a comment
  CHECK(runs[1].move_count == 2);  // X4 X5
  CHECK(runs[2].move_count == 3);  // X6 X7 X8 (F changes at X9)
  CHECK(runs[0].point(r.in, 0).isApprox(Vec3(0, 0, 0)));
  CHECK(runs[2].point(r.in, 3).x() == 8.0);
}

TEST_CASE("canned cycles, homing and work-offset changes are barriers", "[model]") {
  auto r = run("G0 X0 Y0 Z0\nG81 X1 Y1 Z-1 R1 F100\nG80\nG1 X2 Y2\nG1 X3 Y3 Z0\nG1 X3.5\nG55\nG1 X4\n");
  CHECK(r.in.moves[1].kind == MoveKind::Other);
  CHECK_FALSE(r.in.moves[2].known);
  CHECK_FALSE(r.in.moves[3].known);  // Z unknown at its start
  CHECK(r.in.moves[4].known);
  CHECK_FALSE(r.in.moves.back().known);
}

TEST_CASE("bed probing, a skip move, a threading pass and a tool change move the tool where the program does not "
          "say, and leave its position unknown",
          "[model]") {
  // G29 probes the bed and ends where it likes; its X and Y are a grid's size, its F an edge.
  auto probe = run("G0 X0 Y0 Z5\nG1 X10 F3000\nG29 X3 Y3 F0\nG1 X20 Y20\nG1 Z1\n");
  REQUIRE(probe.in.moves.size() == 4);
  CHECK_FALSE(probe.in.moves[2].known);
  CHECK(probe.in.moves[2].unfit == Unfit::UnknownAfterHoming);
  CHECK(probe.in.moves[2].feed_mm_min == 3000);
  CHECK_FALSE(probe.in.moves[3].known);  // Z after the probing
  // G31 stops where a signal comes; G32 cuts a thread, as G33 does: neither is a G1.
  auto skip = run("G0 X0 Y0 Z0\nG1 X1 F100\nG31 X10 F50\nG1 X11\nG1 X12 Y0 Z0\nG1 X13\n");
  REQUIRE(skip.in.moves.size() == 6);
  CHECK(skip.in.moves[2].kind == MoveKind::Other);
  CHECK_FALSE(skip.in.moves[3].known);  // from wherever the signal stopped it
  CHECK_FALSE(skip.in.moves[4].known);  // Y and Z still from there
  CHECK(skip.in.moves[4].end_known);
  CHECK(skip.in.moves[5].known);
  auto thread = run("G18 G0 X20 Z5\nG32 Z-20 F1.5\nG0 X22\nZ5\nX19.5\nG32 Z-20\n");
  for (size_t k : {1, 5}) {
    CHECK(thread.in.moves[k].kind == MoveKind::Other);
    CHECK_FALSE(thread.in.moves[k].fittable());
  }
  // A lathe's G50 with axis words names the present point, as G92; with S alone, a speed limit.
  auto g50 = run("G0 X10 Z10\nG50 X100 Z50\nG1 X99 F100\nG50 S2000\nG1 X98\n");
  REQUIRE(g50.in.moves.size() == 3);
  CHECK(g50.in.moves[1].to[kX] == 9.0);
  CHECK(g50.in.moves[1].to[kZ] == 10.0);
  CHECK(g50.in.moves[2].to[kX] == 8.0);
  // A tool length offset changes what Z names; G43.1's words are the offset, not a place.
  auto length = run("G0 X0 Y0 Z5\nG43 H1\nG1 X1 F100\nG1 Z2\nG43.1 Z0.5\nG1 X2\nG1 Z1\n");
  REQUIRE(length.in.moves.size() == 5);
  CHECK(length.in.moves[1].known);        // X alone: Z stays where the tool is
  CHECK_FALSE(length.in.moves[2].known);  // Z from a point the offset moved
  CHECK(length.in.moves[2].end_known);
  // G43.1 Z0.5 made no move (five moves in all), and what follows is read anew.
  CHECK_FALSE(length.in.moves[3].known);
  CHECK(length.in.moves[3].end_known);
  // A tool change may take the tool anywhere.
  auto m6 = run("G0 X0 Y0 Z0\nG1 X1 F100\nT2 M6\nG1 X2 Y1\nG1 Z1\n");
  CHECK(m6.in.moves[2].end_known);
  CHECK_FALSE(m6.in.moves[2].known);
  CHECK(m6.in.moves[2].unfit == Unfit::UnknownAfterToolChange);
  CHECK_FALSE(m6.in.moves[3].known);  // Z from wherever the change left it
}

TEST_CASE("modal codes that move nothing the path depends on leave the position known", "[model]") {
  for (const char* code : {"G40", "G41 D1", "G42 D1", "G61", "G61.1", "G64 P0.01", "G98", "G99", "G96 S200",
                           "G97 S1000", "G49", "G15", "G50 S2000"}) {
    INFO(code);
    auto r = run(std::string("G0 X0 Y0 Z0\nG1 X1 F100\n") + code + "\nG1 X2 Y1\nG1 X3\n");
    REQUIRE(r.in.moves.size() == 4);
    CHECK(r.in.moves[2].known);
    CHECK(r.in.moves[3].fittable());
  }
}

TEST_CASE("blocks no controller runs are diagnosed with their place and never read as something else", "[model]") {
  DiagnosticSink sink("t.nc");
  Program p = lex("t.nc", "G21 G90\nG0 X0 Y0 Z0\nG2 X10 Y0 F100\nG3 X0 Y0 R2\nG1 X5 X6\nG1 X7\nG3 X0 Y0 R-5.001\n", sink);
  Interpretation in = interpret(p, sink);
  REQUIRE(in.moves.size() == 6);
  // G2 without a centre: not a line, not placed.
  CHECK_FALSE(in.moves[1].known);
  CHECK(in.moves[1].unfit == Unfit::UnreadableArc);
  // R 2 mm for a 10 mm chord: no circle joins the ends.
  CHECK_FALSE(in.moves[2].known);
  CHECK(in.moves[2].unfit == Unfit::UnreadableArc);
  // X twice.
  CHECK_FALSE(in.moves[3].known);
  CHECK(in.moves[3].unfit == Unfit::RepeatedWord);
  // What follows is placed again.
  CHECK(in.moves[4].known);
  // An R a hair short of half the chord (within the controller's check) is the half circle.
  CHECK(in.moves[5].known);
  const std::string said = sink.format_all();
  CHECK(said.find("t.nc:3:1: warning: E-MODEL-ARC-CENTRE: G2 has no centre") != std::string::npos);
  CHECK(said.find("t.nc:4:1: warning: E-MODEL-ARC-RADIUS: R 2.0000 mm is shorter than half the chord, 5.0000 mm") !=
        std::string::npos);
  CHECK(said.find("t.nc:5:7: warning: E-MODEL-REPEATED-WORD: X appears twice in the block ('X6')") != std::string::npos);
  // Under --strict each is an error.
  DiagnosticSink strict("t.nc");
  strict.set_strict(true);
  Program q = lex("t.nc", "G0 X0 Y0 Z0\nG2 X10 Y0 F100\n", strict);
  interpret(q, strict);
  CHECK(strict.error_count() == 1);
}

TEST_CASE("an arc whose end lies off its circle is diagnosed as its controller refuses it, with the reading that "
          "would make it whole",
          "[model]") {
  // I0 J0 from (0,10): the centre at the start under RS274's offsets, the origin under G90.1.
  const std::string program = "G21 G90 G17\nG0 X0 Y10\nG3 X-10 Y0 I0 J0 F100\nG1 X-11\nG3 X0 Y11 I11 J0\n";
  DiagnosticSink sink("t.nc");
  Program p = lex("t.nc", program, sink);
  Interpretation in = interpret(p, sink);
  REQUIRE(in.moves.size() == 4);
  CHECK_FALSE(in.moves[1].known);
  CHECK(in.moves[1].unfit == Unfit::UnreadableArc);
  CHECK(in.moves[2].known);
  CHECK(in.moves[3].known);  // a true quarter circle: no word of it
  CHECK(sink.warning_count("E-MODEL-ARC-RADIUS") == 1);
  CHECK(sink.format_all().find("t.nc:3:1: warning: E-MODEL-ARC-RADIUS: the end lies 14.1421 mm off the circle through "
                               "the start about the centre (read as drawn up to 0.0283 mm); read as the absolute centre (G90.1), "
                               "the radii agree") != std::string::npos);
  // A printer's firmware does not check: it goes on, and so does the reading.
  Dialect printer;
  printer.radius_abs_mm = 0;
  DiagnosticSink quiet("t.nc");
  Program q = lex("t.nc", program, quiet);
  CHECK(interpret(q, quiet, printer).moves[1].known);
  CHECK(quiet.warning_count("E-MODEL-ARC-RADIUS") == 0);
}

TEST_CASE("two readers read on alike when their positions and offsets differ by floating noise only, never by a place",
          "[model]") {
  DiagnosticSink sink;
  ModalState a = initial_state(Dialect{});
  a.pos[kE] = 0.1 + 0.2 + 0.3;  // a relative E counter summed in one order...
  a.frame.offset[kE] = a.pos[kE];
  ModalState b = a;
  b.pos[kE] = 0.3 + 0.2 + 0.1;  // ... and in another (0.6000000000000001 against 0.6)
  b.frame.offset[kE] = b.pos[kE];
  REQUIRE(a.pos[kE] != b.pos[kE]);
  CHECK(a.reads_as(b, true));
  b.pos[kE] += 0.00001;  // the least E step a printer is sent
  CHECK_FALSE(a.reads_as(b, true));
  b = a;
  b.motion = 20;
  CHECK(a.reads_as(b, false));
  CHECK_FALSE(a.reads_as(b, true));
  b = a;
  b.known |= 1u << kZ;  // Z placed in one, not in the other
  CHECK_FALSE(a.reads_as(b, false));
}

TEST_CASE("a line's block with an R word ends where the program does not say", "[model]") {
  // RepRapFirmware's G1 R1 moves to the position saved in slot 1, offset by X/Y/Z; a lathe
  // that takes direct drawing dimensions rounds the corner after G01 X.. R..: the move after
  // starts elsewhere.
  auto r = run("G21 G90\nG0 X0 Y0 Z1\nG1 X1 Y0 F600\nG1 R1 X0 Y0 Z2\nG1 X2 Y0\nG1 X3 Y0\n");
  REQUIRE(r.in.moves.size() == 5);
  CHECK(r.line_r_warnings == 1);
  CHECK_FALSE(r.in.moves[3].known);
  CHECK(r.in.moves[4].known);
  // An arc's R is its radius: the position after it is known.
  auto arc = run("G21 G90\nG0 X0 Y0 Z0\nG2 X2 Y0 R1 F600\nG1 X3 Y0\n");
  REQUIRE(arc.in.moves.size() == 3);
  CHECK(arc.in.moves[2].known);
  CHECK(arc.line_r_warnings == 0);
}

TEST_CASE("after M2 or M30 the program goes on in G1, G17, G90 and G94, as LinuxCNC and Grbl end a program", "[model]") {
  for (const char* end : {"M30", "M2"}) {
    INFO(end);
    // G91, G18 and G93 before the end; after it, a bare axis word is an absolute G1 move in G17.
    auto r = run(std::string("G21 G90\nG0 X1 Y2 Z3\nG91 G18 G93\nG2 X1 Z1 I1 F1\n") + end + "\nX5 Y5 F100\nG3 X7 Y7 R2\n");
    REQUIRE(r.in.moves.size() == 4);
    const Move& after = r.in.moves[2];
    CHECK(after.kind == MoveKind::Line);
    CHECK(after.known);
    CHECK(after.to[kX] == 5.0);
    CHECK(after.to[kY] == 5.0);
    CHECK(after.plane == Plane::XY);
    CHECK(r.in.moves[3].plane == Plane::XY);
    CHECK_FALSE(r.in.frames[after.frame].inverse_time);
  }
  // In another work offset than G54, the end selects G54: the position is read anew.
  auto r = run("G21 G90 G55\nG0 X1 Y2 Z3\nM30\nG1 X5 Y5 F100\n");
  REQUIRE(r.in.moves.size() == 2);
  CHECK_FALSE(r.in.moves[1].known);
}

TEST_CASE("a line not read sets the plane, units, G90/G91 and motion its G words name, as far as arcpress knows",
          "[model]") {
  // The controller reads `G18` and `G91` on lines arcpress does not: the moves after them are
  // not placed until the program states those modes again, where they once were read in G17
  // and G90.
  for (const char* unread : {"G18 X1 Y{depth}", "G91 X1 Y{depth}", "G20 X1 Y{depth}", "G#1 X1 Y2", "G[10+8] X1 Y2"}) {
    INFO(unread);
    auto r = run(std::string("G17 G21 G90\nG0 X0 Y0 Z1\n") + unread + "\nG1 X2 Y1 Z1 F100\nX3 Y2\nG17 G21 G90\nG1 X4 Y2 Z1\nX5 Y3\n");
    const std::vector<Move>& m = r.in.moves;
    REQUIRE(m.size() >= 5);
    CHECK_FALSE(m[m.size() - 4].known);
    CHECK_FALSE(m[m.size() - 3].known);
    CHECK(m.back().known);  // from a place after the modes were stated again
    CHECK(m.back().to[kX] == 5.0);
  }
  // A line whose G words set none of them leaves the moves after it placed once an axis word
  // places them; so do the letters G of names and of comments.
  for (const char* unread : {"G4 X1 Y{depth}", "M117 {depth} G18", "X1 Y{depth} (G18)", "X1 Y{depth} ; G91",
                             "MSG(\"G18\") X{1}", "T{next} GOTOF END"}) {
    INFO(unread);
    auto r = run(std::string("G17 G21 G90\nG0 X0 Y0 Z1\n") + unread + "\nG1 X2 Y1 Z1 F100\nX3 Y2\n");
    REQUIRE(r.in.moves.size() >= 3);
    CHECK(r.in.moves[r.in.moves.size() - 1].known);
    CHECK(r.in.moves[r.in.moves.size() - 1].to[kX] == 3.0);
  }
  // Bare moves after a line whose motion is not known are placed nowhere, and say why.
  auto bare = run("G17 G21 G90\nG0 X0 Y0 Z1\nG1 X1 Y{depth}\nX2 Y1 Z1\nX3 Y2\nG1 X4\n");
  REQUIRE(bare.in.moves.size() == 4);
  CHECK(bare.in.moves[1].kind == MoveKind::Other);
  CHECK_FALSE(bare.in.moves[2].known);
  CHECK(bare.in.moves[2].unfit == Unfit::UnknownDistanceMode);
}
