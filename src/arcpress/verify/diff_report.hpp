// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// `arcpress diff` output: a text report for people and a JSON document for programs
// (field names are stable and documented in README.md).
#include <string>

#include "arcpress/verify/program_diff.hpp"

namespace arcpress {

struct DiffNames {
  std::string a, b;
};

std::string diff_text(const ProgramDiff& d, const DiffNames& names, double tolerance_mm);
std::string diff_json(const ProgramDiff& d, const DiffNames& names, double tolerance_mm);

/// `s` as a JSON string, quoted, with quotes, backslashes and control characters escaped.
std::string json_string(const std::string& s);

}  // namespace arcpress
