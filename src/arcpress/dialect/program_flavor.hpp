#pragma once
// The controller a program names for itself: slicers write the firmware flavor they sliced
// for into the program (PrusaSlicer, SuperSlicer, OrcaSlicer and Slic3r `; gcode_flavor =
// marlin2` in their config block, Cura `;FLAVOR:Marlin` in its header). Used when the user
// names no dialect, so a slicer's post-processing step needs no options.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace arcpress {

struct ProgramFlavor {
  std::string dialect;   ///< the shipped dialect it maps to ("marlin", "klipper", ...)
  std::string evidence;  ///< the program's own words, e.g. "; gcode_flavor = marlin2"
  uint32_t line = 0;     ///< 1-based line of the evidence
};

/// The dialect `program` names, where it names one that maps to a shipped dialect without
/// doubt; nothing otherwise (no flavor, or one such as RepRap/Sprinter that several
/// firmwares answer to).
std::optional<ProgramFlavor> program_flavor(std::string_view program);

}  // namespace arcpress
