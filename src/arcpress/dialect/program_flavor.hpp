// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The controller a program names for itself: slicers write the firmware flavor they sliced
// for into the program (PrusaSlicer, SuperSlicer, OrcaSlicer and Slic3r `; gcode_flavor =
// marlin2` in their config block, Cura `;FLAVOR:Marlin` in its header), and a Heidenhain ISO
// program begins with its own block (`%NAME G71 *`). Used when the user names no dialect, so
// a slicer's post-processing step needs no options, and a TNC program is not read as RS274
// (whose I/J are offsets where the TNC's are the centre itself).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace arcpress {

struct ProgramFlavor {
  /// The shipped dialect it maps to ("marlin", "klipper", ...); empty where the flavor names
  /// no single firmware (RepRap/Sprinter, Cura's "RepRap (RepRap)"), so none is picked.
  std::string dialect;
  std::string evidence;  ///< the program's own words, e.g. "; gcode_flavor = marlin2"
  uint32_t line = 0;     ///< 1-based line of the evidence
  bool slicer = true;    ///< a slicer's flavor line: a printer's program, which starts in millimetres
  /// Named by a Prusa printer's model alone (`M862.3 P "MK3S"`), no flavor line read with it:
  /// one further on that names another firmware than Marlin outranks it.
  bool model_only = false;
};

/// The first flavor line of `program`: the shipped dialect it maps to without doubt, or an
/// empty dialect where the flavor is one that several firmwares answer to (RepRap/Sprinter);
/// where it says Marlin, or there is none, the first line naming a Prusa printer model
/// (`; printer_model = MK3S`, `M862.3 P "MK4"`) outranks it: prusa-mk3 for Prusa-Firmware's
/// models (MK3, MK3S, MK2.5), prusa for Buddy's (MK3.5, MK3.9, MK4, MINI, XL, CORE One);
/// heidenhain-iso where the program's first line is a TNC program's begin block (`%NAME G71 *`
/// or `G70`); sinumerik where it is a Sinumerik program file's (`%_N_PART1_MPF`), or where a
/// line gives its folder on the control (`;$PATH=/_N_MPF_DIR`); nothing where the program has
/// none of them.
std::optional<ProgramFlavor> program_flavor(std::string_view program);

/// The shipped dialect a program file's extension names where the program names none itself:
/// sinumerik for a Sinumerik main or subprogram file (`part.mpf`, `part.spf`, any case);
/// empty for any other.
std::string dialect_of_extension(std::string_view path);

/// The dialects a flavor line maps to, for a message that says what to pass instead.
std::vector<std::string> flavor_dialects();

}  // namespace arcpress
