# SPDX-License-Identifier: GPL-3.0-or-later
# Sourced by klipper_executed.sh and marlin_executed.sh: a firmware's own arc code as a judge
# of what arcpress writes for it. executed_runs ARCPRESS CORPUS DIALECT FIRMWARE CUT...
# compresses every corpus file at 0.05, 0.025 and 0.01 mm; CUT (a command and its first
# arguments, the program's path added last) writes a program again with each G2/G3 replaced
# by the G1 moves the firmware makes of it, and fails where the firmware would not run the
# program as written; input and output are cut so, and `arcpress diff` must find the two
# paths the printer moves along within the band, with the same extrusion and the same
# non-motion blocks. Prints a line per file and band (the arcs written, the moves the
# firmware makes of the output's arcs, the largest distance, the verdict); returns 1 where a
# path leaves the band or anything else differs. Uses $work, a folder of the caller's.
executed_runs() {
  local arcpress=$1 corpus=$2 dialect=$3 firmware=$4
  shift 4
  local status=0 f name band arcs moves verdict deviation
  printf '%-46s %6s %6s %13s %13s  %s\n' program band arcs "$firmware's G1" "deviation mm" verdict
  for f in "$corpus"/*/*; do
    case $f in *.md) continue ;; esac
    name=$(basename "$f")
    # The input's own arcs are cut by the firmware too: the two paths the printer moves along
    # are compared. A program it does not run as written is for another controller.
    "$@" "$f" > "$work/input.gcode" 2> /dev/null || continue
    # (and one arcpress diff cannot compare with itself: NURBS blocks, G5.2)
    "$arcpress" diff "$work/input.gcode" "$work/input.gcode" --dialect "$dialect" > /dev/null 2>&1 || continue
    for band in 0.05 0.025 0.01; do
      "$arcpress" "$f" -o "$work/out.gcode" --dialect "$dialect" --tolerance "$band" --stats 2> "$work/stats.txt" ||
        { echo "FAIL: $name at $band: arcpress exit $?: $(tail -2 "$work/stats.txt")"; status=1; continue; }
      arcs=$(sed -n 's/^  written *[0-9]* G1 + \([0-9]*\) G2\/G3.*/\1/p' "$work/stats.txt")
      "$@" "$work/out.gcode" > "$work/executed.gcode" 2> "$work/cut.txt" ||
        { echo "FAIL: $name at $band: $firmware's arc code refused an arc: $(tail -1 "$work/cut.txt")"; status=1; continue; }
      moves=$(($(grep -c . "$work/executed.gcode") - $(grep -c . "$work/out.gcode") + arcs))
      verdict=SAME
      "$arcpress" diff "$work/input.gcode" "$work/executed.gcode" --tolerance "$band" --dialect "$dialect" \
        > "$work/diff.txt" 2>&1 || { verdict=$(grep -E '^(DIFFERENT|INCOMPLETE)' "$work/diff.txt" || echo "exit $?"); status=1; }
      deviation=$(sed -n 's/^max deviation \([0-9.]*\) mm.*/\1/p' "$work/diff.txt")
      printf '%-46s %6s %6s %13s %13s  %s\n' "$name" "$band" "$arcs" "$moves" "${deviation:--}" "$verdict"
    done
  done
  return $status
}
