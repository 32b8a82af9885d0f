// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Many programs compressed at once: `arcpress *.gcode --in-place -j N`, or
// `arcpress DIR -o OUTDIR` (recursive, the same relative names).
#include <string>
#include <vector>

#include "compress_file.hpp"

namespace arcpress::cli {

struct BatchArgs {
  std::vector<std::string> inputs;  ///< files and folders
  std::string glob;                 ///< file names a folder's files must match; empty: G-code extensions
  unsigned jobs = 0;                ///< programs at once; 0: one per hardware thread
  bool json = false;                ///< the summary as JSON
};

/// Whether `inputs` make a batch: more than one, or a folder.
bool is_batch(const std::vector<std::string>& inputs);

/// Compresses every program `b` names with the options of `a` (each into a.output, a folder,
/// under its name relative to the folder it was found in, or over itself with a.in_place),
/// b.jobs at once, each on one thread; one progress line for all; then the summary table
/// (or JSON) on standard output. Returns 0 when every program was written, else the
/// highest exit code among those that were not (each named, its destination untouched).
int run_batch(const CompressArgs& a, const BatchArgs& b);

}  // namespace arcpress::cli
