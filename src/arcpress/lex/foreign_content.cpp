// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/lex/foreign_content.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string_view>

namespace arcpress {
namespace {

struct Signature {
  std::string_view bytes;
  const char* what;
};

constexpr Signature kSignatures[] = {
    {std::string_view("PK\x03\x04", 4), "a ZIP archive's signature (a .3mf project is one)"},
    {std::string_view("PK\x05\x06", 4), "an empty ZIP archive's signature"},
    {std::string_view("\x1f\x8b", 2), "a gzip archive's signature"},
    {std::string_view("7z\xbc\xaf\x27\x1c", 6), "a 7-Zip archive's signature"},
    {std::string_view("\xfd" "7zXZ\x00", 6), "an xz archive's signature"},
    {std::string_view("BZh", 3), "a bzip2 archive's signature"},
    {std::string_view("\x89PNG\r\n\x1a\n", 8), "a PNG image's signature"},
    {std::string_view("\xff\xd8\xff", 3), "a JPEG image's signature"},
    {std::string_view("GIF8", 4), "a GIF image's signature"},
    {std::string_view("%PDF-", 5), "a PDF document's signature"},
    {std::string_view("\x7f" "ELF", 4), "an executable's signature"},
    {std::string_view("GCDE", 4), "a binary G-code (.bgcode) signature; export the program as text G-code"},
};

bool is_control(unsigned char c) {
  return (c < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\v' && c != '\f') || c == 0x7f;
}

}  // namespace

std::optional<ForeignContent> foreign_content(const Program& program, bool whole) {
  std::string_view text = std::string_view(program.text).substr(0, kForeignSampleBytes);
  for (const Signature& s : kSignatures)
    if (text.substr(0, s.bytes.size()) == s.bytes) return ForeignContent{{1, 1}, fmt::format("{} at its start", s.what)};
  // Padding at the end of a whole file: NULs, or a DOS end-of-file mark.
  if (whole && text.size() == program.text.size())
    while (!text.empty() && (text.back() == '\0' || text.back() == '\x1a')) text.remove_suffix(1);

  // Control bytes outside comments, counted line by line (a '(' comment ends at its line).
  // Most programs hold none anywhere, which one plain pass over the bytes shows first: then
  // the count below reads nothing.
  const bool any_control =
      std::any_of(text.begin(), text.end(), [](char ch) { return is_control(static_cast<unsigned char>(ch)); });
  size_t outside = 0, control = 0;
  SourceLoc first_control;
  uint32_t line = 1, col = 0;
  bool in_paren = false, in_semicolon = false;
  for (const char ch : any_control ? text : std::string_view()) {
    const auto c = static_cast<unsigned char>(ch);
    ++col;
    if (c == '\n') {
      ++line;
      col = 0;
      in_paren = in_semicolon = false;
      continue;
    }
    if (in_semicolon) continue;
    if (in_paren) {
      in_paren = c != ')';
      continue;
    }
    if (c == '(') {
      in_paren = true;
      continue;
    }
    if (c == ';') {
      in_semicolon = true;
      continue;
    }
    ++outside;
    if (is_control(c) && control++ == 0) first_control = {line, col};
  }
  if (control >= kForeignControlBytes && double(control) > kForeignControlShare * double(outside))
    return ForeignContent{first_control,
                          fmt::format("binary content: {} control bytes outside comments in {} bytes, the first at "
                                      "line {}, column {}",
                                      control, text.size(), first_control.line, first_control.col)};

  size_t unreadable = 0, readable = 0;
  const Block* first_unreadable = nullptr;
  for (const Block& b : program.blocks) {
    if (b.begin >= kForeignSampleBytes) break;
    if (b.kind == BlockKind::Empty) continue;
    if (b.kind != BlockKind::Opaque) {
      ++readable;
    } else if (unreadable++ == 0) {
      first_unreadable = &b;
    }
  }
  if (unreadable > readable)
    return ForeignContent{{first_unreadable->line, 1},
                          fmt::format("{} of its {} blocks cannot be read, the first at line {}", unreadable,
                                      unreadable + readable, first_unreadable->line)};
  return std::nullopt;
}

}  // namespace arcpress
