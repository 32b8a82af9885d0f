// SPDX-License-Identifier: GPL-3.0-or-later
// Whatever bytes a program holds, arcpress passes it through unchanged, compresses it inside
// the band or refuses it with diagnostics, and never finds it different from itself.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "random_program.hpp"
#include "support.hpp"

namespace {

/// A program of random words: the G-code tokens the fuzz target's dictionary holds, numbers
/// of every size and sign, comments, line ends, and now and then a stray byte.
std::string random_text(std::mt19937& rng) {
  static const std::vector<std::string> words = {
      "G0", "G1", "G2", "G3", "G17", "G18", "G19", "G20", "G21", "G28", "G53", "G54", "G7", "G8", "G81", "G80",
      "G90", "G91", "G90.1", "G91.1", "G92", "G93", "G94", "M3", "M4", "M5", "M82", "M83", "M117 hello", "M486 S1",
      "(note)", "; note", "#1=2", "O100 sub", "%", "/", "*12", "$H", "F600", "S300", "P2", "T1", "N10",
      // The Sinumerik language's keywords, which text_promise() reads under its dialect too.
      "SOFT", "ADIS=0.5", "G70", "G71", "MCALL CYCLE81(1,2)", "MCALL", "TRANS", "CR=5", "CT", "DIAMON", "L10", "D1",
      "CYCLE832(0.01,_FINISH,1)", "MSG(\"a (b)\")", "CYCLE81(10,0,2,-5)", "CYCLE800(",
      // Its assignments and labels, and Heidenhain ISO's numbered labels (text_promise() reads those too).
      "R1=2", "X=R1", "X=IC(5)", "LOOP1:", "GOTOB LOOP1", "GOTOF LOOP1", "G98 L1", "L1,2", "L1,0", "G98 L0"};
  static const char axes[] = "XYZAEIJKRF";
  std::uniform_int_distribution<int> pick(0, 99), word(0, int(words.size()) - 1), axis(0, 9), lines(1, 60);
  std::uniform_real_distribution<double> small(-20, 20);
  std::string t;
  for (int l = lines(rng); l-- > 0;) {
    for (int w = pick(rng) % 5; w-- >= 0;) {
      const int r = pick(rng);
      if (r < 35) t += words[size_t(word(rng))];
      else if (r < 90) t += fmt::format("{}{:.{}f}", axes[axis(rng)], small(rng), pick(rng) % 5);
      else if (r < 95) t += fmt::format("{}{}", axes[axis(rng)], pick(rng) < 50 ? "1e15" : "-100000000");
      else t += char(pick(rng) % 2 ? '[' : 0x7f);
      t += pick(rng) < 80 ? " " : "";
    }
    t += pick(rng) < 95 ? "\n" : "\r\n";
  }
  return t;
}

}  // namespace

TEST_CASE("programs of random words keep every promise: passed through unchanged, compressed inside the band or "
          "refused, never different from themselves", "[property][text]") {
  std::mt19937 rng(20261125);
  for (int trial = 0; trial < 1500; ++trial) {
    const std::string text = random_text(rng);
    INFO("trial " << trial << "\n" << text);
    CHECK(arcpress::test::text_promise(text) == "");
  }
}

TEST_CASE("the program texts fuzzing found replay without breaking a promise", "[property][text]") {
  // tests/fuzz/found-text: texts scripts/fuzz.sh stopped at (text_fuzz), and the cases the
  // checks once got wrong, each named for what it found.
  const std::filesystem::path dir = std::filesystem::path(ARCPRESS_SOURCE_DIR) / "tests" / "fuzz" / "found-text";
  size_t replayed = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string text = arcpress::test::read_file(e.path());
    INFO(e.path().filename().string() << "\n" << text);
    CHECK(arcpress::test::text_promise(text) == "");
    ++replayed;
  }
  CHECK(replayed >= 3);
}
