// SPDX-License-Identifier: GPL-3.0-or-later
// What file_io.hpp builds on InputFile and OutputFile, the same on every system (the
// platform files implement those two).
#include "file_io.hpp"

namespace arcpress::cli {

size_t InputFile::copy_rest(const std::function<void(std::string_view)>& put) {
  std::string chunk;
  size_t total = 0;
  while (true) {
    chunk.clear();
    if (read(chunk, size_t(1) << 20) == 0) return total;
    put(chunk);
    total += chunk.size();
  }
}

std::string read_input(const std::string& path) {
  InputFile in(path);
  std::string data;
  constexpr size_t kChunk = size_t(1) << 16;
  // Room for the whole file and for the chunk each read asks room for, so that the last
  // reads do not move it all to a larger buffer.
  if (in.size()) data.reserve(*in.size() + kChunk);
  while (in.read(data, kChunk) > 0) {
  }
  return data;
}

void write_output(const std::string& path, std::string_view data) {
  OutputFile out(path);
  out.write(data);
  out.commit();
}

void write_stdout(std::string_view data) { write_output("-", data); }

}  // namespace arcpress::cli
