// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The controller a program names for itself: slicers write the firmware flavor they sliced
// for into the program (PrusaSlicer, SuperSlicer, OrcaSlicer and Slic3r `; gcode_flavor =
// marlin2` in their config block, Cura `;FLAVOR:Marlin` in its header). Used when the user
// names no dialect, so a slicer's post-processing step needs no options.
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
};

/// The first flavor line of `program`: the shipped dialect it maps to without doubt, or an
/// empty dialect where the flavor is one that several firmwares answer to (RepRap/Sprinter);
/// nothing where the program has no flavor line.
std::optional<ProgramFlavor> program_flavor(std::string_view program);

/// The dialects a flavor line maps to, for a message that says what to pass instead.
std::vector<std::string> flavor_dialects();

}  // namespace arcpress
