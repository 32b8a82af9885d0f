// SPDX-License-Identifier: GPL-3.0-or-later
// Compresses a G-code file for a controller with arcpress's C++ library, as a CAM
// post-processor would: compress INPUT OUTPUT [DIALECT]. Exit 0 written, 1 refused, 2 bad input.
#include <arcpress/arcpress.hpp>

#include <fstream>
#include <iostream>

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: compress INPUT OUTPUT [DIALECT]\n";
    return 2;
  }
  try {
    arcpress::CompressOptions options;
    options.fit.tolerance_mm = 0.01;
    options.dialect = arcpress::dialect_named(argc > 3 ? argv[3] : "rs274");
    std::ifstream in(argv[1], std::ios::binary);
    std::ofstream out(argv[2], std::ios::binary);
    arcpress::DiagnosticSink sink(argv[1]);
    const arcpress::CompressResult r = arcpress::compress_stream(in, out, argv[1], options, sink);
    std::cerr << sink.format_all();
    if (!r.ok || !r.within_band()) {
      std::cerr << "compress: the output cannot be used\n";
      return r.ok ? 1 : 2;
    }
    std::cerr << "compress: " << r.bytes_in << " -> " << r.bytes_out << " bytes, " << r.stats.arcs_out
              << " arcs, deviation " << r.check.max_deviation_mm << " mm\n";
    return 0;
  } catch (const arcpress::Error& e) {
    std::cerr << "compress: " << e.what() << "\n";
    return e.exit_code();
  }
}
