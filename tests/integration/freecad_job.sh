#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# postproc/freecad/arcpress_post.py inside Debian's FreeCAD (freecadcmd): a small Path job
# posted with it (freecad_job.py) holds arcs and `arcpress diff` finds it the same as the
# job posted by linuxcnc_post alone. Skipped (exit 77) where freecadcmd is not installed.
#   freecad_job.sh ARCPRESS SOURCE_DIR
set -euo pipefail
arcpress=$(realpath "$1") source=$(cd "$2" && pwd)
if ! command -v freecadcmd >/dev/null; then
  echo "freecadcmd is not installed: skipped"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export ARCPRESS=$arcpress POST_DIR=$source/postproc/freecad PLAIN=$work/plain.ngc OUT=$work/arcs.ngc RESULT=$work/result
(cd "$work" && HOME=$work timeout 600 freecadcmd "$source/tests/integration/freecad_job.py" >"$work/freecad.log" 2>&1) || true
if [ ! -f "$RESULT" ] || ! grep -q '^ok' "$RESULT"; then
  cat "$RESULT" 2>/dev/null || tail -20 "$work/freecad.log"
  exit 1
fi
cat "$RESULT"; echo
grep -q '^ok [1-9]' "$RESULT"
"$arcpress" diff "$PLAIN" "$OUT" --dialect linuxcnc | tail -1
"$arcpress" diff "$PLAIN" "$OUT" --dialect linuxcnc | tail -1 | grep -q '^SAME'
