// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: a program and options made from the fuzzer's bytes (random_case()), run
// through the whole pipeline with verification; any broken promise aborts with the program
// on standard error, so the fuzzer keeps the input that found it. Built with
// -DARCPRESS_FUZZ=ON and clang; scripts/fuzz.sh builds and runs it.
#include <cstdio>
#include <cstdlib>
#include <span>

#include "random_program.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  arcpress::test::RandomCase c = arcpress::test::random_case(std::span<const uint8_t>(data, size));
  arcpress::DiagnosticSink sink;
  arcpress::CompressResult r = arcpress::compress("fuzz.nc", c.text, c.opt, sink);
  const std::string broken = arcpress::test::broken_promise(r);
  if (!broken.empty()) {
    std::fprintf(stderr, "broken promise: %s\n--- program ---\n%s", broken.c_str(), c.text.c_str());
    std::abort();
  }
  return 0;
}
