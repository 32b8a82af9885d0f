// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// One program compressed from the command line: the dialect it is read in, its input read
// and its output written as they go, and what is said about it; and what the diff command
// shares with it.
#include <atomic>
#include <cstddef>
#include <initializer_list>
#include <string>
#include <string_view>

#include "arcpress/api/arcpress.hpp"

namespace arcpress::cli {

/// The compress command's arguments, as read off the command line.
struct CompressArgs {
  std::string input = "-";
  std::string output;
  std::string dialect = "rs274";
  bool dialect_given = false;  ///< --dialect on the command line
  std::string dialect_file;
  std::string arc_format;
  std::string method = "arcs";
  std::string band;  ///< "program", "executed"; empty: the dialect's choice
  std::string band_side = "both";  ///< "left", "right", "both"
  std::string units;  ///< "mm", "inch": the program's units until its G20 or G21; empty: the dialect's
  bool in_place = false;
  bool stats = false;
  bool quiet = false;
  bool progress = false;
  /// From a pipe, compress as the input comes rather than reading it to its end first
  /// (InputFile::spool()): then a jump back past what was read fails the run, and the
  /// subprograms after the program's end are not read (its calls leave the modes unknown).
  bool stream = false;
  CompressOptions opt;
};


/// What one program's compression came to: the batch's summary row, and the messages for
/// standard error (diagnostics, failures, --stats), kept to be printed when it is done.
struct FileReport {
  std::string input, output;
  size_t bytes_in = 0, bytes_out = 0;  ///< bytes out: 0 where nothing was written
  size_t blocks_in = 0, blocks_out = 0;
  double max_deviation_mm = -1;  ///< measured by the check; < 0: not measured
  int exit_code = 0;
  std::string log;
};

/// Compresses a.input into a.output (standard output where empty, the input with
/// a.in_place), and returns the exit code, its messages in report.log. Throws arcpress::Error
/// for what ends it early (a file that cannot be read or written, an unknown dialect). With
/// `read_counter` (a batch), it draws no progress line of its own and adds what it reads there.
int compress_file(const CompressArgs& a, FileReport& report, std::atomic<size_t>* read_counter = nullptr);

/// What `sinks` say, for standard error: of a file that is not G-code, only that.
std::string diagnostics_text(std::initializer_list<const DiagnosticSink*> sinks);

/// The dialect to read `program` with: the one the command line names (`--dialect-file`,
/// `--dialect` where `name_given`), or else the one the program names for itself (a
/// slicer's flavor line, at its start or in `tail`, its end), or else the one the extension of
/// `path`, the file it is read from, names (dialect_of_extension()), or else `name`. `why` says
/// which. A program with a slicer's flavor line starts in millimetres, as every printer firmware does.
Dialect dialect_for(const std::string& name, bool name_given, const std::string& file, std::string_view program,
                    std::string_view path, std::string_view tail = {}, std::string* why = nullptr);

/// Throws Error(kExitInput), naming `option`, unless `dialect` names the arc segmentation
/// its firmware moves along.
void require_executed_rule(const Dialect& dialect, const char* option);

/// The side a --band-side word names.
BandSide band_side_named(const std::string& word);
/// Sets the units `dialect` reads a program in until its first G20 or G21: "mm", "inch"
/// (--units), or leaves the dialect's own where `units` is empty.
void set_start_units(Dialect& dialect, const std::string& units);

/// The folder of the running program.
std::string exe_dir();

/// `p` with its links resolved, or empty where it does not exist.
std::string real_path(const std::string& p);

}  // namespace arcpress::cli
