#pragma once
// Whole-file input and all-or-nothing output for the command line.
#include <string>
#include <string_view>

namespace arcpress::cli {

/// Reads a file, or standard input for "-". Throws arcpress::Error (exit 3) on failure,
/// naming the file (a folder, a file that cannot be opened or read).
std::string read_input(const std::string& path);

/// Writes `data` to `path`. A regular file, or a path that does not exist yet, is written
/// through a temporary file in the same folder that is renamed into place only once
/// everything is written and synced, so a failure never leaves a partial or clobbered file;
/// an existing file keeps its mode, owner and group (a warning where the process may not set
/// them), and a symbolic link keeps pointing where it did, at the rewritten target. Any
/// other destination (a character device such as /dev/null, a FIFO, a socket, /dev/stdout,
/// /dev/fd/N) is opened and written directly, never replaced. "-" is standard output. Every
/// write, flush and close is checked: a failure throws arcpress::Error (exit 3) naming the
/// destination, and nothing partial is left beside it.
void write_output(const std::string& path, std::string_view data);

/// Writes `data` to standard output, checking every write; throws arcpress::Error (exit 3)
/// when the output cannot take it (a full disk, a closed pipe), after which nothing more is
/// written there.
void write_stdout(std::string_view data);

/// Removes the temporary file of a write in progress when SIGINT, SIGTERM or SIGHUP arrives,
/// then dies of the signal as the program would have (exit status 128 + signal). Call once
/// at start.
void remove_temporary_files_on_signals();

}  // namespace arcpress::cli
