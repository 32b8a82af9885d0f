// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The few exceptions arcpress throws: I/O failures and usage errors. They are caught in
// exactly one place per entry point (the CLI's main, the C API) and mapped to exit codes.
#include <stdexcept>
#include <string>

namespace arcpress {

/// Process exit codes, documented in --help and README.
enum ExitCode : int {
  kExitOk = 0,
  kExitVerifyFailed = 1,  ///< output left the tolerance band, or `diff` found a difference
  kExitInput = 2,         ///< usage error or unreadable input program
  kExitIo = 3,            ///< a file could not be read or written
};

class Error : public std::runtime_error {
 public:
  Error(int exit_code, const std::string& what) : std::runtime_error(what), code_(exit_code) {}
  int exit_code() const { return code_; }

 private:
  int code_;
};

}  // namespace arcpress
