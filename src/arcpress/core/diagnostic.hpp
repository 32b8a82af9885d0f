// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Diagnostics: every input problem is collected here with its place, a stable code and
// the actual text or numbers. Nothing in the pipeline throws for bad input.
#include <cstdint>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace arcpress {

/// A place in an input file: 1-based line and column (column counts bytes).
struct SourceLoc {
  uint32_t line = 0;
  uint32_t col = 0;
};

enum class Severity : uint8_t { Warning, Error };

struct Diagnostic {
  Severity severity = Severity::Warning;
  SourceLoc at;
  std::string code;     ///< stable identifier, e.g. "E-LEX-NUMBER"
  std::string message;  ///< says what was found and what was expected
};

/// Collects diagnostics for one input file. Warnings of one code are kept once
/// (the first place) plus a count, so a 100 000-line file cannot flood the terminal.
class DiagnosticSink {
 public:
  explicit DiagnosticSink(std::string file = "<stdin>") : file_(std::move(file)) {}

  /// In strict mode every unreadable-input finding (codes "E-...") is an error, not a warning.
  void set_strict(bool strict) { strict_ = strict; }
  bool strict() const { return strict_; }
  /// An input problem: an error when strict, otherwise a warning reported once per code.
  void problem(SourceLoc at, std::string_view code, std::string message) {
    strict_ ? error(at, code, std::move(message)) : warning(at, code, std::move(message));
  }

  void error(SourceLoc at, std::string_view code, std::string message);
  void warning(SourceLoc at, std::string_view code, std::string message);

  const std::vector<Diagnostic>& all() const { return list_; }
  size_t error_count() const { return errors_; }
  /// Every diagnostic reported so far, suppressed repeats included.
  size_t reported() const { return reported_; }
  /// Number of warnings of `code`, including the suppressed repeats.
  size_t warning_count(std::string_view code) const;
  const std::string& file() const { return file_; }

  /// "file:line:col: error: CODE: message", one line per kept diagnostic.
  std::string format(const Diagnostic& d) const;
  /// Every kept diagnostic, plus "N more" lines for suppressed warnings.
  std::string format_all() const;

 private:
  std::string file_;
  std::vector<Diagnostic> list_;
  std::vector<std::pair<std::string, size_t>> warn_counts_;
  size_t errors_ = 0;
  size_t reported_ = 0;
  bool strict_ = false;
};

}  // namespace arcpress
