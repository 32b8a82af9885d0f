#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Klipper's own arc code as a judge of the klipper dialect: every corpus file is compressed
# at 0.05, 0.025 and 0.01 mm, each G2/G3 of the output is cut into the G1 moves Klipper's
# gcode_arcs.py makes of it (klipper_executed.py imports it from a Klipper source tree), as
# are the input's own arcs, and `arcpress diff` must find the two paths the printer moves
# along within the band, with the same extrusion and the same non-motion blocks. Left out: a
# program Klipper does not run (an arc in R form or under G91, a block without a command: no
# modal motion) and one `arcpress diff` cannot compare with itself (NURBS). Prints the arcs written, the
# moves Klipper makes of them and the largest distance per file and band
# (scripts/docs_figures.sh klipper puts the table in docs/dialects.md); exit 1 where a path
# leaves the band or anything else differs.
#   klipper_executed.sh ARCPRESS KLIPPER_SOURCE_DIR CORPUS_DIR
# KLIPPER_SOURCE_DIR: a clone of https://github.com/Klipper3d/klipper in a folder of your own.
set -euo pipefail
arcpress=$1 klipper=$2 corpus=$3
[ -f "$klipper/klippy/extras/gcode_arcs.py" ] || { echo "klipper_executed: no Klipper source at '$klipper'" >&2; exit 2; }
here=$(dirname "$0")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0
printf '%-46s %6s %6s %13s %13s  %s\n' program band arcs "Klipper's G1" "deviation mm" verdict
for f in "$corpus"/*/*; do
  case $f in *.md) continue ;; esac
  name=$(basename "$f")
  # The input's own arcs are cut by Klipper too: the two paths the printer moves along are
  # compared. A program with arcs Klipper refuses (R, or G91) is for another controller.
  python3 "$here/klipper_executed.py" "$klipper" "$f" > "$work/input.gcode" 2> /dev/null || continue
  # (and one arcpress diff cannot compare with itself: NURBS blocks, G5.2)
  "$arcpress" diff "$work/input.gcode" "$work/input.gcode" --dialect klipper > /dev/null 2>&1 || continue
  for band in 0.05 0.025 0.01; do
    "$arcpress" "$f" -o "$work/out.gcode" --dialect klipper --tolerance "$band" --stats 2> "$work/stats.txt" ||
      { echo "FAIL: $name at $band: arcpress exit $?: $(tail -2 "$work/stats.txt")"; status=1; continue; }
    arcs=$(sed -n 's/^  written *[0-9]* G1 + \([0-9]*\) G2\/G3.*/\1/p' "$work/stats.txt")
    python3 "$here/klipper_executed.py" "$klipper" "$work/out.gcode" > "$work/executed.gcode" ||
      { echo "FAIL: $name at $band: Klipper's arc code refused an arc"; status=1; continue; }
    moves=$(($(grep -c . "$work/executed.gcode") - $(grep -c . "$work/out.gcode") + arcs))
    verdict=SAME
    "$arcpress" diff "$work/input.gcode" "$work/executed.gcode" --tolerance "$band" --dialect klipper > "$work/diff.txt" 2>&1 ||
      { verdict=$(grep -E '^(DIFFERENT|INCOMPLETE)' "$work/diff.txt" || echo "exit $?"); status=1; }
    deviation=$(sed -n 's/^max deviation \([0-9.]*\) mm.*/\1/p' "$work/diff.txt")
    printf '%-46s %6s %6s %13s %13s  %s\n' "$name" "$band" "$arcs" "$moves" "${deviation:--}" "$verdict"
  done
done
exit $status
