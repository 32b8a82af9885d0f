// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Paths are UTF-8 strings everywhere in arcpress. std::filesystem reads a narrow string in
// the system's code page, which is UTF-8 on POSIX systems but a legacy one on Windows: these
// two conversions go through char8_t, so that a file named `Ø-pièce 部品.nc` is the same file
// on every system.
#include <filesystem>
#include <string>
#include <string_view>

namespace arcpress {

/// The path a UTF-8 string names.
inline std::filesystem::path utf8_path(std::string_view utf8) {
  return std::filesystem::path(std::u8string(utf8.begin(), utf8.end()));
}

/// A path as a UTF-8 string.
inline std::string utf8_string(const std::filesystem::path& p) {
  const std::u8string s = p.u8string();
  return std::string(s.begin(), s.end());
}

}  // namespace arcpress
