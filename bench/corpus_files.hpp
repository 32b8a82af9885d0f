// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The corpus files the benches run on: every file under ARCPRESS_CORPUS_DIR but its
// MANIFEST (.md), in path order; none when the folder is absent.
#include <algorithm>
#include <filesystem>
#include <vector>

inline std::vector<std::filesystem::path> corpus_files() {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  if (fs::is_directory(ARCPRESS_CORPUS_DIR))
    for (const auto& e : fs::recursive_directory_iterator(ARCPRESS_CORPUS_DIR))
      if (e.is_regular_file() && e.path().extension() != ".md") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}
