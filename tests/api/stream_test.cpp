// SPDX-License-Identifier: GPL-3.0-or-later
// The streaming engine (Compressor): the text does not depend on how the bytes arrive or on
// the threads, output comes before the input ends, and pieces cut inside a path still keep
// every promise.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "arcpress/api/compressor.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"
#include "random_program.hpp"
#include "support.hpp"

using namespace arcpress;

namespace {

struct Streamed {
  std::string output;
  CompressResult result;
  size_t forced_cuts = 0;
  size_t taken_before_finish = 0;  ///< output bytes take() gave before finish()
};

/// Pushes `text` in pieces of the sizes `next_size()` gives, taking output after each push.
template <class NextSize>
/// With `jumps_ahead`, the program's jumps are read from its text first, as the command
/// reads a file's (a jump back is then never too late).
Streamed stream(const std::string& text, const CompressOptions& opt, NextSize next_size, bool jumps_ahead = false) {
  DiagnosticSink sink("stream");
  Compressor c("stream", opt, sink);
  if (jumps_ahead) c.read_jumps(text, 1), c.read_loops(text);
  Streamed s;
  for (size_t at = 0; at < text.size();) {
    const size_t n = std::min(next_size(), text.size() - at);
    c.push(std::string_view(text).substr(at, n));
    at += n;
    c.take(s.output);
  }
  s.taken_before_finish = s.output.size();
  c.finish();
  c.take(s.output);
  s.result = c.result();
  s.forced_cuts = c.forced_cuts();
  return s;
}

/// One line at a time, as a sender reading a serial stream would.
Streamed stream_lines(const std::string& text, const CompressOptions& opt) {
  size_t at = 0;
  return stream(text, opt, [&] {
    const size_t nl = text.find('\n', at);
    const size_t n = nl == std::string::npos ? text.size() - at : nl + 1 - at;
    at += n;
    return n;
  });
}

/// A smooth spiral of `moves` G1 moves (no corner, no rapid, nothing a piece ends at).
std::string spiral(size_t moves) {
  std::string s = "G21 G90\nG0 X0 Y0 Z1\nG1 Z0 F600\n";
  for (size_t k = 1; k <= moves; ++k) {
    const double t = 0.01 * double(k), r = 10 + 0.002 * double(k);
    s += fmt::format("G1 X{:.4f} Y{:.4f}\n", r * std::cos(t), r * std::sin(t));
  }
  return s + "G0 Z5\nM2\n";
}

}  // namespace

TEST_CASE("every corpus file streamed a line at a time, or in random chunks on two threads, gives the program's "
          "compressed text, as the command line writes it",
          "[stream][corpus]") {
  ARCPRESS_CORPUS_FILES_OR_SKIP(files)
  std::mt19937 rng(7);
  for (const auto& f : files) {
    const std::string text = test::read_file(f);
    CompressOptions opt;
    opt.threads = 1;
    DiagnosticSink sink(f.string());
    const CompressResult whole = compress(f.string(), text, opt, sink);
    INFO(f.filename().string());
    REQUIRE(whole.ok);
    REQUIRE(whole.within_band());
    // Every piece's check accepts every fit: a piece ends where the input's state and the
    // output's read back agree (an E counter summed over arcs differs in its last bits only).
    CHECK(whole.runs_kept_as_input == 0);
    const Streamed lines = stream_lines(text, opt);
    CHECK(lines.output == whole.output);
    CHECK(lines.result.within_band());
    opt.threads = 2;
    std::uniform_int_distribution<size_t> size(1, 100000);
    const Streamed chunks = stream(text, opt, [&] { return size(rng); });
    CHECK(chunks.output == whole.output);
    CHECK(chunks.result.stats.arcs_out == whole.stats.arcs_out);
    CHECK(chunks.result.check.max_deviation_mm == whole.check.max_deviation_mm);
    // The command line runs the same engine on the same options.
    const test::Command cli = test::run_arcpress("'" + f.string() + "' --dialect rs274");
    CHECK(cli.exit_code == 0);
    CHECK(cli.out == whole.output);
  }
}

TEST_CASE("output comes out before the input ends, and all of a big program is never held", "[stream][corpus]") {
  ARCPRESS_CORPUS_FILES_OR_SKIP(files)
  const auto bunny = std::find_if(files.begin(), files.end(),
                                  [](const auto& p) { return p.filename().string().find("bunny") != std::string::npos; });
  REQUIRE(bunny != files.end());
  const std::string text = test::read_file(*bunny);
  CompressOptions opt;
  opt.threads = 2;
  const Streamed s = stream(text, opt, [] { return size_t(1) << 16; });
  // All but the last pieces in flight were written before the end: the most the engine
  // holds is a few pieces per thread.
  CHECK(s.taken_before_finish > 0);
  CHECK(s.output.size() - s.taken_before_finish <= 2 * kPiecesInFlight * kMaxPieceBytes);
  CHECK(s.result.within_band());
  CHECK(s.forced_cuts == 0);  // a printer program has a retraction or a travel often enough
}

TEST_CASE("the first pieces are small and each is twice the one before, so that a short program is shared among "
          "the threads",
          "[stream]") {
  CHECK(piece_bytes(0) == kFirstPieceBytes);
  for (size_t i = 1; i < 12; ++i) CHECK(piece_bytes(i) == std::min(2 * piece_bytes(i - 1), kPieceBytes));
  CHECK(piece_bytes(1000) == kPieceBytes);
  // Short passes, each after a travel (a move no chain crosses): a piece ends at the first
  // travel past its size. 150 KB, as a slicer writes a small part: four pieces of 16, 32,
  // 64 and the rest, where pieces of kPieceBytes alone would make two.
  std::string text = "G21 G90 M83\nG0 X0 Y0 Z0.2\n";
  for (int pass = 0; text.size() < 150000; ++pass) {
    const double y = 0.4 * pass;
    text += fmt::format("G0 X0 Y{:.3f}\n", y);
    for (int k = 1; k <= 20; ++k)
      text += fmt::format("G1 X{:.3f} Y{:.3f} E0.02\n", 2.0 * k, y + 0.2 * std::sin(0.3 * k));
  }
  CompressOptions opt;
  opt.threads = 2;
  DiagnosticSink sink("pieces");
  Compressor c("pieces", opt, sink);
  c.push(text);
  c.finish();
  CHECK(c.pieces() == 4);
  std::string out;
  c.take(out);
  CHECK(c.result().ok);
  CHECK(c.result().within_band());
  // The same text on one thread, pushed a line at a time.
  opt.threads = 1;
  CHECK(stream_lines(text, opt).output == out);
}

TEST_CASE("a path that goes on for longer than a piece may hold is cut at a vertex and still kept in the band",
          "[stream]") {
  const std::string text = spiral(60000);  // about 1.3 MB of one smooth path, five pieces' worth
  REQUIRE(text.size() > kMaxPieceBytes);
  CompressOptions opt;
  opt.threads = 2;
  const Streamed s = stream(text, opt, [] { return size_t(4096); });
  CHECK(s.forced_cuts >= text.size() / kMaxPieceBytes - 1);  // a cut every kMaxPieceBytes
  CHECK(s.forced_cuts <= text.size() / kMaxPieceBytes);
  CHECK(s.result.ok);
  CHECK(s.result.verified);
  CHECK(s.result.within_band());
  CHECK(s.result.check.same(opt.fit.tolerance_mm));
  CHECK(s.result.stats.arcs_out > 0);
  // The check read the whole output back as one program too.
  DiagnosticSink sink("whole");
  CompressResult whole;
  whole.output = s.output;
  const Program in = lex("in", text, sink);
  const Interpretation ii = interpret(in, sink);
  verify_output(in, ii, opt, whole);
  CHECK(whole.within_band());
  // The joints across the cuts are measured as the whole program's check measures them.
  CHECK(s.result.comparison.smooth_joints == whole.comparison.smooth_joints);
  CHECK(s.result.comparison.smooth_joints_over_g1 == whole.comparison.smooth_joints_over_g1);
  CHECK(s.result.comparison.max_smooth_kink_deg == Approx(whole.comparison.max_smooth_kink_deg));
  // The same text for one thread and for any chunking.
  opt.threads = 1;
  CHECK(stream_lines(text, opt).output == s.output);
}

TEST_CASE("a forced cut comes before a move, so a code arcpress does not model right after the cut still keeps the "
          "move before it as written",
          "[stream]") {
  // The first piece of one long path is cut at the first line past kMaxPieceBytes. A G25
  // (no RS274 code: not modelled) right after that line may go on from it (Heidenhain's
  // rounding does), so that move must stay as written; cut after it, the move would already
  // be fitted in the piece before.
  std::string text = spiral(60000);
  const size_t end = text.find('\n', kMaxPieceBytes - 1) + 1;  // just after the line that crosses the cap
  const size_t begin = text.rfind('\n', end - 2) + 1;
  const std::string line = text.substr(begin, end - begin);
  REQUIRE(line.rfind("G1 X", 0) == 0);
  text.insert(end, "G25 R5\n");
  CompressOptions opt;
  for (unsigned threads : {1u, 2u}) {
    opt.threads = threads;
    const Streamed s = stream(text, opt, [] { return size_t(4096); });
    INFO(line << threads << " threads");
    CHECK(s.forced_cuts >= 1);
    CHECK(s.result.within_band());
    CHECK(s.output.find("\n" + line + "G25 R5\n") != std::string::npos);
    CHECK(s.result.stats.arcs_out > 0);
  }
}

TEST_CASE("in strict mode, an error stops the stream: nothing after it is given out and the result is not ok",
          "[stream]") {
  std::string text = spiral(20000);
  text += "G1 X1.2.3 Y2\n" + spiral(100);
  CompressOptions opt;
  opt.strict = true;
  opt.threads = 2;
  DiagnosticSink sink("strict");
  Compressor c("strict", opt, sink);
  c.push(text);
  c.finish();
  std::string out;
  c.take(out);
  CHECK_FALSE(c.result().ok);
  CHECK(sink.error_count() > 0);
}

TEST_CASE("an empty program and one without a last end of line stream as they are", "[stream]") {
  CompressOptions opt;
  CHECK(stream("", opt, [] { return size_t(1); }).output.empty());
  const Streamed s = stream("G0 X1 Y0\nG1 X2 F100\nG1 X3 Y1\r\nG1 X4 Y3", opt, [] { return size_t(3); });
  CHECK(s.output == "G0 X1 Y0\nG1 X2 F100\nG1 X3 Y1\r\nG1 X4 Y3");  // a corner at each vertex: nothing to fit
  CHECK(s.result.ok);
}

TEST_CASE("a compressor takes no bytes after finish(), and one dropped half way stops at once", "[stream]") {
  CompressOptions opt;
  opt.threads = 2;
  DiagnosticSink sink("late");
  {
    Compressor c("late", opt, sink);
    c.push("G0 X0 Y0\nG1 X1 F100\n");
    c.finish();
    c.finish();
    CHECK_THROWS_AS(c.push("G1 X2\n"), std::logic_error);
  }
  // Dropped with pieces in flight: the destructor returns without working through them.
  const std::string text = spiral(40000);
  Compressor dropped("dropped", opt, sink);
  dropped.push(text);
}

TEST_CASE("random programs long enough to be cut into pieces keep every promise, checked piece by piece and whole",
          "[stream][property]") {
  for (uint32_t seed = 1; seed <= 6; ++seed) {
    std::mt19937 rng(seed);
    std::vector<uint8_t> bytes(3 + 3 * 30000);
    for (auto& b : bytes) b = uint8_t(rng());
    test::RandomCase c = test::random_case(bytes);
    INFO("seed " << seed << ", " << c.text.size() << " bytes");
    REQUIRE(c.text.size() > 2 * kPieceBytes);
    c.opt.threads = 1;
    DiagnosticSink sink("random");
    const CompressResult whole = compress("random", c.text, c.opt, sink);
    CHECK(test::broken_promise(whole).empty());
    INFO(test::broken_promise(whole));
    // Any chunks, any threads: the same text (with the jumps read ahead, as the command
    // reads a file's: some of these programs jump back, to a block chunks before).
    c.opt.threads = 2;
    std::uniform_int_distribution<size_t> size(1, 50000);
    const Streamed chunks = stream(c.text, c.opt, [&] { return size(rng); }, true);
    CHECK(chunks.output == whole.output);
    // The whole output, checked as one program, is inside the band, no farther from the
    // input than the pieces' checks measured it (to the whole-path measure's precision): on
    // the programmed path, or where the firmware moves on chords on those, which may lie
    // farther than the programmed path's move-by-move measure.
    if (!whole.ok || !whole.verified) continue;
    DiagnosticSink check_sink("random");
    CompressResult again;
    again.output = whole.output;
    const Program in = lex("random", c.text, check_sink);
    const Interpretation ii = interpret(in, check_sink, c.opt.dialect);
    verify_output(in, ii, c.opt, again);  // (no runs given: every joint read in the output's plane)
    CHECK(again.within_band());
    CHECK(again.check.max_deviation_mm <= whole.check.max_deviation_mm + again.check.arc_chord_mm);
  }
}
