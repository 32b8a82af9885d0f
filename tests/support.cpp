// SPDX-License-Identifier: GPL-3.0-or-later
#include "support.hpp"

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <random>

#include "arcpress/dialect/dialect_loader.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"

namespace fs = std::filesystem;

namespace arcpress::test {

Dialect shipped_dialect(const std::string& name) { return find_dialect(name, {ARCPRESS_SOURCE_DIR "/dialects"}); }

CompressResult compress_as(const std::string& dialect, const std::string& text, double tolerance_mm) {
  DiagnosticSink sink;
  CompressOptions opt;
  opt.dialect = shipped_dialect(dialect);
  opt.fit.tolerance_mm = tolerance_mm;
  return compress("part.nc", text, opt, sink);
}

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

ProgramDiff diff_texts(const std::string& a, const std::string& b, const DiffOptions& opt, const Dialect& dialect) {
  DiagnosticSink sa("a.nc"), sb("b.nc");
  const Program pa = lex("a.nc", a, sa, lex_rules(dialect)), pb = lex("b.nc", b, sb, lex_rules(dialect));
  const Interpretation ia = interpret(pa, sa, dialect), ib = interpret(pb, sb, dialect);
  return diff_programs(pa, ia, pb, ib, opt);
}

std::vector<fs::path> corpus_files() {
  std::vector<fs::path> files;
  fs::path dir(ARCPRESS_CORPUS_DIR);
  if (!fs::is_directory(dir)) return files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    auto ext = e.path().extension().string();
    if (ext == ".nc" || ext == ".ngc" || ext == ".gcode") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string read_file(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

void write_file(const fs::path& p, const std::string& data) {
  std::ofstream f(p, std::ios::binary);
  f << data;
}

TempDir::TempDir(const std::string& tag)
    : fs::path(fs::temp_directory_path() / ("arcpress-test-" + tag + "-" + std::to_string(std::random_device()()))) {
  fs::remove_all(*this);
  fs::create_directories(*this);
}

TempDir::TempDir(TempDir&& other) noexcept : fs::path(std::move(other)) { other.clear(); }

TempDir::~TempDir() {
  std::error_code ignored;  // a folder the test removed itself, or one that is busy: nothing to do
  if (!empty()) fs::remove_all(*this, ignored);
}

namespace {

/// Runs `command` with the shell, standard input from `stdin_path`, standard output and error
/// into files of `d`, and reads them back.
Command run_redirected(const std::string& command, const fs::path& stdin_path, const TempDir& d) {
  const std::string cmd = command + " < '" + stdin_path.string() + "' > '" + (d / "stdout").string() + "' 2> '" +
                          (d / "stderr").string() + "'";
  int status = std::system(cmd.c_str());
  Command c;
  c.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  c.out = read_file(d / "stdout");
  c.err = read_file(d / "stderr");
  return c;
}

}  // namespace

Command run_arcpress(const std::string& args, const std::string& stdin_text) {
  TempDir d("cmd");
  write_file(d / "stdin", stdin_text);
  return run_redirected(std::string("'") + ARCPRESS_EXE + "' " + args, d / "stdin", d);
}

Command run_shell(const std::string& script) {
  TempDir d("sh");
  write_file(d / "script.sh", script);
  return run_redirected(std::string("ARCPRESS='") + ARCPRESS_EXE + "' bash '" + (d / "script.sh").string() + "'",
                        "/dev/null", d);
}

}  // namespace arcpress::test
