#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# PrusaSlicer runs arcpress as its post-processing script, as postproc/README.md tells users
# to set it up: a cylinder is sliced for a Marlin 2 printer with two scripts, the first
# keeping a copy of the G-code as the slicer wrote it, the second `arcpress --in-place`. The
# sliced file must then hold arcs, arcpress must have picked the marlin dialect from the
# file's own config block, and `arcpress diff` must find it the same as the copy.
# Skipped (exit 77) where prusa-slicer is not installed.
#   prusaslicer.sh ARCPRESS
set -euo pipefail
arcpress=$1
if ! command -v prusa-slicer >/dev/null; then
  echo "prusa-slicer is not installed: skipped"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# A cylinder, 20 mm across and 4 mm high, as 128 facets around.
python3 - "$work/cylinder.stl" <<'PY'
import math, sys
n, r, h = 128, 10.0, 4.0
def v(a, z): return (r * math.cos(a), r * math.sin(a), z)
with open(sys.argv[1], "w") as f:
    f.write("solid cylinder\n")
    for k in range(n):
        a0, a1 = 2 * math.pi * k / n, 2 * math.pi * (k + 1) / n
        p0, p1, q0, q1 = v(a0, 0), v(a1, 0), v(a0, h), v(a1, h)
        for t in ((p0, p1, q1), (p0, q1, q0), ((0, 0, 0), p1, p0), ((0, 0, h), q0, q1)):
            f.write(" facet normal 0 0 0\n  outer loop\n")
            for p in t: f.write("   vertex %f %f %f\n" % p)
            f.write("  endloop\n endfacet\n")
    f.write("endsolid cylinder\n")
PY
printf '#!/bin/sh\ncp "$1" "%s/before.gcode"\n' "$work" > "$work/keep_copy.sh"
chmod +x "$work/keep_copy.sh"
# The line a user pastes into Print Settings > Output options > Post-processing scripts.
line="$arcpress --in-place --quiet"
prusa-slicer --export-gcode --center 100,100 --gcode-flavor marlin2 \
  --post-process "$work/keep_copy.sh;$line" "$work/cylinder.stl" -o "$work/out.gcode" >"$work/slicer.log" 2>&1 ||
  { cat "$work/slicer.log"; exit 1; }
test -s "$work/before.gcode"
arcs=$(grep -c '^G[23] ' "$work/out.gcode" || true)
echo "arcs in the sliced file: $arcs"
test "$arcs" -gt 0
# (Read whole before grep -q: it stops at its first match, and the writer then meets a closed pipe.)
"$arcpress" "$work/before.gcode" -o /dev/null --stats 2>"$work/stats.txt"
grep -E "^  (dialect|written|deviation) " "$work/stats.txt"
grep -q "dialect        marlin .*gcode_flavor = marlin2" "$work/stats.txt"
status=0
"$arcpress" diff "$work/before.gcode" "$work/out.gcode" >"$work/diff.txt" 2>&1 || status=$?
tail -1 "$work/diff.txt"
if [ "$status" -ne 0 ] || ! tail -1 "$work/diff.txt" | grep -q '^SAME'; then
  echo "arcpress diff exited $status:"
  cat "$work/diff.txt"
  exit 1
fi
