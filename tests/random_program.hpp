// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Programs and options made from arbitrary bytes, and the promises every compression of
// them must keep: shared by the property test (bytes from a seeded generator) and the
// fuzz target (bytes from libFuzzer), so that whatever the fuzzer finds, the test can
// replay.
#include <cstdint>
#include <span>
#include <string>

#include "arcpress/api/arcpress.hpp"

namespace arcpress::test {

struct RandomCase {
  CompressOptions opt;
  std::string text;  ///< the program
};

/// The first three bytes choose the options (tolerance, method, helical arcs, smallest
/// radius, spikes), the program's form (plane, step scale, printed decimals, smooth turns
/// or free steps, flat or wandering normal axis, extrusion) and the controller (a shipped dialect,
/// R-form arcs); every further three bytes make one G1 move, and some of them a comment or
/// a feed change before it.
RandomCase random_case(std::span<const uint8_t> bytes);

/// The first promise `r` (compressed with verification) breaks, or empty when it keeps
/// them all: it reads, its output reads back move by move onto the input path, stays
/// within the band and keeps every non-motion block (as `arcpress diff` judges) without
/// writing any run back as its input for the check's sake, and every smooth joint that
/// turns by more than the G1 angle is one the fit reported as forced.
std::string broken_promise(const CompressResult& r);

/// The first promise that `text`, taken as a program whatever its bytes, breaks, or empty:
/// passed through it comes back byte for byte; compressed (with verification) it is either
/// refused with diagnostics or written inside the band; and `arcpress diff` never finds it
/// different from itself (the same, or incomplete where moves cannot be placed).
std::string text_promise(const std::string& text);
/// The same, the program read as `dialect`'s controller reads it (text_promise() reads it as
/// RS274 and as the Sinumerik language, whose keywords are words of a block).
std::string text_promise(const std::string& text, const Dialect& dialect);

}  // namespace arcpress::test
