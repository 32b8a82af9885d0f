// SPDX-License-Identifier: GPL-3.0-or-later
// The Sinumerik language (dialects/sinumerik.toml): its keywords are words of a block, its
// G70/G71 are units, and what arcpress does not read of it is kept as written.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>

#include "arcpress/arcpress.hpp"
#include "arcpress/core/error.hpp"
#include "arcpress/dialect/dialect_loader.hpp"
#include "arcpress/dialect/program_flavor.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"
#include "random_program.hpp"
#include "support.hpp"

using namespace arcpress;

namespace {

Dialect sinumerik() { return find_dialect("sinumerik", {ARCPRESS_SOURCE_DIR "/dialects"}); }
Dialect rs274() { return find_dialect("rs274", {ARCPRESS_SOURCE_DIR "/dialects"}); }
Dialect shipped_siemens_iso() { return find_dialect("siemens", {ARCPRESS_SOURCE_DIR "/dialects"}); }

CompressResult compress_as(const Dialect& d, const std::string& text, double tol_mm) {
  DiagnosticSink sink;
  CompressOptions opt;
  opt.dialect = d;
  opt.fit.tolerance_mm = tol_mm;
  return compress("part.mpf", text, opt, sink);
}

/// `header`, then 40 moves along half a circle of radius `r` (in the program's units) about
/// (-r, 0), printed to `decimals`, then `after`.
std::string half_circle(const std::string& header, double r, int decimals, const std::string& after = "") {
  std::string t = header + "N20 G0 X0 Y0 Z0.2\nN30 G1 Z-0.1 F20\n";
  for (int i = 1; i <= 40; ++i) {
    const double a = M_PI * i / 40;
    t += fmt::format("N{} G1 X{:.{}f} Y{:.{}f}\n", 30 + 10 * i, r * std::cos(a) - r, decimals, r * std::sin(a), decimals);
  }
  return t + after + "N500 G0 Z1\nN510 M30\n";
}

struct Read {
  Program program;
  Interpretation in;
  DiagnosticSink sink{"part.mpf"};
};

std::unique_ptr<Read> read_as(const Dialect& d, const std::string& text) {
  auto r = std::make_unique<Read>();
  r->program = lex("part.mpf", text, r->sink, lex_rules(d));
  r->in = interpret(r->program, r->sink, d);
  return r;
}

}  // namespace

TEST_CASE("a Sinumerik header's keywords are words of its block, and its G70 makes every length inches", "[dialect]") {
  const std::string inch = half_circle("N10 G17 G90 G70 G642 SOFT FFWON\n", 2.0, 4);
  const auto r = read_as(sinumerik(), inch);
  CHECK(r->sink.reported() == 0);
  CHECK(r->sink.warning_count("W-MODEL-UNITS") == 0);
  REQUIRE(r->program.blocks[0].kind == BlockKind::Code);
  CHECK(r->program.blocks[0].word_count == 7);
  REQUIRE(r->in.moves.size() == 1 + 1 + 40 + 1);
  CHECK(r->in.moves[2].to[kX] == Approx((2.0 * std::cos(M_PI / 40) - 2.0) * 25.4).margin(1e-3));
  // The band is millimetres: the chords' sagitta is 0.039 mm, so no circle passes within 0.01 mm
  // of both their ends and their middles; within 0.05 mm, one does.
  const CompressResult fine = compress_as(sinumerik(), inch, 0.01);
  CHECK(test::broken_promise(fine) == "");
  CHECK(fine.stats.arcs_out == 0);
  const CompressResult coarse = compress_as(sinumerik(), inch, 0.05);
  CHECK(test::broken_promise(coarse) == "");
  CHECK(coarse.stats.arcs_out == 1);
  CHECK(coarse.output.rfind("N10 G17 G90 G70 G642 SOFT FFWON\n", 0) == 0);
  // Not read so elsewhere: the line is not understood, and the program is taken for millimetres.
  const auto iso = read_as(rs274(), inch);
  CHECK(iso->program.blocks[0].kind == BlockKind::Opaque);
  CHECK(iso->sink.warning_count("E-LEX-KEYWORD") == 1);
  CHECK(iso->sink.warning_count("W-MODEL-UNITS") == 1);
  // Where the program never states its units, the warning names the language's own codes.
  const auto unstated = read_as(sinumerik(), half_circle("N10 G17 G90\n", 50, 3));
  REQUIRE(unstated->sink.warning_count("W-MODEL-UNITS") == 1);
  CHECK(unstated->sink.format_all().find("before any G70 or G71") != std::string::npos);
}

TEST_CASE("a Sinumerik keyword is read bare, in any case, or with a number after '=', and no other keyword is read",
          "[dialect]") {
  const auto r = read_as(sinumerik(), "N10 G64 soft\nN20 G641 ADIS=0.05 ADISPOS = 0.1\nN30 G0 X0 Y0 Z1 ; go\n"
                                      "N40 G641 ADIS=R1\nN50 G0 X0 Y0 Z1 FOO\nN60 SOFT\n");
  const Program& p = r->program;
  for (int b : {0, 1, 2, 5}) {
    INFO(b);
    CHECK(p.blocks[size_t(b)].kind == BlockKind::Code);
  }
  const Word& adis = p.words[p.blocks[1].first_word + 2];
  CHECK(adis.letter == kKeywordLetter);
  CHECK(p.keyword_name(p.blocks[1], adis) == "ADIS");
  CHECK(adis.value == 0.05);
  CHECK(p.words[p.blocks[1].first_word + 3].value == 0.1);
  CHECK(p.blocks[3].kind == BlockKind::Opaque);  // a value arcpress does not compute
  CHECK(r->sink.warning_count("E-LEX-KEYWORD-VALUE") == 1);
  CHECK(p.blocks[4].kind == BlockKind::Opaque);  // a keyword the dialect does not list
  CHECK(r->sink.warning_count("E-LEX-KEYWORD") == 1);
  // Keywords set nothing the path depends on: the position stays known across them.
  const auto across = read_as(sinumerik(), "N10 G0 X0 Y0 Z5\nN20 G641 ADIS=0.05 SOFT FFWON\nN30 G0 X0 Y0 Z1\n");
  REQUIRE(across->in.moves.size() == 2);
  CHECK(across->in.moves[1].known);
  CHECK_FALSE(read_as(rs274(), "N10 G0 X0 Y0 Z5\nN20 G641 ADIS=0.05 SOFT FFWON\nN30 G0 X0 Y0 Z1\n")->in.moves[1].known);
  // A keyword with its arguments in parentheses: a message and the high-speed settings leave
  // the position known, a swivel of the plane and a drilling cycle where the tool is do not;
  // a call the dialect does not list leaves its line unread.
  for (const auto& [line, known] : {std::pair{"MSG(\"Roughing (1)\")", true}, std::pair{"CYCLE832(0.01,_FINISH,1)", true},
                                    std::pair{"CYCLE800(1,\"\",0,57,0,0,0,0,0,0,0,0,0,1)", false},
                                    std::pair{"CYCLE81(10,0,2,-5)", false}, std::pair{"POCKET9(1,2)", false}}) {
    INFO(line);
    const auto call = read_as(sinumerik(), std::string("N10 G0 X0 Y0 Z5\nN20 ") + line + "\nN30 G0 X0 Y0 Z1\n");
    REQUIRE(call->in.moves.size() == 2);
    CHECK(call->in.moves[1].known == known);
    CHECK((call->program.blocks[1].kind == BlockKind::Opaque) == (std::string(line).rfind("POCKET9", 0) == 0));
  }
}

TEST_CASE("a Sinumerik line of R-parameter assignments is a macro line, X=10 is X10, and X=R1 or X=IC(5) is an X word "
          "whose value is not known",
          "[dialect]") {
  const auto r = read_as(sinumerik(), "N10 R1=5 R2=R1*2\nR[R1]=4\nN20 G0 X=10 Y = -2.5 Z5\nN30 G18 X=R1 Z=IC(5)\n"
                                      "T=\"DRILL 10\" D1\nM2=3 S2=1000\nN40 G1 X10 R1=5\n");
  const Program& p = r->program;
  CHECK(p.blocks[0].kind == BlockKind::Macro);
  CHECK(p.blocks[1].kind == BlockKind::Macro);
  auto words = [&](size_t b) {
    std::string out;
    for (const Word* w = p.words_begin(p.blocks[b]); w != p.words_end(p.blocks[b]); ++w)
      out += fmt::format("{}{} ", w->letter, w->is_expr ? "?" : fmt::format("{:g}", w->value));
    return out;
  };
  CHECK(words(2) == "N20 G0 X10 Y-2.5 Z5 ");
  CHECK(words(3) == "N30 G18 X? Z? ");
  CHECK(p.raw(p.blocks[3], p.words_begin(p.blocks[3])[3]) == "Z=IC(5)");
  CHECK(words(4) == "T? D1 ");  // (the blank in the quoted name is the name's)
  CHECK(words(5) == "M? S? ");
  CHECK(p.blocks[6].kind == BlockKind::Opaque);  // an assignment after a move is not read
  CHECK(r->sink.warning_count("E-LEX-ASSIGN") == 1);
  CHECK(r->sink.warning_count("E-LEX-CHAR") + r->sink.warning_count("E-LEX-NUMBER") == 0);
  REQUIRE(r->in.moves.size() == 2);
  CHECK(r->in.moves[0].to[kX] == 10.0);
  CHECK(r->in.moves[0].to[kY] == -2.5);
  CHECK_FALSE(r->in.moves[1].known);  // X and Z not known
  // Elsewhere an `=` after an address is no word: the line is not read.
  const auto iso = read_as(rs274(), "R1=5\nG0 X=10\n");
  CHECK(iso->program.blocks[0].kind == BlockKind::Opaque);
  CHECK(iso->program.blocks[1].kind == BlockKind::Opaque);
}

TEST_CASE("a Sinumerik label is a word at its block's start, after its number at most, and elsewhere no label", "[dialect]") {
  const auto r = read_as(sinumerik(), "LOOP1:\nN10 _Start2: G1 X0 Y0\nN20 G1 X10 AB:\nA:\n");
  const Program& p = r->program;
  REQUIRE(p.blocks[0].kind == BlockKind::Code);
  REQUIRE(p.blocks[0].word_count == 1);
  const Word& loop1 = *p.words_begin(p.blocks[0]);
  CHECK(loop1.letter == kLabelLetter);
  CHECK(loop1.target_key() == (kLabelKey | label_hash("loop1")));
  REQUIRE(p.blocks[1].kind == BlockKind::Code);
  CHECK(p.words_begin(p.blocks[1])[1].letter == kLabelLetter);
  CHECK(p.raw(p.blocks[1], p.words_begin(p.blocks[1])[1]) == "_Start2:");
  CHECK(p.blocks[1].word_count == 5);  // N10 _Start2: G1 X0 Y0
  CHECK(p.blocks[2].kind == BlockKind::Opaque);  // (after a move's words: no label)
  CHECK(p.blocks[3].kind == BlockKind::Opaque);  // (one letter: no name)
  CHECK(read_as(rs274(), "LOOP1:\n")->program.blocks[0].kind == BlockKind::Opaque);
  // Its jumps are flow control, after a block number too.
  const auto jumps = read_as(sinumerik(), "N10 GOTOB LOOP1\nGOTOF N20\nN30 IF R1<2 GOTOC LOOP1\n");
  for (const Block& b : jumps->program.blocks) CHECK(b.kind == BlockKind::Macro);
  CHECK(jumps->sink.reported() == 0);
}

TEST_CASE("a Sinumerik G18 on a line with an expression is read: a contour in XY after it is written in G17, and G18 "
          "stated again after it",
          "[dialect]") {
  // Once, the `=` left the line unread, and the arcs went out in the plane the program had
  // before it, which the control then reads in XZ.
  const CompressResult res = compress_as(sinumerik(), half_circle("N10 G17 G90 G71\nN15 R1=0\nN16 G18 X=R1\n", 2.0, 4), 0.01);
  CHECK(test::broken_promise(res) == "");
  CHECK(res.stats.arcs_out > 0);
  DiagnosticSink sink;
  const Program out = lex("out.mpf", res.output, sink, lex_rules(sinumerik()));
  const Interpretation in = interpret(out, sink, sinumerik());
  size_t arcs = 0;
  for (const Move& m : in.moves) {
    if (!is_arc(m.kind)) continue;
    ++arcs;
    CHECK(m.plane == Plane::XY);
  }
  CHECK(arcs == res.stats.arcs_out);
  CHECK(res.output.find("G18\nN500 G0 Z1") != std::string::npos);
}

TEST_CASE("Sinumerik's modal call keeps every move it calls at, and its frames, subprogram calls and tangential arcs "
          "are not read through",
          "[dialect]") {
  // MCALL CYCLE81(...) drills at the end of every move until MCALL alone: none is merged.
  const std::string holes = "N10 G17 G90 G71\nN20 G0 X0 Y0 Z5\nN30 G1 Z2 F1000\nN40 MCALL CYCLE81(10,0,2,-5)\n"
                            "N50 X10\nN60 X20\nN70 X30\nN80 X40\nN90 MCALL\nN100 G0 Z50\nN110 M30\n";
  const CompressResult calls = compress_as(sinumerik(), holes, 0.01);
  CHECK(calls.output == holes);
  CHECK(compress_as(rs274(), holes, 0.01).output.find("\nN60 X20\n") == std::string::npos);
  // A keyword's block is compared whole: a call changed, or a line of settings left out, is a difference.
  std::string deeper = holes, unsettled = holes, faster = holes;
  faster.replace(faster.find("N10 G17 G90 G71\n"), 16, "N10 G17 G90 G71\nCYCLE832(0.05,_ROUGH,1)\n");
  deeper.replace(deeper.find("-5)"), 3, "-8)");
  unsettled.replace(unsettled.find("N10 G17 G90 G71\n"), 16, "N10 G17 G90 G71 SOFT\n");
  DiffOptions dopt;
  CHECK(test::diff_texts(holes, holes, dopt, sinumerik()).verdict(0.01) == ProgramDiff::Verdict::Same);
  const std::string finer = std::string(faster).replace(faster.find("0.05,_ROUGH"), 11, "0.01,_FINISH");
  CHECK(test::diff_texts(faster, finer, dopt, sinumerik()).verdict(0.01) == ProgramDiff::Verdict::Different);
  for (const std::string& other : {deeper, unsettled}) {
    const ProgramDiff d = test::diff_texts(holes, other, dopt, sinumerik());
    CHECK(d.non_motion_differences >= 1);
    CHECK(d.verdict(0.01) == ProgramDiff::Verdict::Different);
  }

  // TRANS shifts the coordinates: its X is the shift, and where the tool is after it is not known.
  const auto trans = read_as(sinumerik(), "N10 G71 G90\nN20 G0 X0 Y0 Z1\nN30 TRANS X10\nN40 G1 X5 Y5 F100\nN50 G1 X6\n");
  REQUIRE(trans->in.moves.size() == 3);
  CHECK_FALSE(trans->in.moves[1].known);
  CHECK(trans->in.moves[1].unfit == Unfit::UnknownAfterOffset);
  CHECK(trans->in.moves[2].known);

  // A subprogram call (L10) and a tool's edge (D1) may move the tool.
  for (const char* call : {"N35 L10\n", "N35 D1\n"}) {
    INFO(call);
    const auto sub = read_as(sinumerik(), std::string("N10 G71 G90\nN20 G0 X0 Y0 Z1\nN30 G1 X1 F100\n") + call +
                                              "N40 G1 X5 Y5\nN50 G1 X6\n");
    REQUIRE(sub->in.moves.size() == 4);
    CHECK_FALSE(sub->in.moves[2].known);
  }

  // CT goes on tangentially from the block before it: that move stays as written.
  const std::string ct = half_circle("N10 G17 G90 G71\n", 20, 3, "N450 CT X-60 Y-20\n");
  const CompressResult tangent = compress_as(sinumerik(), ct, 0.05);
  CHECK(test::broken_promise(tangent) == "");
  CHECK(tangent.stats.arcs_out >= 1);
  CHECK(tangent.output.find("\nN430 G1 X-40.000 Y0.000\nN450 CT X-60 Y-20\n") != std::string::npos);
}

TEST_CASE("a Sinumerik arc's CR= is its radius, as RS274's R, and arcpress writes none", "[dialect]") {
  // From (20, 0) a quarter circle of radius 20 about the origin, then a line on along Y.
  const std::string cr = "N10 G17 G90 G71\nN20 G0 X20 Y-5 Z0\nN30 G1 Y0 F500\nN40 G3 X0 Y20 CR=20\n"
                         "N50 G1 X-1 Y20\nN60 G1 X-2 Y20\n";
  const auto r = read_as(sinumerik(), cr);
  CHECK(r->sink.reported() == 0);
  REQUIRE(r->in.moves.size() == 5);
  CHECK(r->in.moves[2].known);
  CHECK(r->in.moves[2].center.norm() == Approx(0).margin(1e-9));
  CHECK(r->in.moves[3].known);  // the position is known after it
  CHECK(read_as(shipped_siemens_iso(), cr)->in.moves.size() == 4);  // ISO mode: a line not understood
  // Over half a turn, CR is negative: the centre lies beyond the chord.
  const auto big = read_as(sinumerik(), "N10 G17 G90 G71\nN20 G0 X20 Y0 Z0\nN30 G3 X0 Y-20 CR=-20 F500\n");
  REQUIRE(big->in.moves.size() == 2);
  CHECK(big->in.moves[1].center.norm() == Approx(0).margin(1e-9));
  // R1..R99 are parameters there: R-form arcs are never written.
  CompressOptions opt;
  opt.dialect = sinumerik();
  opt.arc_format = ArcFormat::Radius;
  DiagnosticSink sink;
  CHECK_THROWS_AS(compress("part.mpf", cr, opt, sink), Error);
  try {
    parse_dialect("name = \"x\"\n[codes]\nG5 = \"arc-radius\"\n", "x.toml");
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find("is a keyword's meaning") != std::string::npos);
  }
}

TEST_CASE("under Sinumerik's DIAMON X words are diameters, and the moves are compared, not fitted", "[dialect]") {
  const std::string lathe = "N10 G18 G90 G71 DIAMON\nN15 SETMS(1)\nN20 G0 X40 Z1\nN25 G96 S200 LIMS=3000\nN30 G1 Z0 F100\n"
                            "N40 G1 X42 Z-1\nN50 G1 X43 Z-2\nN60 DIAMOF\nN70 G1 X22 Z-3\n";
  const auto r = read_as(sinumerik(), lathe);
  CHECK(r->sink.reported() == 0);  // (the master spindle and its speed limit read as modes)
  REQUIRE(r->in.moves.size() == 5);
  CHECK(r->in.moves[1].known);
  CHECK(r->in.moves[0].to[kX] == 20);
  CHECK(r->in.moves[2].unfit == Unfit::DiameterMode);
  CHECK(r->in.moves[4].to[kX] == 22);
  CHECK(r->in.moves[4].unfit != Unfit::DiameterMode);
}

TEST_CASE("a dialect's [codes] take keywords and the letters T, D and L, with what each means", "[dialect]") {
  const Dialect d = parse_dialect("name = \"x\"\n[codes]\nsoft = \"settings\"\nMCALL = \"cycle-calls\"\nD = \"moves\"\n"
                                  "DIAMON = \"diameter\"\n",
                                  "x.toml");
  REQUIRE(d.keyword_meaning("Soft"));
  CHECK(*d.keyword_meaning("SOFT") == CodeMeaning::Settings);
  CHECK(*d.keyword_meaning("diamon") == CodeMeaning::Diameter);
  CHECK(d.keyword_meaning("BRISK") == nullptr);
  REQUIRE(d.meaning_of('D', 0));
  CHECK(*d.meaning_of('D', 0) == CodeMeaning::Moves);
  const std::vector<KeywordSpelling> k = lex_rules(d).keywords;
  REQUIRE(k.size() == 3);  // (in the order of the names)
  CHECK(k[0].name == "DIAMON");
  CHECK(k[1].name == "MCALL");
  CHECK(k[1].takes_call);
  CHECK(k[2].name == "SOFT");
  CHECK_FALSE(k[2].takes_call);
  try {
    parse_dialect("name = \"x\"\n[codes]\nS = \"settings\"\n", "x.toml");
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find("codes.S: expected a G- or M-code") != std::string::npos);
  }
}

TEST_CASE("a Sinumerik program file names its dialect by its first line or its folder on the control",
          "[dialect][flavor]") {
  const auto header = program_flavor("%_N_PART1_MPF\n;$PATH=/_N_MPF_DIR\nN10 G17 G90 G71 SOFT\n");
  REQUIRE(header);
  CHECK(header->dialect == "sinumerik");
  CHECK(header->evidence == "%_N_PART1_MPF");
  CHECK_FALSE(header->slicer);
  const auto folder = program_flavor("; part 1\n;$PATH=/_N_WKS_DIR/_N_PLATE_WPD\nN10 G17 G90 G71\n");
  REQUIRE(folder);
  CHECK(folder->dialect == "sinumerik");
  CHECK(folder->line == 2);
  CHECK(program_flavor("%_N_PART1\nG1 X1\n") == std::nullopt);
  CHECK(program_flavor("%\nO1000\nG1 X1\n") == std::nullopt);
  // Without --dialect the command reads it so: its header's keywords and units are read.
  const auto c = test::run_arcpress("--stats --tolerance 0.05", "%_N_PART1_MPF\n" + half_circle("N10 G17 G90 G70 SOFT\n", 2.0, 4));
  CHECK(c.exit_code == 0);
  CHECK(c.err.find("dialect        sinumerik") != std::string::npos);
  CHECK(c.err.find("by the program's '%_N_PART1_MPF' at line 1") != std::string::npos);
  CHECK(c.err.find("E-LEX-KEYWORD") == std::string::npos);
  CHECK(c.err.find("W-MODEL-UNITS") == std::string::npos);
  CHECK(c.err.find("1 G2/G3") != std::string::npos);
  // A program that names nothing itself is read as its file's extension says: .mpf, .spf.
  CHECK(dialect_of_extension("/cam/out/PART1.MPF") == "sinumerik");
  CHECK(dialect_of_extension("sub.spf") == "sinumerik");
  CHECK(dialect_of_extension("part.nc").empty());
  CHECK(dialect_of_extension("dir.mpf/part").empty());
  const test::TempDir d("sinumerik-ext");
  test::write_file(d / "part1.mpf", half_circle("N10 G17 G90 G70 SOFT\n", 2.0, 4));
  test::write_file(d / "part1.nc", half_circle("N10 G17 G90 G70 SOFT\n", 2.0, 4));
  const auto mpf = test::run_arcpress("'" + (d / "part1.mpf").string() + "' -o '" + (d / "o1").string() +
                                      "' --stats --tolerance 0.05");
  CHECK(mpf.exit_code == 0);
  CHECK(mpf.err.find("by the file's extension (.mpf)") != std::string::npos);
  CHECK(mpf.err.find("E-LEX-KEYWORD") == std::string::npos);
  const auto nc = test::run_arcpress("'" + (d / "part1.nc").string() + "' -o '" + (d / "o2").string() +
                                     "' --stats --tolerance 0.05");
  CHECK(nc.err.find("dialect        rs274") != std::string::npos);
}

TEST_CASE("the Sinumerik sample is read as its extension names, its contour fitted and its calls kept", "[dialect][cli]") {
  const std::string sample = ARCPRESS_SOURCE_DIR "/samples/pocket.mpf";
  const test::TempDir d("sinumerik-sample");
  const std::string out = (d / "pocket.mpf").string();
  const auto c = test::run_arcpress("'" + sample + "' -o '" + out + "' --stats --tolerance 0.01");
  REQUIRE(c.exit_code == 0);
  CHECK(c.err.find("by the file's extension (.mpf)") != std::string::npos);
  CHECK(c.err.find("warning") == std::string::npos);
  const std::string written = test::read_file(out);
  // The rounded rectangle's four corners as arcs, its sides as lines, tangent throughout.
  CHECK(c.err.find("4 G2/G3") != std::string::npos);
  CHECK(c.err.find("max kink 0.000 deg") != std::string::npos);
  // The modal cycle call's holes each stay a block of their own, as does the program's own arc.
  for (const char* kept : {"\nN1170 MCALL CYCLE81(5,0,2,-6)\nN1180 X-15\nN1190 X-5\nN1200 X5\nN1210 X15\nN1220 MCALL\n",
                           "\nN1110 G3 X-14 Y-16 CR=4\n"})
    CHECK(written.find(kept) != std::string::npos);
  CHECK(test::run_arcpress("diff '" + sample + "' '" + out + "' --tolerance 0.01").exit_code == 0);
}
