#include "arcpress/emit/number_format.hpp"

#include <fmt/format.h>

#include <cmath>

namespace arcpress {

double rounded(double value, int decimals) {
  double scale = std::pow(10.0, decimals);
  return std::round(value * scale) / scale;
}

std::string format_number(double value, const NumberStyle& style) {
  double v = rounded(value, style.decimals);
  if (v == 0) v = 0;  // no "-0"
  std::string s = fmt::format("{:.{}f}", v, style.decimals);
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
