// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The ASCII letters and digits G-code is read by, for the files of the lex stage.

namespace arcpress {

inline bool is_digit(char c) { return c >= '0' && c <= '9'; }
inline bool is_alpha(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }
inline char upper(char c) { return (c >= 'a' && c <= 'z') ? char(c - 32) : c; }

}  // namespace arcpress
