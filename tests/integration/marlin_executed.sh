#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Marlin's own arc code as a judge of the marlin dialect, Prusa's Buddy firmware's of the
# prusa dialect, Prusa-Firmware's (the MK3's) of prusa-mk3 and Smoothieware's of
# smoothieware: the firmware's G2_G3.cpp (plan_arc() and GcodeSuite::G2_G3()), the MK3's
# motion_control.cpp (mc_arc()) with prusa_mk3_arc.cpp around it, or Smoothieware's
# Robot::append_arc() cut from its Robot.cpp into smoothieware_arc.cpp, from its source
# tree, not copied, is built on this machine with marlin_shim.hpp (prusa_mk3_shim.hpp) and
# marlin_executed.cpp, which replaces each G2/G3 block of a program by the G1 moves the
# firmware hands its planner.
# Marlin runs in its default configuration (segments of 0.1 to 1 mm, at least 72 a circle, an
# exact end every 25th); Buddy in the arc settings of its MK4 configuration
# (include/marlin/Configuration_MK4_adv.h: segments for 0.02 mm within 0.1 to 2 mm, shorter
# below 50 a second at the program's own feed); the MK3 in its MK3S variant's
# (Firmware/variants/MK3S.h: a 20th of the circle within 0.5 to 1 mm, an exact end every
# 26th), in floats as its AVR computes; Smoothieware in Robot::load_config()'s defaults
# (segments for 0.01 mm, their count rounded down, an exact end every 6th). Every corpus file is compressed at 0.05, 0.025
# and 0.01 mm, input and output are cut so, and `arcpress diff` must find the two paths the
# printer moves along within the band, with the same extrusion and the same non-motion
# blocks. Left out: a program the firmware does not run as written (a block without a command,
# or inches) and one `arcpress diff` cannot compare with itself (NURBS). Prints the arcs
# written, the moves the firmware makes of them and the largest distance per file and band
# (scripts/docs_figures.sh marlin, prusa, prusa-mk3 and smoothieware put the tables in
# docs/dialects.md);
# exit 1 where a path leaves the band or anything else differs.
#   marlin_executed.sh ARCPRESS SOURCE_DIR CORPUS_DIR
# SOURCE_DIR: a clone of https://github.com/MarlinFirmware/Marlin (2.0.9 to 2.1.0, whose
# G2_G3.cpp names LINEAR_AXES: the marlin dialect), of
# https://github.com/prusa3d/Prusa-Firmware-Buddy (the prusa dialect), of
# https://github.com/prusa3d/Prusa-Firmware (the prusa-mk3 dialect) or of
# https://github.com/Smoothieware/Smoothieware (the smoothieware dialect), in a folder of
# your own.
set -euo pipefail
arcpress=$1 source=$2 corpus=$3
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The value of each #define NAME of `config` named after it, as -DNAME=value.
config_defines() {
  local config=$1 name value
  shift
  for name in "$@"; do
    value=$(sed -n "s/^ *#define $name  *\([0-9.][0-9.]*\).*/\1/p" "$config" | head -1)
    [ -n "$value" ] || { echo "marlin_executed: no $name in $config" >&2; exit 2; }
    defines+=("-D$name=$value")
  done
}
# A Marlin G2_G3.cpp in a tree of its own, where the headers it includes are empty: the shim
# stands in for them.
marlin_file() {
  local tree="$work/Marlin/src"
  mkdir -p "$tree/gcode/motion" "$tree/inc" "$tree/module" "$tree/feature/precise_stepping"
  cp "$1" "$tree/gcode/motion/G2_G3.cpp"
  touch "$tree/inc/MarlinConfig.h" "$tree/gcode/gcode.h" "$tree/module/motion.h" "$tree/module/planner.h" \
    "$tree/module/temperature.h" "$tree/feature/precise_stepping/internal.hpp"
  g++ -std=c++17 -O2 -c -include "$here/marlin_shim.hpp" -DMARLIN_FIRMWARE_FILE "${defines[@]}" -I"$tree" \
    "$tree/gcode/motion/G2_G3.cpp" -o "$work/arc.o"
}
defines=() driver_defines=()
if [ -f "$source/lib/Marlin/Marlin/src/gcode/motion/G2_G3.cpp" ]; then
  dialect=prusa firmware=Buddy
  config_defines "$source/include/marlin/Configuration_MK4_adv.h" MIN_ARC_SEGMENT_MM MAX_ARC_SEGMENT_MM \
    MIN_ARC_SEGMENTS_PER_SEC MAX_ARC_DEVIATION N_ARC_CORRECTION
  marlin_file "$source/lib/Marlin/Marlin/src/gcode/motion/G2_G3.cpp"
elif [ -f "$source/Marlin/src/gcode/motion/G2_G3.cpp" ]; then
  dialect=marlin firmware=Marlin
  marlin_file "$source/Marlin/src/gcode/motion/G2_G3.cpp"
elif [ -f "$source/Firmware/motion_control.cpp" ]; then
  dialect=prusa-mk3 firmware=MK3
  config_defines "$source/Firmware/variants/MK3S.h" DEFAULT_MM_PER_ARC_SEGMENT DEFAULT_MIN_MM_PER_ARC_SEGMENT \
    DEFAULT_N_ARC_CORRECTION DEFAULT_MIN_ARC_SEGMENTS DEFAULT_ARC_SEGMENTS_PER_SEC
  # mc_arc() in a tree of its own, its headers empty; G2/G3 around it, the driver reading E
  # by M82/M83 only ("E axis is left intact" by G90/G91).
  mkdir -p "$work/Firmware"
  cp "$source/Firmware/motion_control.cpp" "$work/Firmware/"
  touch "$work/Firmware/Marlin.h" "$work/Firmware/stepper.h" "$work/Firmware/planner.h"
  g++ -std=c++17 -O2 -c -include "$here/prusa_mk3_shim.hpp" "${defines[@]}" -I"$work/Firmware" \
    "$work/Firmware/motion_control.cpp" -o "$work/motion_control.o"
  g++ -std=c++17 -O2 -c -include "$here/marlin_shim.hpp" "$here/prusa_mk3_arc.cpp" -o "$work/arc.o"
  driver_defines=(-DE_BY_M82_M83)
elif [ -f "$source/src/modules/robot/Robot.cpp" ]; then
  dialect=smoothieware firmware=Smoothieware
  # Robot::append_arc(), cut from Robot.cpp (its first line to the brace that ends it), built
  # inside smoothieware_arc.cpp with what it reads of the Robot around it.
  sed -n '/^bool Robot::append_arc(/,/^}/p' "$source/src/modules/robot/Robot.cpp" > "$work/append_arc.inc"
  grep -q '^}' "$work/append_arc.inc" || { echo "marlin_executed: no Robot::append_arc() in $source" >&2; exit 2; }
  g++ -std=c++17 -O2 -c -include "$here/marlin_shim.hpp" -DSMOOTHIEWARE_APPEND_ARC="\"$work/append_arc.inc\"" \
    "$here/smoothieware_arc.cpp" -o "$work/arc.o"
else
  echo "marlin_executed: no Marlin, Buddy, MK3 or Smoothieware source at '$source'" >&2
  exit 2
fi
g++ -std=c++17 -O2 -c -include "$here/marlin_shim.hpp" "${driver_defines[@]}" "$here/marlin_executed.cpp" \
  -o "$work/driver.o"
g++ "$work"/*.o -o "$work/marlin_executed"
. "$here/executed_runs.sh"
executed_runs "$arcpress" "$corpus" "$dialect" "$firmware" "$work/marlin_executed"
