// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What differs between operating systems, behind one interface: one source file per system
// implements it (posix.cpp here; CMake picks the file), and nothing else in the library
// asks the system these things.
#include <optional>
#include <string>

namespace arcpress::platform {

/// The folder of the file this code was loaded from (the shared library, or the program it
/// is linked into), its links resolved; empty where the system cannot say.
std::string own_folder();

/// The folder of the running program, its links resolved; empty where the system cannot say.
std::string program_folder();

/// The environment variable `name` in UTF-8 (read through the wide API on Windows), or none
/// where it is not set.
std::optional<std::string> environment(const char* name);

/// What separates the folders of a path list such as $ARCPRESS_DIALECT_PATH (':' on POSIX
/// systems, where ';' may stand in a folder's name).
char path_list_separator();

}  // namespace arcpress::platform
