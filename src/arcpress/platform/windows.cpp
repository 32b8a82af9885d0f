// SPDX-License-Identifier: GPL-3.0-or-later
// The platform layer on Windows: paths come from the wide API and are given out in UTF-8.
#include <windows.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>

#include "arcpress/core/utf8_path.hpp"
#include "arcpress/platform/platform.hpp"

namespace arcpress::platform {
namespace {

/// The folder of the module `module` was loaded from (nullptr: the program), in UTF-8.
std::string folder_of_module(HMODULE module) {
  std::wstring name(MAX_PATH, L'\0');
  for (;;) {
    const DWORD n = ::GetModuleFileNameW(module, name.data(), DWORD(name.size()));
    if (n == 0) return {};
    if (n < name.size()) {
      name.resize(n);
      break;
    }
    name.resize(name.size() * 2);  // cut short: a longer buffer
  }
  std::error_code ec;
  const std::filesystem::path resolved = std::filesystem::weakly_canonical(std::filesystem::path(name), ec);
  return utf8_string((ec ? std::filesystem::path(name) : resolved).parent_path());
}

}  // namespace

std::string own_folder() {
  HMODULE module = nullptr;
  if (!::GetModuleHandleExW(GET_MODULE_HANDLE_EX_FLAG_FROM_ADDRESS | GET_MODULE_HANDLE_EX_FLAG_UNCHANGED_REFCOUNT,
                            reinterpret_cast<LPCWSTR>(&own_folder), &module))
    return {};
  return folder_of_module(module);
}

std::string program_folder() { return folder_of_module(nullptr); }

std::optional<std::string> environment(const char* name) {
  const std::wstring wide_name(name, name + std::strlen(name));  // (names are ASCII)
  const DWORD n = ::GetEnvironmentVariableW(wide_name.c_str(), nullptr, 0);
  if (n == 0) return std::nullopt;
  std::wstring value(n, L'\0');
  const DWORD got = ::GetEnvironmentVariableW(wide_name.c_str(), value.data(), n);
  value.resize(got < n ? got : 0);
  return utf8_string(std::filesystem::path(value));
}

char path_list_separator() { return ';'; }

}  // namespace arcpress::platform
