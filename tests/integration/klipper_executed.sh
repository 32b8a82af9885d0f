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
. "$here/executed_runs.sh"
executed_runs "$arcpress" "$corpus" klipper Klipper python3 "$here/klipper_executed.py" "$klipper"
