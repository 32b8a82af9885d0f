// SPDX-License-Identifier: GPL-3.0-or-later
#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "arcpress/api/arcpress.hpp"
#include "arcpress/lex/lexer.hpp"
#include "support.hpp"

using namespace arcpress;

namespace {
Program lex_text(const std::string& text, DiagnosticSink& sink) { return lex("t.nc", text, sink); }
std::string letters(const Program& p, const Block& b) {
  std::string s;
  for (auto* w = p.words_begin(b); w != p.words_end(b); ++w) s += w->letter;
  return s;
}
}  // namespace

TEST_CASE("words are read in upper and lower case, with or without spaces", "[lex]") {
  DiagnosticSink sink;
  auto p = lex_text("G1X1Y2\ng 1 x 1 y 2\nG01 X-0.5 Y+3 Z.5 F1.\n", sink);
  REQUIRE(p.blocks.size() == 3);
  CHECK(letters(p, p.blocks[0]) == "GXY");
  CHECK(letters(p, p.blocks[1]) == "GXY");
  CHECK(p.words_begin(p.blocks[1])[1].value == 1.0);
  const Word* w = p.words_begin(p.blocks[2]);
  CHECK(w[0].value == 1.0);
  CHECK(w[1].value == -0.5);
  CHECK(w[2].value == 3.0);
  CHECK(w[3].value == 0.5);
  CHECK(w[4].value == 1.0);
  CHECK(w[4].has_point);
  CHECK(w[1].decimals == 1);
  CHECK(sink.all().empty());
}

TEST_CASE("a word's raw text is exactly what the input wrote", "[lex]") {
  DiagnosticSink sink;
  auto p = lex_text("N0140 G01 X 12.50 Y-3", sink);
  const Block& b = p.blocks[0];
  CHECK(p.raw(b, p.words_begin(b)[0]) == "N0140");
  CHECK(p.raw(b, p.words_begin(b)[2]) == "X 12.50");
  CHECK(p.raw(b, p.words_begin(b)[3]) == "Y-3");
  CHECK(p.words_begin(b)[2].decimals == 2);
}

TEST_CASE("decimal values are correctly rounded doubles", "[lex]") {
  DiagnosticSink sink;
  auto p = lex_text("X43.2289 Y-0.1 Z123456.123456", sink);
  const Word* w = p.words_begin(p.blocks[0]);
  CHECK(w[0].value == 43.2289);
  CHECK(w[1].value == -0.1);
  CHECK(w[2].value == 123456.123456);
}

TEST_CASE("a number may have blanks between its characters, and ends before blanks and the next word", "[lex]") {
  DiagnosticSink sink;
  auto p = lex_text("G1 X1 2.5 Y- 3 .25 Z1. E7\tF 1 0 0\n", sink);
  const Block& b = p.blocks[0];
  REQUIRE(letters(p, b) == "GXYZEF");
  const Word* w = p.words_begin(b);
  CHECK(w[1].value == 12.5);
  CHECK(p.raw(b, w[1]) == "X1 2.5");
  CHECK(w[1].decimals == 1);
  CHECK(w[2].value == -3.25);
  CHECK(p.raw(b, w[2]) == "Y- 3 .25");
  CHECK(w[2].decimals == 2);
  CHECK(w[3].value == 1.0);
  CHECK(p.raw(b, w[3]) == "Z1.");
  CHECK(w[4].value == 7.0);
  CHECK(p.raw(b, w[4]) == "E7");
  CHECK(w[5].value == 100.0);
  CHECK(p.raw(b, w[5]) == "F 1 0 0");
  CHECK(sink.all().empty());
  // A second point starts no number: "X1." ends there, and ".5" is not a word.
  p = lex_text("G1 X1. .5\n", sink);
  CHECK(letters(p, p.blocks[0]) == "GX");
  CHECK(p.raw(p.blocks[0], p.words_begin(p.blocks[0])[1]) == "X1.");
  CHECK(p.blocks[0].kind == BlockKind::Opaque);
  CHECK(sink.error_count() + sink.all().size() > 0);
}

TEST_CASE("numbers with more digits than an integer holds are read whole", "[lex]") {
  DiagnosticSink sink;
  auto p = lex_text("X12345678901234567890.5 Y0.1234567890123456789012345 Z123456789012345678 E12345678901234567 8\n", sink);
  const Word* w = p.words_begin(p.blocks[0]);
  CHECK(w[0].value == 12345678901234567890.5);
  CHECK(w[1].value == 0.1234567890123456789012345);
  CHECK(w[2].value == 123456789012345678.0);
  CHECK(w[3].value == 123456789012345678.0);
  CHECK(sink.all().empty());
}

TEST_CASE("comments of both kinds are skipped and remembered", "[lex]") {
  DiagnosticSink sink;
  auto p = lex_text("G0 X1 (move) Y2 ; rest\n(only a comment)\n; semicolon\n", sink);
  CHECK(letters(p, p.blocks[0]) == "GXY");
  CHECK(p.blocks[0].has_comment);
  CHECK(p.blocks[1].kind == BlockKind::Empty);
  CHECK(p.blocks[1].has_comment);
  CHECK(p.blocks[2].kind == BlockKind::Empty);
}

TEST_CASE("line endings, empty lines and a missing final newline are kept exactly", "[lex]") {
  DiagnosticSink sink;
  auto p = lex_text("G0 X1\r\n\r\n\tG1 Y2\nM2", sink);
  REQUIRE(p.blocks.size() == 4);
  CHECK(p.eol(p.blocks[0]) == "\r\n");
  CHECK(p.raw(p.blocks[1]).empty());
  CHECK(p.raw(p.blocks[2]) == "\tG1 Y2");
  CHECK(p.eol(p.blocks[2]) == "\n");
  CHECK(p.eol(p.blocks[3]).empty());
  std::string back;
  for (const auto& b : p.blocks) back += std::string(p.raw(b)) + std::string(p.eol(b));
  CHECK(back == p.text);
}

TEST_CASE("block delete, line numbers, checksums, percent and O program numbers", "[lex]") {
  DiagnosticSink sink;
  auto p = lex_text("%\nO1006\n/G1 X1\nN10 G1 X2*57\n", sink);
  CHECK(p.blocks[0].kind == BlockKind::Percent);
  CHECK(p.blocks[1].kind == BlockKind::Code);
  CHECK(letters(p, p.blocks[1]) == "O");
  CHECK(p.blocks[2].block_delete);
  CHECK(p.blocks[3].has_checksum);
  CHECK(letters(p, p.blocks[3]) == "NGX");
  CHECK(sink.all().empty());
}

TEST_CASE("Heidenhain ISO blocks end with a star that is no checksum, and a program name line has its words read",
          "[lex]") {
  DiagnosticSink sink;
  auto p = lex_text("%CIRC G71 *\nN10 G01 X+1.5 Y-2*  ; cut\nN20 G1 X2*57\nN99999999 %CIRC G71 *\n%\n% (tape)\n", sink);
  REQUIRE(p.blocks.size() == 6);
  CHECK(p.blocks[0].kind == BlockKind::Code);
  CHECK(letters(p, p.blocks[0]) == "G");
  CHECK(p.words_begin(p.blocks[0])->value == 71);
  CHECK(p.blocks[0].block_end);
  CHECK_FALSE(p.blocks[0].has_checksum);
  CHECK(letters(p, p.blocks[1]) == "NGXY");
  CHECK(p.blocks[1].block_end);
  CHECK(p.blocks[1].has_comment);
  CHECK_FALSE(p.blocks[1].has_checksum);
  // A '+' is remembered, so that new blocks can write numbers as the program does.
  CHECK(p.words_begin(p.blocks[1])[2].plus);
  CHECK_FALSE(p.words_begin(p.blocks[1])[3].plus);
  CHECK(p.words_begin(p.blocks[1])[3].value == -2);
  // A star with a number is still a host's checksum.
  CHECK(p.blocks[2].has_checksum);
  CHECK_FALSE(p.blocks[2].block_end);
  CHECK(letters(p, p.blocks[3]) == "NG");
  CHECK(p.blocks[3].block_end);
  // A '%' alone, or with a comment after a blank, is a tape mark.
  CHECK(p.blocks[4].kind == BlockKind::Percent);
  CHECK(p.blocks[5].kind == BlockKind::Percent);
  CHECK(sink.all().empty());
  // A name after other words than a block number is no program's.
  DiagnosticSink other;
  CHECK(lex_text("G1 X1 %CIRC\n", other).blocks[0].kind == BlockKind::Opaque);
}

TEST_CASE("LinuxCNC parameters, expressions and flow control are recognised, not fitted", "[lex]") {
  DiagnosticSink sink;
  auto p = lex_text("#1=0.1 (SafeHeight)\nG00 X [2019*#3+#5] Y#<y>\nO100 sub\no<loop> while [#1 LT 3]\nO100 endsub\n", sink);
  CHECK(p.blocks[0].kind == BlockKind::Macro);
  CHECK(p.blocks[1].kind == BlockKind::Code);
  CHECK(p.blocks[1].has_expr);
  CHECK(p.words_begin(p.blocks[1])[1].is_expr);
  CHECK(p.words_begin(p.blocks[1])[2].is_expr);
  CHECK(p.blocks[2].kind == BlockKind::Control);
  CHECK(p.blocks[3].kind == BlockKind::Control);
  CHECK(p.blocks[4].kind == BlockKind::Control);
  CHECK(sink.all().empty());
}

TEST_CASE("Fanuc macro lines and firmware host commands are kept as their own kinds", "[lex]") {
  DiagnosticSink sink;
  auto p = lex_text("IF [#100 GT 5] GOTO 10\nWHILE [#1 LT 3] DO1\nEND1\nM117 Printing layer 3\n$H\n?\nSET_FAN_SPEED FAN=x SPEED=1\n", sink);
  CHECK(p.blocks[0].kind == BlockKind::Macro);
  CHECK(p.blocks[1].kind == BlockKind::Macro);
  CHECK(p.blocks[2].kind == BlockKind::Macro);
  CHECK(p.blocks[3].kind == BlockKind::HostCommand);
  CHECK(p.blocks[4].kind == BlockKind::HostCommand);
  CHECK(p.blocks[5].kind == BlockKind::HostCommand);
  CHECK(p.blocks[6].kind == BlockKind::HostCommand);
  CHECK(sink.all().empty());
}

TEST_CASE("non-ASCII bytes inside comments are fine", "[lex]") {
  DiagnosticSink sink;
  auto p = lex_text("G0 X1 (Maß: 3 mm \xE2\x80\x94 ok)\n", sink);
  CHECK(p.blocks[0].kind == BlockKind::Code);
  CHECK(sink.all().empty());
}

TEST_CASE("a word without a number is reported with its line and column", "[lex]") {
  DiagnosticSink sink("bad.nc");
  auto p = lex_text("G1 X1\nG1 X Y2\n", sink);
  CHECK(p.blocks[1].kind == BlockKind::Opaque);
  REQUIRE(sink.all().size() == 1);
  const auto& d = sink.all()[0];
  CHECK(d.code == "E-LEX-NUMBER");
  CHECK(d.at.line == 2);
  CHECK(d.at.col == 4);
  CHECK(sink.format(d).rfind("bad.nc:2:4: warning: E-LEX-NUMBER: word 'X' has no number (found 'Y')", 0) == 0);
}

TEST_CASE("strict mode turns unreadable blocks into errors", "[lex]") {
  DiagnosticSink sink;
  sink.set_strict(true);
  lex_text("G1 X1 @\n(unclosed\n", sink);
  CHECK(sink.error_count() == 2);
  CHECK(sink.all()[0].code == "E-LEX-CHAR");
  CHECK(sink.all()[1].code == "E-LEX-COMMENT");
}

TEST_CASE("repeated warnings of one kind are kept once and counted", "[lex]") {
  DiagnosticSink sink;
  lex_text("G1 X@\nG1 X@\nG1 X@\n", sink);
  CHECK(sink.all().size() == 1);
  CHECK(sink.warning_count("E-LEX-NUMBER") == 3);
  CHECK(sink.format_all().find("2 more E-LEX-NUMBER") != std::string::npos);
}

TEST_CASE("a word longer than 65535 bytes keeps its block as it is, with its place", "[lex]") {
  const std::string text = "G0 X0 Y0 Z0\nG1 X1." + std::string(70000, '0') + "1 F100\nG1 X2\n";
  DiagnosticSink sink("long.nc");
  const Program p = lex("long.nc", text, sink);
  REQUIRE(p.blocks.size() == 3);
  CHECK(p.blocks[1].kind == BlockKind::Opaque);
  CHECK(sink.format_all().find("long.nc:2:4: warning: E-LEX-WORD-LENGTH: word 'X' is 70004 bytes long") !=
        std::string::npos);
  CompressOptions opt;
  DiagnosticSink again("long.nc");
  const CompressResult r = compress("long.nc", text, opt, again);
  REQUIRE(r.ok);
  CHECK(r.output == text);
}

TEST_CASE("a block of more than 65535 words keeps its block as it is, with its place, and is never read short",
          "[lex]") {
  // Inside a run of G1 moves: the M0 must survive, and diff must not call the line absent.
  std::string run = "G21 G90\nG0 X0 Y0 Z0\nG1 F300\n";
  for (int k = 1; k <= 20; ++k) run += fmt::format("G1 X{:.4f} Y{:.4f}\n", 0.5 * k, std::sin(0.1 * k));
  std::string crowded = "M0";
  for (int k = 0; k < 65535; ++k) crowded += " X1";
  crowded += " G1 X10.5 Y0.9\n";
  std::string tail;
  for (int k = 22; k <= 40; ++k) tail += fmt::format("G1 X{:.4f} Y{:.4f}\n", 0.5 * k, std::sin(0.1 * k));
  const std::string text = run + crowded + tail + "M2\n";
  DiagnosticSink sink("crowded.nc");
  const Program p = lex("crowded.nc", text, sink);
  REQUIRE(p.blocks.size() == 44);
  CHECK(p.blocks[23].kind == BlockKind::Opaque);
  CHECK(sink.format_all().find("crowded.nc:24:196606: warning: E-LEX-WORD-COUNT: block has more than 65535 words") !=
        std::string::npos);
  CompressOptions opt;
  DiagnosticSink again("crowded.nc");
  const CompressResult r = compress("crowded.nc", text, opt, again);
  REQUIRE(r.ok);
  CHECK(r.output.find("\n" + crowded) != std::string::npos);
  DiffOptions dopt;
  CHECK(test::diff_texts(text, run + tail + "M2\n", dopt).verdict(dopt.tolerance_mm) != ProgramDiff::Verdict::Same);
}

namespace {
/// Whether `b` holds the blocks and words of `a`, field by field, but for the values of the
/// words of the blocks in `shifted`, which lie `shift` above a's.
void require_same_program(const Program& a, const Program& b, const std::vector<size_t>& shifted, double shift) {
  REQUIRE(a.blocks.size() == b.blocks.size());
  for (size_t i = 0; i < a.blocks.size(); ++i) {
    const Block &x = a.blocks[i], &y = b.blocks[i];
    INFO("block " << i << ": " << a.raw(x));
    CHECK(x.begin == y.begin);
    CHECK(x.length == y.length);
    CHECK(x.line == y.line);
    CHECK(x.eol_length == y.eol_length);
    CHECK(x.kind == y.kind);
    CHECK(x.block_delete == y.block_delete);
    CHECK(x.has_comment == y.has_comment);
    CHECK(x.has_checksum == y.has_checksum);
    CHECK(x.has_expr == y.has_expr);
    REQUIRE(x.word_count == y.word_count);
    const bool moved = std::find(shifted.begin(), shifted.end(), i) != shifted.end();
    for (size_t k = 0; k < x.word_count; ++k) {
      const Word &u = a.words_begin(x)[k], &v = b.words_begin(y)[k];
      CHECK(u.letter == v.letter);
      CHECK(u.value + (moved ? shift : 0.0) == v.value);
      CHECK(u.col == v.col);
      CHECK(u.length == v.length);
      CHECK(u.is_expr == v.is_expr);
      CHECK(u.decimals == v.decimals);
      CHECK(u.has_point == v.has_point);
      CHECK(u.flag == v.flag);
    }
  }
}
}  // namespace

TEST_CASE("lines said to be copies of another program's blocks take over its words where their bytes are the "
          "block's, and lex like the text elsewhere, diagnostics included",
          "[lex]") {
  DiagnosticSink in_sink;
  const std::string input = "\xEF\xBB\xBFG21 G90\r\n/N10 g1 x1.5 Y-2 (cut) *57\r\nG1 X2 Y3 ; on\r\nG1 X@3\r\n"
                            "M117 Printing...\r\nG1 X[1+2] Y#5\r\nG1 X4 Y5\r\n";
  Program source = lex_text(input, in_sink);
  REQUIRE(source.blocks.size() == 7);
  REQUIRE(source.blocks[3].kind == BlockKind::Opaque);
  REQUIRE(in_sink.reported() == 1);
  // Every word of the source 1000 higher than read: a line that takes its block's words over
  // shows it.
  for (Word& w : source.words) w.value += 1000;
  // An output that copies the input's lines with new lines between, and line 7 as its own
  // last line without its end of line. Each copy names its block; lexed all the same are the
  // first line (a byte-order mark is skipped there only), the line whose lexing was reported
  // (so that it is reported again), and two lines that are not their block's bytes.
  std::string out;
  std::vector<CopiedLine> copies;
  auto copy = [&](uint32_t block, std::string_view text) {
    copies.push_back({out.size(), block});
    out += text;
  };
  copy(0, "\xEF\xBB\xBFG21 G90\r\n");
  copy(1, "/N10 g1 x1.5 Y-2 (cut) *57\n");  // taken: the same line, another end of line
  out += "G2 X1 Y1 I0.5 J0\r\n";
  copy(2, "G1 X2 Y3 ; on\r\n");         // taken
  copy(3, "G1 X@3\r\n");
  copy(4, "M117 Printing...\r\n");      // taken
  copy(5, "G1 X[1+2] Y#5\r\n");         // taken
  copy(2, "G1 X2 Y4 ; on\r\n");
  copy(6, "G1 X4 Y5 \r\n");
  out += "G3 X0 Y0 R1\n";
  copy(6, "G1 X4 Y5");                   // taken
  DiagnosticSink lexed_sink, copied_sink;
  const Program lexed = lex("out.nc", out, lexed_sink);
  const Program copied = lex("out.nc", out, copied_sink, source, copies);
  require_same_program(lexed, copied, {1, 3, 5, 6, 10}, 1000);
  CHECK(lexed_sink.reported() == 1);
  CHECK(copied_sink.reported() == 1);
  // With no copies named, the text is lexed as it is.
  DiagnosticSink plain_sink;
  require_same_program(lexed, lex("out.nc", out, plain_sink, source, {}), {}, 0);
}
