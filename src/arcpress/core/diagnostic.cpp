// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/core/diagnostic.hpp"

#include <fmt/format.h>

namespace arcpress {

void DiagnosticSink::error(SourceLoc at, std::string_view code, std::string message) {
  ++errors_;
  ++reported_;
  list_.push_back({Severity::Error, at, std::string(code), std::move(message)});
}

void DiagnosticSink::warning(SourceLoc at, std::string_view code, std::string message) {
  ++reported_;
  for (auto& [c, n] : warn_counts_) {
    if (c == code) {
      ++n;
      return;
    }
  }
  warn_counts_.emplace_back(std::string(code), 1);
  list_.push_back({Severity::Warning, at, std::string(code), std::move(message)});
}

size_t DiagnosticSink::warning_count(std::string_view code) const {
  for (auto& [c, n] : warn_counts_)
    if (c == code) return n;
  return 0;
}

std::string DiagnosticSink::format(const Diagnostic& d) const {
  return fmt::format("{}:{}:{}: {}: {}: {}", file_, d.at.line, d.at.col,
                     d.severity == Severity::Error ? "error" : "warning", d.code, d.message);
}

std::string DiagnosticSink::format_all() const {
  std::string out;
  for (const auto& d : list_) {
    out += format(d);
    out += '\n';
    if (d.severity == Severity::Warning) {
      size_t n = warning_count(d.code);
      if (n > 1) out += fmt::format("{}: note: {} more {} warning(s) not shown\n", file_, n - 1, d.code);
    }
  }
  return out;
}

}  // namespace arcpress
