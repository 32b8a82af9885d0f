// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Reading dialect files: TOML (toml++), one controller per file, every field optional and
// defaulting to generic RS274 (Dialect{}). Unknown keys and wrong types are errors, so a
// typo in a user's file cannot silently fall back to a default.
#include <string>
#include <vector>

#include "arcpress/dialect/dialect.hpp"

namespace arcpress {

/// Parses dialect TOML `text`; `path` names it in errors. Throws Error(kExitInput) with
/// "path:line:col: key: what is wrong".
Dialect parse_dialect(const std::string& text, const std::string& path);
/// Reads and parses the file at `path`. Throws Error (kExitIo when unreadable).
Dialect load_dialect_file(const std::string& path);

/// Folders searched for NAME.toml, first match wins: $ARCPRESS_DIALECT_PATH (':'-separated),
/// then `exe_dir`/../share/arcpress/dialects and `exe_dir`/../dialects (an installed or a
/// build-tree program), then the source tree's dialects/ this binary was built from.
std::vector<std::string> dialect_search_path(const std::string& exe_dir);
/// Loads dialect `name` from the search path. Throws Error(kExitInput) listing the known names.
Dialect find_dialect(const std::string& name, const std::vector<std::string>& search_path);
/// Every dialect on the search path (first of each name), sorted by name.
std::vector<Dialect> list_dialects(const std::vector<std::string>& search_path);

}  // namespace arcpress
