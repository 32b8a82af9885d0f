// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/arcpress.hpp"

#include <cstdlib>

#include <fmt/format.h>

#include "arcpress/api/compressor.hpp"
#include "arcpress/platform/platform.hpp"

namespace arcpress {

Dialect dialect_named(const std::string& name) {
  // $ARCPRESS_DIALECT_PATH, then beside the library as installed (PREFIX/lib ->
  // PREFIX/share/arcpress/dialects) or built, then the prefix it was configured for, then
  // the source tree.
  std::vector<std::string> path = dialect_search_path(platform::own_folder());
  path.insert(path.end() - (*ARCPRESS_SOURCE_DIALECT_DIR ? 1 : 0), ARCPRESS_INSTALL_DIALECT_DIR);
  return find_dialect(name, path);
}

CompressResult compress_stream(std::istream& in, std::ostream& out, const std::string& name,
                               const CompressOptions& options, DiagnosticSink& sink) {
  constexpr size_t kChunk = size_t(1) << 20;
  Compressor c(name, options, sink);
  std::string chunk(kChunk, '\0'), text;
  // A stream that can be read again has its jumps read first, whole lines at a time.
  if (const std::streampos start = in.tellg(); start != std::streampos(-1)) {
    std::string lines;
    for (size_t got; in.read(chunk.data(), std::streamsize(chunk.size())), (got = size_t(in.gcount())) > 0;) {
      lines.append(chunk.data(), got);
      const size_t last = lines.rfind('\n');
      if (last == std::string::npos) continue;
      c.read_jumps(std::string_view(lines).substr(0, last + 1), 0);
      lines.erase(0, last + 1);
    }
    if (in.bad()) throw Error(kExitIo, fmt::format("cannot read '{}'", name));
    c.read_jumps(lines, 0);
    in.clear();
    if (!in.seekg(start)) throw Error(kExitIo, fmt::format("cannot read '{}' again", name));
    // A program that jumps is read once more ahead, whole, for its loops (up to the size
    // read_loops() takes).
    if (c.has_jumps()) {
      std::string program;
      for (size_t got; program.size() <= Compressor::kLoopsAheadBytes &&
                       (in.read(chunk.data(), std::streamsize(chunk.size())), (got = size_t(in.gcount())) > 0);)
        program.append(chunk.data(), got);
      c.read_loops(program);
      in.clear();
      if (!in.seekg(start)) throw Error(kExitIo, fmt::format("cannot read '{}' again", name));
    }
  }
  auto write = [&] {
    text.clear();
    if (c.take(text) > 0 && !out.write(text.data(), std::streamsize(text.size())))
      throw Error(kExitIo, fmt::format("cannot write the output of '{}'", name));
  };
  while (c.result().ok && in) {
    in.read(chunk.data(), std::streamsize(chunk.size()));
    const auto got = size_t(in.gcount());
    if (got == 0) break;
    c.push(std::string_view(chunk.data(), got));
    write();
  }
  if (in.bad()) throw Error(kExitIo, fmt::format("cannot read '{}'", name));
  c.finish();
  write();
  out.flush();
  if (!out) throw Error(kExitIo, fmt::format("cannot write the output of '{}'", name));
  return c.result();
}

}  // namespace arcpress
