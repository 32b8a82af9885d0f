// SPDX-License-Identifier: GPL-3.0-or-later
// The platform layer on Linux and other POSIX systems.
#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "arcpress/platform/platform.hpp"

namespace arcpress::platform {
namespace {

std::string folder_of(const std::filesystem::path& file) {
  std::error_code ec;
  const std::filesystem::path resolved = std::filesystem::canonical(file, ec);
  return ec ? std::string() : resolved.parent_path().string();
}

}  // namespace

std::string own_folder() {
  Dl_info info{};
  if (::dladdr(reinterpret_cast<void*>(&own_folder), &info) == 0 || !info.dli_fname) return {};
  return folder_of(info.dli_fname);
}

std::string program_folder() { return folder_of("/proc/self/exe"); }

std::optional<std::string> environment(const char* name) {
  const char* value = std::getenv(name);
  return value ? std::optional<std::string>(value) : std::nullopt;
}

char path_list_separator() { return ':'; }

}  // namespace arcpress::platform
