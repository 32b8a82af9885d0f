// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Input that is not a G-code program at all: an archive, an image, a binary G-code file,
// random bytes, prose. Compressing such a file would "succeed" with a copy and a page of
// warnings, which a slicer or a script takes for success; it is refused instead, before a
// byte is written. A real program with a few unreadable lines is not refused: those lines
// are warned about and passed through as they are.
#include <cstddef>
#include <optional>
#include <string>

#include "arcpress/core/diagnostic.hpp"
#include "arcpress/lex/block.hpp"

namespace arcpress {

/// Why the start of a program is not G-code, and where that shows.
struct ForeignContent {
  SourceLoc at;
  std::string why;  ///< e.g. "a ZIP archive's signature (a .3mf project is one) at its start"
};

/// How much of a program is judged: its first 128 KiB (a streamed program's first piece
/// holds at least as much), the blocks that begin in them.
inline constexpr size_t kForeignSampleBytes = size_t(1) << 17;
/// Control bytes (other than tab, line and page ends) outside comments that show a program
/// is binary: more than this share of its bytes outside comments...
inline constexpr double kForeignControlShare = 0.005;
/// ... and at least this many of them.
inline constexpr size_t kForeignControlBytes = 8;

/// Whether `program` (the whole of it, or, where `whole` is false, its first lines as read
/// so far) is something other than G-code, judged by its first kForeignSampleBytes. The
/// line is drawn at:
/// - a file signature at the start: ZIP (and so .3mf), gzip, 7-Zip, xz, bzip2, PNG, JPEG,
///   GIF, PDF, ELF, and PrusaSlicer's binary G-code (.bgcode);
/// - control bytes (not tab, CR, LF, VT, FF) outside '( )' and ';' comments, more than
///   kForeignControlShare of the bytes outside comments and at least kForeignControlBytes;
///   NUL or Ctrl-Z padding at the end of a file (an SD card's) does not count;
/// - more unreadable blocks (BlockKind::Opaque) than readable ones (code, flow control,
///   macro, host command, '%').
/// Comment-only and empty programs are G-code.
std::optional<ForeignContent> foreign_content(const Program& program, bool whole);

}  // namespace arcpress
