// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/emit/number_format.hpp"

#include <fmt/format.h>

#include <cmath>

#include "arcpress/core/decimal.hpp"

namespace arcpress {

double rounded(double value, int decimals) {
  const double scale = pow10(decimals);
  return std::round(value * scale) / scale;
}

std::string format_number(double value, const NumberStyle& style) {
  const int dec = style.decimals;
  const double scaled = std::round(value * pow10(dec));
  std::string s;
  if (dec >= 0 && dec <= 15 && std::abs(scaled) < 1e15) {
    // The rounded value is the integer `scaled` over 10^dec: its digits, with the point put
    // in (what printing the rounded double to dec places gives, without the formatter).
    long long k = static_cast<long long>(scaled);
    const bool negative = k < 0;
    if (negative) k = -k;
    char digits[20];
    int n = 0;
    do {
      digits[n++] = static_cast<char>('0' + k % 10);
      k /= 10;
    } while (k > 0 || n <= dec);
    s.reserve(static_cast<size_t>(n) + 2);
    if (negative) s += '-';
    for (int i = n - 1; i >= 0; --i) {
      s += digits[i];
      if (i == dec && dec > 0) s += '.';
    }
  } else {
    double v = scaled / pow10(dec);
    if (v == 0) v = 0;  // no "-0"
    s = fmt::format("{:.{}f}", v, dec);
  }
  if (style.trim_zeros && s.find('.') != std::string::npos) {
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.' && !style.keep_point) s.pop_back();
  } else if (style.keep_point && s.find('.') == std::string::npos) {
    s += '.';
  }
  if (s == "-0" || s == "-0.") s.erase(0, 1);
  if (style.plus_sign && s.front() != '-') s.insert(s.begin(), '+');
  return s;
}

}  // namespace arcpress
