// SPDX-License-Identifier: GPL-3.0-or-later
// The C library (arcpress.h): statuses and messages instead of exceptions, no state shared
// between handles, and the same text as the C++ engine.
#include <catch2/catch.hpp>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <string>
#include <thread>

#include "arcpress/arcpress.h"
#include "arcpress/arcpress.hpp"
#include "support.hpp"

namespace {

/// A quarter circle of radius 10 mm in 2 degree steps, printed with a decimal point always.
std::string quarter_circle() {
  std::string s = "G21 G90\nG0 X10. Y0. Z1.\nG1 Z0. F600\n";
  for (int k = 1; k <= 45; ++k) {
    const double t = 2.0 * k * 3.14159265358979 / 180;
    s += "G1 X" + std::to_string(10 * std::cos(t)) + " Y" + std::to_string(10 * std::sin(t)) + "\n";
  }
  return s + "G0 Z5.\nM2\n";
}
const std::string kProgram = quarter_circle();

/// The text and status of compressing `program` through the C library, pushed in pieces of `step`.
std::pair<std::string, arcpress_status> through_c(const std::string& program, size_t step, const char* dialect) {
  arcpress_options* o = arcpress_options_new();
  REQUIRE(o);
  REQUIRE(arcpress_options_set_dialect(o, dialect) == ARCPRESS_OK);
  arcpress_compressor* c = nullptr;
  REQUIRE(arcpress_compressor_new(o, "c", &c) == ARCPRESS_OK);
  std::string out;
  const char* text = nullptr;
  size_t n = 0;
  for (size_t at = 0; at < program.size(); at += step) {
    REQUIRE(arcpress_push(c, program.data() + at, std::min(step, program.size() - at)) == ARCPRESS_OK);
    REQUIRE(arcpress_take(c, &text, &n) == ARCPRESS_OK);
    out.append(text, n);
  }
  const arcpress_status s = arcpress_finish(c);
  REQUIRE(arcpress_take(c, &text, &n) == ARCPRESS_OK);
  out.append(text, n);
  arcpress_compressor_free(c);
  arcpress_options_free(o);
  return {out, s};
}

/// Compresses `program` whole with `o` (which it frees): the text and the diagnostics.
std::pair<std::string, std::string> compressed_whole(arcpress_options* o, const std::string& program) {
  arcpress_compressor* c = nullptr;
  REQUIRE(arcpress_compressor_new(o, "c", &c) == ARCPRESS_OK);
  REQUIRE(arcpress_push(c, program.data(), program.size()) == ARCPRESS_OK);
  REQUIRE(arcpress_finish(c) == ARCPRESS_OK);
  const char* text = nullptr;
  size_t n = 0;
  REQUIRE(arcpress_take(c, &text, &n) == ARCPRESS_OK);
  std::pair<std::string, std::string> out{std::string(text, n), arcpress_diagnostics(c)};
  arcpress_compressor_free(c);
  arcpress_options_free(o);
  return out;
}

}  // namespace

TEST_CASE("the C library writes what the C++ engine writes, on two threads at once", "[capi]") {
  arcpress::CompressOptions opt;
  opt.dialect = arcpress::dialect_named("fanuc");
  arcpress::DiagnosticSink sink;
  const std::string expected = arcpress::compress("c", kProgram, opt, sink).output;
  REQUIRE(expected.find("G3") != std::string::npos);
  std::pair<std::string, arcpress_status> a, b;
  std::thread t1([&] { a = through_c(kProgram, 7, "fanuc"); });
  std::thread t2([&] { b = through_c(kProgram, 1000, "fanuc"); });
  t1.join();
  t2.join();
  CHECK(a.second == ARCPRESS_OK);
  CHECK(b.second == ARCPRESS_OK);
  CHECK(a.first == expected);
  CHECK(b.first == expected);
}

TEST_CASE("the C library answers a bad call with a status and a message, never an exception", "[capi]") {
  arcpress_options* o = arcpress_options_new();
  CHECK(arcpress_options_set_tolerance(o, -1) == ARCPRESS_BAD_INPUT);
  CHECK(std::string(arcpress_options_last_error(o)).find("tolerance") != std::string::npos);
  CHECK(arcpress_options_set_dialect(o, "no-such-controller") == ARCPRESS_BAD_INPUT);
  CHECK(std::string(arcpress_options_last_error(o)).find("no-such-controller") != std::string::npos);
  CHECK(arcpress_options_set_dialect_file(o, "/nonexistent/dialect.toml") == ARCPRESS_IO_ERROR);
  CHECK(arcpress_options_set_method(o, "magic") == ARCPRESS_BAD_INPUT);
  CHECK(arcpress_compressor_new(o, "x", nullptr) == ARCPRESS_BAD_INPUT);
  // Strict mode: a line that cannot be read stops the compressor, with its place.
  REQUIRE(arcpress_options_set_dialect(o, "rs274") == ARCPRESS_OK);
  REQUIRE(arcpress_options_set_strict(o, 1) == ARCPRESS_OK);
  arcpress_compressor* c = nullptr;
  REQUIRE(arcpress_compressor_new(o, "bad.nc", &c) == ARCPRESS_OK);
  const std::string bad = "G0 X0\nG1 X1.2.3 F100\n";
  CHECK(arcpress_push(c, bad.data(), bad.size()) == ARCPRESS_BAD_INPUT);
  CHECK(arcpress_finish(c) == ARCPRESS_BAD_INPUT);
  CHECK(std::string(arcpress_diagnostics(c)).find("bad.nc:2:") != std::string::npos);
  CHECK(arcpress_push(c, "G0 X1\n", 6) == ARCPRESS_BAD_INPUT);  // finished: refused, not a crash
  arcpress_compressor_free(c);
  arcpress_options_free(o);
  CHECK(std::string(arcpress_version()) == arcpress::kVersion);
}

TEST_CASE("postproc/README.md shows the examples the package tests build, as they are", "[capi][docs]") {
  const std::string readme = arcpress::test::read_file(ARCPRESS_SOURCE_DIR "/postproc/README.md");
  for (const char* example : {"/postproc/examples/compress.cpp", "/postproc/examples/compress.c"}) {
    INFO(example);
    CHECK(readme.find(arcpress::test::read_file(std::string(ARCPRESS_SOURCE_DIR) + example)) != std::string::npos);
  }
}

TEST_CASE("the C library sets the band, the extrusion variance and the header as the command line does", "[capi]") {
  const std::string program = "; a slicer's first line\n" + kProgram;
  auto compressed = [&](const char* band, double variance, int header, const char* side = "both") {
    arcpress_options* o = arcpress_options_new();
    REQUIRE(o);
    REQUIRE(arcpress_options_set_dialect(o, "klipper") == ARCPRESS_OK);
    REQUIRE(arcpress_options_set_band(o, band) == ARCPRESS_OK);
    REQUIRE(arcpress_options_set_band_side(o, side) == ARCPRESS_OK);
    REQUIRE(arcpress_options_set_extrusion_variance(o, variance) == ARCPRESS_OK);
    REQUIRE(arcpress_options_set_header(o, header) == ARCPRESS_OK);
    return compressed_whole(o, program).first;
  };
  // The engine's text for the same options.
  auto engine = [&](arcpress::CompressOptions::Band band, bool header) {
    arcpress::CompressOptions opt;
    opt.dialect = arcpress::dialect_named("klipper");
    opt.band = band;
    opt.header = header;
    arcpress::DiagnosticSink sink;
    return arcpress::compress("c", program, opt, sink).output;
  };
  using B = arcpress::CompressOptions::Band;
  CHECK(compressed("program", 0.05, 1) == engine(B::Program, true));
  CHECK(compressed("executed", 0.05, 0) == engine(B::Executed, false));
  CHECK(compressed("dialect", 0.05, 1) == engine(B::Executed, true));
  CHECK(compressed("program", 0.05, 1).find("; arcpress ") != std::string::npos);
  CHECK(compressed("program", 0.05, 0).find("; arcpress ") == std::string::npos);
  // One side: the same text as the engine's; refused on the firmware's chords.
  {
    arcpress::CompressOptions opt;
    opt.dialect = arcpress::dialect_named("klipper");
    opt.band = B::Program;
    opt.fit.band_side = arcpress::BandSide::Left;
    arcpress::DiagnosticSink sink;
    const std::string left = compressed("program", 0.05, 1, "left");
    CHECK(left == arcpress::compress("c", program, opt, sink).output);
    CHECK(left.find("--band-side left") != std::string::npos);
    arcpress_options* s = arcpress_options_new();
    REQUIRE(arcpress_options_set_band_side(s, "left") == ARCPRESS_OK);
    REQUIRE(arcpress_options_set_dialect(s, "klipper") == ARCPRESS_OK);
    arcpress_compressor* c = nullptr;
    CHECK(arcpress_compressor_new(s, "c", &c) == ARCPRESS_BAD_INPUT);
    CHECK(std::string(arcpress_options_last_error(s)).find("--band program") != std::string::npos);
    CHECK(arcpress_options_set_band_side(s, "inside") == ARCPRESS_BAD_INPUT);
    arcpress_options_free(s);
  }
  arcpress_options* o = arcpress_options_new();
  CHECK(arcpress_options_set_band(o, "chords") == ARCPRESS_BAD_INPUT);
  CHECK(std::string(arcpress_options_last_error(o)).find("unknown band") != std::string::npos);
  CHECK(arcpress_options_set_extrusion_variance(o, 2) == ARCPRESS_BAD_INPUT);
  arcpress_options_free(o);
}

TEST_CASE("the C library reads a program in the units the controller starts in, set before or after the dialect",
          "[capi][units]") {
  // Quarter circle printed without G21: read in inches it is 25.4 times as large.
  const std::string program = kProgram.substr(kProgram.find('\n') + 1);
  auto compressed = [&](const char* units, bool units_first) {
    arcpress_options* o = arcpress_options_new();
    REQUIRE(o);
    if (units_first) REQUIRE(arcpress_options_set_units(o, units) == ARCPRESS_OK);
    REQUIRE(arcpress_options_set_dialect(o, "linuxcnc") == ARCPRESS_OK);
    if (!units_first) REQUIRE(arcpress_options_set_units(o, units) == ARCPRESS_OK);
    return compressed_whole(o, program);
  };
  auto engine = [&](arcpress::StartUnits units) {
    arcpress::CompressOptions opt;
    opt.dialect = arcpress::dialect_named("linuxcnc");
    opt.dialect.start_units = units;
    arcpress::DiagnosticSink sink;
    return arcpress::compress("c", program, opt, sink).output;
  };
  for (bool first : {true, false}) {
    CHECK(compressed("inch", first).first == engine(arcpress::StartUnits::Inch));
    CHECK(compressed("mm", first).first == engine(arcpress::StartUnits::Mm));
    CHECK(compressed("mm", first).second.find("W-MODEL-UNITS") == std::string::npos);
  }
  CHECK(engine(arcpress::StartUnits::Inch) != engine(arcpress::StartUnits::Mm));
  arcpress_options* o = arcpress_options_new();
  CHECK(arcpress_options_set_units(o, "cm") == ARCPRESS_BAD_INPUT);
  CHECK(std::string(arcpress_options_last_error(o)).find("unknown units 'cm'") != std::string::npos);
  arcpress_options_free(o);
}

TEST_CASE("a compressor owns what it reads: options changed or freed after it is made change nothing", "[capi]") {
  const auto expected = through_c(kProgram, 1000, "fanuc");
  REQUIRE(expected.second == ARCPRESS_OK);
  arcpress_options* o = arcpress_options_new();
  REQUIRE(arcpress_options_set_dialect(o, "fanuc") == ARCPRESS_OK);
  arcpress_compressor* c = nullptr;
  REQUIRE(arcpress_compressor_new(o, "c", &c) == ARCPRESS_OK);
  // A lathe dialect reads X as a diameter: read through the options, every X would halve.
  REQUIRE(arcpress_options_set_dialect(o, "haas-lathe") == ARCPRESS_OK);
  REQUIRE(arcpress_options_set_tolerance(o, 5) == ARCPRESS_OK);
  arcpress_options_free(o);
  REQUIRE(arcpress_push(c, kProgram.data(), kProgram.size()) == ARCPRESS_OK);
  CHECK(arcpress_finish(c) == ARCPRESS_OK);
  const char* text = nullptr;
  size_t n = 0;
  REQUIRE(arcpress_take(c, &text, &n) == ARCPRESS_OK);
  CHECK(std::string(text, n) == expected.first);
  arcpress_compressor_free(c);
  // The same in C++: a compressor made from options that end with the statement.
  arcpress::DiagnosticSink sink;
  arcpress::Compressor cpp("c", arcpress::CompressOptions{}, sink);
  cpp.push(kProgram);
  cpp.finish();
  CHECK(cpp.result().ok);
  CHECK(cpp.result().within_band());
}

TEST_CASE("after a call fails every later call fails: a push whose threads cannot start never ends in OK",
          "[capi]") {
  // A child process with 1 GiB of address space: 1024 threads' stacks do not fit in it.
  std::string program = "G21 G90\nG0 X0 Y0 Z0\nG1 F600\n";
  for (int k = 0; program.size() < (size_t(1) << 20); ++k)
    program += "G1 X" + std::to_string(0.1 * k) + " Y" + std::to_string(std::sin(0.01 * k)) + "\n";
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    const struct rlimit limit = {rlim_t(1) << 30, rlim_t(1) << 30};
    ::setrlimit(RLIMIT_AS, &limit);
    arcpress_options* o = arcpress_options_new();
    arcpress_options_set_threads(o, 1024);
    arcpress_compressor* c = nullptr;
    if (arcpress_compressor_new(o, "c", &c) != ARCPRESS_OK) ::_exit(10);
    arcpress_status first = ARCPRESS_OK;
    size_t at = 0;
    for (; at < program.size() && first == ARCPRESS_OK; at += 65536)
      first = arcpress_push(c, program.data() + at, std::min<size_t>(65536, program.size() - at));
    if (first == ARCPRESS_OK) ::_exit(11);  // the threads started after all: nothing shown
    if (at < program.size() && arcpress_push(c, program.data() + at, program.size() - at) == ARCPRESS_OK) ::_exit(12);
    const char* text = nullptr;
    size_t n = 0;
    if (arcpress_take(c, &text, &n) == ARCPRESS_OK) ::_exit(13);
    if (arcpress_finish(c) == ARCPRESS_OK) ::_exit(14);
    if (arcpress_finish(c) == ARCPRESS_OK) ::_exit(15);
    ::_exit(0);
  }
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
}

TEST_CASE("the C library refuses what the command refuses, with the status of its kind", "[capi]") {
  arcpress_options* o = arcpress_options_new();
  // More threads than any count the command takes.
  CHECK(arcpress_options_set_threads(o, 100000) == ARCPRESS_BAD_INPUT);
  CHECK(std::string(arcpress_options_last_error(o)).find("thread count") != std::string::npos);
  // A dialect path longer than the system takes: an I/O error, not an internal one.
  CHECK(arcpress_options_set_dialect_file(o, ("/tmp/" + std::string(5000, 'd') + ".toml").c_str()) ==
        ARCPRESS_IO_ERROR);
  // An empty file is no dialect.
  auto dir = arcpress::test::temp_dir("capi-dialect");
  arcpress::test::write_file(dir / "empty.toml", "");
  CHECK(arcpress_options_set_dialect_file(o, (dir / "empty.toml").c_str()) == ARCPRESS_BAD_INPUT);
  CHECK(std::string(arcpress_options_last_error(o)).find("name: missing") != std::string::npos);
  // The executed band on a dialect whose controller moves on the circles.
  REQUIRE(arcpress_options_set_dialect(o, "rs274") == ARCPRESS_OK);
  REQUIRE(arcpress_options_set_band(o, "executed") == ARCPRESS_OK);
  arcpress_compressor* c = nullptr;
  CHECK(arcpress_compressor_new(o, "c", &c) == ARCPRESS_BAD_INPUT);
  CHECK(c == nullptr);
  CHECK(std::string(arcpress_options_last_error(o)).find("names no arc segmentation") != std::string::npos);
  // Statistics before finish() claim no check.
  REQUIRE(arcpress_options_set_band(o, "dialect") == ARCPRESS_OK);
  REQUIRE(arcpress_compressor_new(o, "c", &c) == ARCPRESS_OK);
  REQUIRE(arcpress_push(c, kProgram.data(), kProgram.size()) == ARCPRESS_OK);
  arcpress_stats stats{};
  REQUIRE(arcpress_get_stats(c, &stats) == ARCPRESS_OK);
  CHECK(stats.verified == 0);
  REQUIRE(arcpress_finish(c) == ARCPRESS_OK);
  REQUIRE(arcpress_get_stats(c, &stats) == ARCPRESS_OK);
  CHECK(stats.verified == 1);
  arcpress_compressor_free(c);
  arcpress_options_free(o);
}

/// A compressor for Fanuc's dialect (freed by the caller).
static arcpress_compressor* fanuc_compressor() {
  arcpress_options* o = arcpress_options_new();
  REQUIRE(arcpress_options_set_dialect(o, "fanuc") == ARCPRESS_OK);
  arcpress_compressor* c = nullptr;
  REQUIRE(arcpress_compressor_new(o, "c", &c) == ARCPRESS_OK);
  arcpress_options_free(o);
  return c;
}

TEST_CASE("the C library reads a program's jumps ahead of its pushes, or fails a jump back it reads too late", "[capi][jumps]") {
  // quarter_circle() with its 20th move numbered N100, and a jump back to it after the path.
  std::string program = kProgram;
  size_t at = 0;
  for (int k = 0; k < 22; ++k) at = program.find('\n', at) + 1;
  program.insert(at, "N100 ");
  program.insert(program.find("G0 Z5."), "IF [#1 LT 3] GOTO 100\n");
  auto run = [&](bool ahead) {
    arcpress_compressor* c = fanuc_compressor();
    if (ahead) REQUIRE(arcpress_read_jumps(c, program.data(), program.size(), 1) == ARCPRESS_OK);
    arcpress_status status = ARCPRESS_OK;
    for (size_t from = 0; from < program.size() && status == ARCPRESS_OK;) {  // a line a push
      const size_t nl = program.find('\n', from) + 1;
      status = arcpress_push(c, program.data() + from, nl - from);
      from = nl;
    }
    if (status == ARCPRESS_OK) status = arcpress_finish(c);
    const char* text = nullptr;
    size_t n = 0;
    std::string out;
    if (status == ARCPRESS_OK && arcpress_take(c, &text, &n) == ARCPRESS_OK) out.assign(text, n);
    const std::string told = arcpress_diagnostics(c);
    arcpress_compressor_free(c);
    return std::tuple(status, out, told);
  };
  const auto [late, late_out, late_told] = run(false);
  CHECK(late == ARCPRESS_BAD_INPUT);
  CHECK(late_told.find("E-FLOW-JUMP-BACK") != std::string::npos);
  const auto [ahead, ahead_out, ahead_told] = run(true);
  CHECK(ahead == ARCPRESS_OK);
  CHECK(ahead_out.find("\nN100 G1 X") != std::string::npos);
}

TEST_CASE("the C library reads a program's loops ahead, or fails a loop back in other modes it reads too late", "[capi][jumps]") {
  // quarter_circle() with its first move numbered N100 and stating G90, then a G18 and a
  // jump back to it: the quarter would run again in G18.
  std::string program = kProgram;
  const size_t first = program.find("G1 ");
  program.insert(first, "N100 G90 ");
  program.insert(program.find("G0 Z5."), "G18\nIF [#1 LT 3] GOTO 100\n");
  auto run = [&](bool loops) {
    arcpress_compressor* c = fanuc_compressor();
    REQUIRE(arcpress_read_jumps(c, program.data(), program.size(), 1) == ARCPRESS_OK);
    if (loops) REQUIRE(arcpress_read_loops(c, program.data(), program.size()) == ARCPRESS_OK);
    arcpress_status status = arcpress_push(c, program.data(), program.size());
    if (status == ARCPRESS_OK) status = arcpress_finish(c);
    const std::string told = arcpress_diagnostics(c);
    arcpress_compressor_free(c);
    return std::pair(status, told);
  };
  const auto [late, late_told] = run(false);
  CHECK(late == ARCPRESS_BAD_INPUT);
  CHECK(late_told.find("E-FLOW-LOOP-MODES") != std::string::npos);
  const auto [ahead, ahead_told] = run(true);
  CHECK(ahead == ARCPRESS_OK);
  CHECK(ahead_told.find("W-FLOW-LOOP-MODES") != std::string::npos);
  CHECK(arcpress_read_loops(nullptr, program.data(), program.size()) == ARCPRESS_BAD_INPUT);
}
