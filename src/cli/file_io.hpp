// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Input read in chunks and all-or-nothing output for the command line. One file per system
// implements it (src/cli/platform/posix.cpp, windows.cpp); what differs is said there.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace arcpress::cli {

/// An input read in chunks: a file, or standard input for "-". Throws arcpress::Error
/// (exit 3) on failure, naming the file (a folder, a file that cannot be opened or read).
class InputFile {
 public:
  explicit InputFile(const std::string& path);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  /// Appends up to `max` bytes to `into`; returns how many, 0 at the end.
  size_t read(std::string& into, size_t max);
  /// The bytes left to read where the input is a regular file.
  std::optional<size_t> size() const { return size_; }
  /// Up to `n` bytes of a regular file from `offset` (counted from where reading began; empty
  /// for anything else), leaving the reading where it is.
  std::string read_at(size_t offset, size_t n) const;
  /// The last `n` bytes of a regular file (empty for anything else), as read_at().
  std::string tail(size_t n) const {
    return size_ ? read_at(*size_ - std::min(n, *size_), std::min(n, *size_)) : std::string();
  }
  /// Where the input is no regular file (a pipe), reads it to its end into an unnamed
  /// temporary file (in TMPDIR, or the system's folder for them; gone when the process ends)
  /// and reads on from there, as from a regular file: size(), read_at() and tail() answer.
  /// Nothing where it is one. Throws arcpress::Error (exit 3), naming the folder, where the
  /// temporary file cannot be made or written.
  void spool();

 private:
  /// Reads the rest of the input, handing each piece read to `put`; returns how many bytes.
  size_t copy_rest(const std::function<void(std::string_view)>& put);

  std::string name_;
  std::intptr_t handle_ = -1;  // the system's descriptor or handle
  bool owned_ = false;
  std::optional<size_t> size_;
  long long start_ = 0;
  size_t taken_ = 0;  // bytes read so far
  /// How many of `max` bytes a read asks for: of a regular file, no more than are left (and
  /// at least kSmallestRead, should it grow), so that a small file does not have a whole
  /// chunk's room cleared for it.
  size_t asked(size_t max) const {
    constexpr size_t kSmallestRead = size_t(1) << 16;
    if (!size_) return max;
    return std::min(max, std::max(*size_ > taken_ ? *size_ - taken_ : 0, kSmallestRead));
  }
};

/// Reads a file, or standard input for "-". Throws arcpress::Error (exit 3) on failure,
/// naming the file (a folder, a file that cannot be opened or read).
std::string read_input(const std::string& path);

/// An output written as it is made. A regular file, or a path that does not exist yet, is
/// written through a temporary file in the same folder that commit() renames into place
/// once everything is written and synced, so a failure never leaves a partial or clobbered
/// file; an existing file keeps its mode, owner and group (a warning where the process may
/// not set them), and a symbolic link keeps pointing where it did, at the rewritten target.
/// Any other destination (a character device such as /dev/null, a FIFO, a socket,
/// /dev/stdout, /dev/fd/N) is opened and written directly, never replaced; "-" is standard
/// output. Every write, sync, close and rename is checked: a failure throws arcpress::Error
/// (exit 3) naming the destination. Destroyed without commit(), it discards what it wrote.
class OutputFile {
 public:
  explicit OutputFile(const std::string& path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  void write(std::string_view data);
  /// Puts the output in place (a temporary file renamed over the destination).
  void commit();
  /// Takes back what was written where it can: the temporary file is removed, and a regular
  /// file behind standard output or /dev/fd/N (a shell's `> out.nc`) is cut back to where
  /// it began. Returns the bytes that stay written (to a pipe or terminal), 0 if none.
  size_t discard();
  size_t written() const { return written_; }

 private:
  friend struct OutputFileSystem;  // the system's half, in the platform file
  [[noreturn]] void fail(const std::string& what, int err);

  std::string path_, temporary_, target_;
  std::intptr_t handle_ = -1;  // the system's descriptor or handle
  int slot_ = -1;           // the temporary file's place in the interrupt handler's table
  bool owned_ = false;      // opened here (closed by commit)
  bool is_stdout_ = false;
  bool done_ = false;
  long long start_ = -1;    // a shell-opened regular file's offset at the start
  size_t written_ = 0;
};

/// Writes `data` to `path` at once, as OutputFile does. A regular file, or a path that does not exist yet, is written
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

/// Removes the temporary file of a write in progress when the program is interrupted (SIGINT,
/// SIGTERM or SIGHUP; on Windows Ctrl-C, Ctrl-Break or the console closing), then ends as
/// it would have (on POSIX dying of the signal, exit status 128 + signal); and on POSIX
/// ignores SIGPIPE, so that a reader closing a pipe is an I/O error ("standard output closed
/// after N bytes", exit 3). Call once at start.
void remove_temporary_files_on_signals();

}  // namespace arcpress::cli
