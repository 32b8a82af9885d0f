// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Powers of ten for reading and printing decimal numbers: 10^0 to 10^22, each exact as a
// double, so a number of up to 15 significant digits read as integer / 10^d, or rounded as
// round(x · 10^d), is the correctly rounded value.
#include <cmath>

namespace arcpress {

inline constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
inline constexpr int kExactPow10Max = 22;

/// 10^decimals: exact from the table where it can be, else std::pow.
inline double pow10(int decimals) {
  return decimals >= 0 && decimals <= kExactPow10Max ? kPow10[decimals] : std::pow(10.0, decimals);
}

}  // namespace arcpress
