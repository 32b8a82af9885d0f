// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the fuzzer's bytes taken as a program text, whatever they are, through
// pass-through, compression with verification and `arcpress diff` against itself
// (text_promise()); a broken promise aborts with the text on standard error, so the fuzzer
// keeps the input that found it. Built with -DARCPRESS_FUZZ=ON and clang; scripts/fuzz.sh
// builds and runs it beside compress_fuzz.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "random_program.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string broken = arcpress::test::text_promise(text);
  if (!broken.empty()) {
    std::fprintf(stderr, "broken promise: %s\n--- program ---\n%s\n", broken.c_str(), text.c_str());
    std::abort();
  }
  return 0;
}
