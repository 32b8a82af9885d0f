#pragma once
// The C++ façade: one call runs the whole pipeline on a program held in memory.
// lex -> interpret -> extract runs -> fit -> emit (-> verify).
#include <string>

#include "arcpress/core/diagnostic.hpp"
#include "arcpress/emit/emitter.hpp"
#include "arcpress/fit/primitive.hpp"

namespace arcpress {

inline constexpr const char* kVersion = "0.1.0";

struct CompressOptions {
  FitOptions fit;
  bool passthrough = false;  ///< lex and write back every block unchanged
  bool strict = false;       ///< any unreadable block is an error
};

struct CompressResult {
  bool ok = false;        ///< false: input errors (see the sink); `output` is then empty
  std::string output;
  size_t blocks_in = 0;
  size_t bytes_in = 0;
  EmitStats stats;
};

/// Compresses `text` (the program called `name` in diagnostics). Never throws for bad
/// input: problems go to `sink`, and in strict mode any of them makes `ok` false.
CompressResult compress(const std::string& name, std::string text, const CompressOptions& opt,
                        DiagnosticSink& sink);

}  // namespace arcpress
