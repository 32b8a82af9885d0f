// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// arcpress's C++ library: the one header an embedding program includes.
//
//   arcpress::CompressOptions  every option of the command line (api/arcpress.hpp)
//   arcpress::Compressor       push a program's bytes, take finished text, finish() (api/compressor.hpp)
//   arcpress::compress()       a whole program in memory, at once
//   arcpress::dialect_named()  a shipped (or the user's own) controller dialect by name
//   arcpress::CompressResult   counts, the measured deviation and the verdict, as data
//   arcpress::DiagnosticSink   every problem of the input with line, column and a stable code
//
// Contracts: nothing throws for bad G-code (it goes to the sink; under `strict` it makes
// the result not ok). Options out of range and unknown dialects throw arcpress::Error with
// a message and the command line's exit code. A Compressor is used from one thread at a
// time; two Compressors share nothing and may run on two threads at once. Output taken
// from a Compressor is final, but usable only when, after finish(), result().ok and
// result().within_band() hold.
#include <istream>
#include <ostream>
#include <string>

#include "arcpress/api/arcpress.hpp"
#include "arcpress/api/compressor.hpp"
#include "arcpress/core/error.hpp"
#include "arcpress/dialect/dialect_loader.hpp"

namespace arcpress {

/// The dialect called `name`, looked for in $ARCPRESS_DIALECT_PATH, then where the library
/// was installed (PREFIX/share/arcpress/dialects), then in the source tree it was built
/// from. Throws Error(kExitInput) listing the names it knows.
Dialect dialect_named(const std::string& name);

/// Compresses the program read from `in` to `out` as it comes, in bounded memory. Returns
/// the result; where it is not usable (!ok or !within_band()), what was written to `out` must
/// be thrown away. Throws Error(kExitIo) when `in` or `out` fails. A stream that can be read
/// again (a file, a string) is read through once first for the program's jumps
/// (Compressor::read_jumps()); from one that cannot, a jump back may come too late.
CompressResult compress_stream(std::istream& in, std::ostream& out, const std::string& name,
                               const CompressOptions& options, DiagnosticSink& sink);

}  // namespace arcpress
