#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# postproc/freecad/arcpress_post.py called as FreeCAD calls a post processor,
# export(objectslist, filename, argstring), with linuxcnc_post stood in for by a stub that
# posts a CNC program (FreeCAD itself is not installed here): the file it leaves holds arcs
# and `arcpress diff` finds it the same as the posted program; through "-" the text comes
# back compressed; a failing arcpress leaves the posted file as it was and raises.
#   freecad_post.sh ARCPRESS SOURCE_DIR PROGRAM
set -euo pipefail
arcpress=$1 source=$2 program=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export STUB_PROGRAM=$program ARCPRESS=$arcpress
export PYTHONPATH="$source/tests/integration/freecad_stub:$source/postproc/freecad"
python3 - "$work" <<'PY'
import os, subprocess, sys
import arcpress_post
work = sys.argv[1]
out = os.path.join(work, "job.ngc")
text = arcpress_post.export([], out, "--tolerance 0.01 --no-show-editor")
assert text == open(out).read(), "export returns what it wrote"
assert any(line.startswith(("G2 ", "G3 ")) for line in text.splitlines()), "the posted job holds arcs"
diff = subprocess.run([os.environ["ARCPRESS"], "diff", os.environ["STUB_PROGRAM"], out], capture_output=True, text=True)
assert diff.returncode == 0 and diff.stdout.splitlines()[-1].startswith("SAME"), diff.stdout
piped = arcpress_post.export([], "-", "")
assert piped == text, "through '-' the same text"
# A failure: the posted file stays as linuxcnc_post wrote it, and FreeCAD is told.
try:
    arcpress_post.export([], out, "--tolerance -1")
    raise SystemExit("a failing arcpress must raise")
except RuntimeError as e:
    assert "exit 2" in str(e), e
assert open(out).read() == open(os.environ["STUB_PROGRAM"]).read()
print("arcpress_post: arcs written, SAME as the posted program; failures raise and keep the posted file")
PY
