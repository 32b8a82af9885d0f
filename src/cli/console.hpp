// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What the command line asks of the system besides files: its arguments, its streams and its
// memory. One file per system implements it (src/cli/platform/), as it does file_io.hpp.
#include <string>
#include <vector>

namespace arcpress::cli {

/// Sets the process up before anything is read or written: the command line's arguments in
/// UTF-8 (on Windows read again from the wide command line, so that any file name survives),
/// standard input and output in binary mode (no CR added or dropped, no Ctrl-Z ending the
/// input), messages to a console in UTF-8, and the allocator's habits for a program that
/// frees and allocates about the same memory piece after piece.
std::vector<std::string> start_process(int argc, char** argv);

/// Whether standard input (0) or standard error (2) is a terminal or console.
bool is_terminal(int stream);

}  // namespace arcpress::cli
