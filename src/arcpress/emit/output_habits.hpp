// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// How the input writes its blocks, which the blocks arcpress adds copy: program-wide habits
// (G01 or G1, "1." or "1", "+1" or "1", a " *" at the end), and what RS274 reads as motion.
#include <fmt/format.h>

#include <string>
#include <string_view>

#include "arcpress/lex/block.hpp"
#include "arcpress/model/move.hpp"

namespace arcpress {

/// Program-wide habits of the input that new blocks copy: G01 or G1, whole numbers as "1." or
/// "1", positive numbers as "+1" or "1", and blocks ended with " *" (Heidenhain ISO) or not.
struct OutputHabits {
  bool padded = false;
  bool keep_point = false;
  bool plus_sign = false;
  bool block_end = false;
};
/// The habits of `program` (the first 200 motion words decide G01 or G1; the axis words and
/// code blocks, the signs and the block end).
OutputHabits output_habits(const Program& program);

/// How one block of the input is written, which a block arcpress writes in its place copies,
/// so that new blocks look like their neighbours.
struct BlockStyle {
  bool lower = false;
  bool spaced = true;
  bool padded = false;  ///< G01 rather than G1
  bool keep_point = false;
  bool plus = false;  ///< positive numbers with a '+'

  std::string letter(char c) const { return std::string(1, lower ? char(c + 32) : c); }
  std::string motion(int g) const { return fmt::format("{}{}{}", letter('G'), padded ? "0" : "", g); }
};
/// The style of block `b` of `program`: its letters' case, spaces between its first words and
/// its motion word's G01 or G1, else the program's `habits`.
BlockStyle block_style(const Program& program, const Block& b, const OutputHabits& habits);

/// The blanks block `b` of `program` begins with, which a block written in place of moves
/// from it takes (so it stays in the `if` or `while` they were in: Dialect::indented_blocks).
std::string_view block_indent(const Program& program, const Block& b);

/// Whether G-code `v` is one RS274 reads as a motion (G0..G3, G5.x, G33, G38.x, G73, G76,
/// G80..G89): modal, and stated again where the output's modal motion differs.
bool is_motion_gcode(double v);
/// Whether a word's letter names an axis (X Y Z A B C U V W, and E).
inline bool moves_axis(char letter) { return axis_of_letter(letter) >= 0; }

}  // namespace arcpress
