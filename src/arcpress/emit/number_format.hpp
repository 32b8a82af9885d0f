// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Explicit number output for G-code: fixed point, never exponent notation, no "-0".
#include <string>

namespace arcpress {

struct NumberStyle {
  int decimals = 4;           ///< digits after the point before trimming
  bool trim_zeros = true;     ///< drop trailing zeros after the point
  bool keep_point = false;    ///< "1." rather than "1" for whole numbers (Fanuc, Haas)
  bool plus_sign = false;     ///< "+1.5" rather than "1.5" (and "+0"), as Heidenhain programs write them
};

/// Formats `value` for a G-code word. Round-half-away-from-zero at `decimals` digits.
std::string format_number(double value, const NumberStyle& style);
/// The value a controller reads back from format_number's text.
double rounded(double value, int decimals);

}  // namespace arcpress
