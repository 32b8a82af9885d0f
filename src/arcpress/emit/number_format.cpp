#include "arcpress/emit/number_format.hpp"

#include <fmt/format.h>

#include <cmath>

namespace arcpress {

namespace {
/// 10^decimals, exact up to 10^22; from the table where the printing below handles it.
double scale_of(int decimals) {
  static constexpr double kPow10[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
  return decimals >= 0 && decimals <= 15 ? kPow10[decimals] : std::pow(10.0, decimals);
}
}  // namespace

double rounded(double value, int decimals) {
  const double scale = scale_of(decimals);
  return std::round(value * scale) / scale;
}

std::string format_number(double value, const NumberStyle& style) {
  const int dec = style.decimals;
  const double scaled = std::round(value * scale_of(dec));
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
    double v = scaled / scale_of(dec);
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
  return s;
}

}  // namespace arcpress
