#pragma once
// Whole-file input and all-or-nothing output for the command line.
#include <string>

namespace arcpress::cli {

/// Reads a file, or standard input for "-". Throws arcpress::Error (exit 3) on failure.
std::string read_input(const std::string& path);

/// Writes `data` to `path` through a temporary file in the same folder that is renamed into
/// place only once everything is written, so a failure never leaves a partial or clobbered
/// file. "-" writes to standard output. Throws arcpress::Error (exit 3) on failure.
void write_output(const std::string& path, const std::string& data);

}  // namespace arcpress::cli
