// SPDX-License-Identifier: GPL-3.0-or-later
// The bytes every fitting method writes for every corpus file, at two bands, pinned by their
// hashes (tests/corpus/output_hashes.txt): a change meant to move code without changing
// what it does (the fitter's methods into files of their own) must keep every one. A change
// meant to change the output rewrites the table: run the test with ARCPRESS_WRITE_HASHES set
// to the table's path, and say in the commit why the bytes changed.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "arcpress/api/arcpress.hpp"
#include "support.hpp"

using namespace arcpress;

namespace {

/// FNV-1a, 64 bits: enough to tell two outputs apart, and the same on every machine.
uint64_t fnv1a(const std::string& s) {
  uint64_t h = 14695981039346656037ull;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

TEST_CASE("every method writes the same bytes as recorded for every corpus file at 0.01 and 0.002 mm",
          "[corpus][hash]") {
  ARCPRESS_CORPUS_FILES_OR_SKIP(files)
  const std::string table_path = ARCPRESS_SOURCE_DIR "/tests/corpus/output_hashes.txt";
  std::map<std::string, std::string> recorded;  // "file method tolerance" -> hash
  {
    std::ifstream in(table_path);
    for (std::string key_file, method, tolerance, hash; in >> key_file >> method >> tolerance >> hash;)
      recorded[key_file + " " + method + " " + tolerance] = hash;
  }
  const std::pair<const char*, FitOptions::Method> methods[] = {
      {"keep", FitOptions::Method::Keep},     {"arcs", FitOptions::Method::Arcs},
      {"global", FitOptions::Method::Global}, {"greedy", FitOptions::Method::Greedy},
      {"stream", FitOptions::Method::Stream}, {"lowe", FitOptions::Method::Lowe}};
  std::string table;
  for (const auto& f : files) {
    const std::string text = test::read_file(f);
    for (const auto& [name, method] : methods) {
      for (const char* tolerance : {"0.01", "0.002"}) {
        CompressOptions opt;
        opt.fit.method = method;
        opt.fit.tolerance_mm = std::atof(tolerance);
        opt.verify = false;  // the bytes are what is pinned; their checks are the corpus tests'
        opt.header = false;  // (the header names the commit, which every commit changes)
        DiagnosticSink sink(f.string());
        const CompressResult r = compress(f.string(), text, opt, sink);
        const std::string key = f.filename().string() + " " + name + " " + tolerance;
        const std::string hash = fmt::format("{:016x}", fnv1a(r.output));
        table += key + " " + hash + "\n";
        INFO(key);
        CHECK(recorded[key] == hash);
      }
    }
  }
  if (const char* out = std::getenv("ARCPRESS_WRITE_HASHES")) {
    std::ofstream(out) << table;
    WARN("wrote " << out);
  }
}
