// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Helpers shared by the tests: corpus discovery and running the arcpress executable.
#include <filesystem>
#include <string>
#include <vector>

#include "arcpress/api/arcpress.hpp"
#include "arcpress/dialect/dialect.hpp"
#include "arcpress/verify/program_diff.hpp"

namespace arcpress::test {

/// All files of the development corpus (sorted), or empty when the folder is absent.
std::vector<std::filesystem::path> corpus_files();
std::string read_file(const std::filesystem::path& p);
/// Programs `a` and `b` read with `dialect` and compared as `arcpress diff` compares them.
ProgramDiff diff_texts(const std::string& a, const std::string& b, const DiffOptions& opt,
                       const Dialect& dialect = Dialect{});
void write_file(const std::filesystem::path& p, const std::string& data);

/// The dialect `name` as shipped (the source tree's dialects/).
Dialect shipped_dialect(const std::string& name);
/// `text` compressed for the shipped dialect `dialect` at ±`tolerance_mm`.
CompressResult compress_as(const std::string& dialect, const std::string& text, double tolerance_mm = 0.01);
/// How many times `what` occurs in `text`.
size_t count_of(const std::string& text, const std::string& what);

struct Command {
  int exit_code = -1;
  std::string out;  ///< standard output
  std::string err;  ///< standard error
};
/// Runs the arcpress executable with `args` (shell words), feeding `stdin_text`.
Command run_arcpress(const std::string& args, const std::string& stdin_text = "");
/// Runs `script` with bash, the arcpress executable's path in $ARCPRESS; its standard
/// output and error are captured unless the script redirects them itself.
Command run_shell(const std::string& script);

/// A fresh empty folder under the system temp dir, removed with all it holds when the
/// test is done with it (when this goes out of scope).
class TempDir : public std::filesystem::path {
 public:
  explicit TempDir(const std::string& tag);
  TempDir(TempDir&& other) noexcept;
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  TempDir& operator=(TempDir&&) = delete;
  ~TempDir();
};
inline TempDir temp_dir(const std::string& tag) { return TempDir(tag); }

}  // namespace arcpress::test

/// Declares `files`, the corpus files, and leaves the test case with a warning when the
/// corpus folder is absent.
#define ARCPRESS_CORPUS_FILES_OR_SKIP(files)                                               \
  auto files = arcpress::test::corpus_files();                                             \
  if (files.empty()) {                                                                     \
    WARN("corpus folder " ARCPRESS_CORPUS_DIR " is absent: skipped");                      \
    return;                                                                                \
  }
