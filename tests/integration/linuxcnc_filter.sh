#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The LinuxCNC program filter (postproc/linuxcnc), installed into copies of LinuxCNC's own
# sample machines (an inch one and a mm one) and run as AXIS runs a filter: the command
# found in the INI file by LinuxCNC's own INI reader, run by AXIS's own filter_program()
# (taken from /usr/bin/axis), its progress read by AXIS's pattern. The program it loads holds
# arcs where the machine's units allow them, `arcpress diff` finds it the same as the file,
# LinuxCNC's interpreter (rs274) runs it, and a failure loads the program as it was (or,
# with --strict, nothing).
#   linuxcnc_filter.sh ARCPRESS SOURCE_DIR
set -uo pipefail
arcpress=$(realpath "$1") source=$(realpath "$2")
samples=/usr/share/doc/linuxcnc/examples/sample-configs/sim/axis
if [ ! -x /usr/bin/axis ] || ! command -v rs274 >/dev/null || [ ! -f "$samples/axis.ini" ] ||
   ! /usr/bin/python3 -c "import linuxcnc" 2>/dev/null; then
  echo "SKIP: LinuxCNC (linuxcnc-uspace) is not installed"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail=0
no() { echo "FAIL: $*"; fail=1; }

cp "$samples/axis.ini" "$work/inch.ini"
cp "$samples/axis_mm.ini" "$work/mm.ini"
grep -q "^LINEAR_UNITS *= *inch" "$work/inch.ini" && grep -q "^LINEAR_UNITS *= *mm" "$work/mm.ini" ||
  no "the sample machines are not an inch one and a mm one"
bash "$source/postproc/linuxcnc/install.sh" --bin "$work/bin" --options "--arcpress $arcpress --tolerance 0.01" \
  "$work/inch.ini" "$work/mm.ini" > "$work/install.txt" || no "install.sh failed: $(cat "$work/install.txt")"
# Installed twice: nothing is added again, and the other filters stay.
cp "$work/inch.ini" "$work/inch.once"
bash "$source/postproc/linuxcnc/install.sh" --bin "$work/bin" --options "--arcpress $arcpress --tolerance 0.01" \
  "$work/inch.ini" > /dev/null || no "install.sh failed the second time"
cmp -s "$work/inch.ini" "$work/inch.once" || no "a second install changed the INI file"
grep -q "^py = python" "$work/inch.ini" || no "the sample's own filters are gone"
cmp -s "$work/inch.ini.arcpress-backup" "$samples/axis.ini" || no "the backup is not the INI file as it was"

# A circle of 1 inch radius in 48 moves that never states its units: 0.054 mm from its
# chords, so arcs only where the machine reads millimetres.
python3 - "$work/circle.ngc" <<'EOF'
import math, sys
lines = ["(a circle in the machine's units)", "G90 G17 G0 X1 Y0 Z0.1", "G1 Z-0.01 F20"]
lines += ["G1 X%.4f Y%.4f" % (math.cos(k * math.pi / 24), math.sin(k * math.pi / 24)) for k in range(1, 49)]
open(sys.argv[1], "w").write("\n".join(lines + ["G0 Z0.1", "M2"]) + "\n")
EOF
# A spiral of 200 000 moves (5 MB), over the size from which arcpress shows its progress.
python3 - "$work/spiral.ngc" <<'EOF'
import math, sys
out = ["G21 G90 G17", "G0 X10 Y0 Z1", "G1 Z-1 F800"]
for k in range(1, 200001):
    a = k * 2 * math.pi / 360
    r = 10 + 0.001 * k
    out.append("G1 X%.4f Y%.4f" % (r * math.cos(a), r * math.sin(a)))
open(sys.argv[1], "w").write("\n".join(out + ["G0 Z5", "M2"]) + "\n")
EOF

# AXIS's way: the filter for the extension from the INI file, run by filter_program().
axis_filter() {  # INI PROGRAM OUT -> prints "exit CODE", then "progress N" lines
  INI_FILE_NAME=$1 /usr/bin/python3 - "$1" "$2" "$3" <<'EOF'
import ast, os, re, select, sys
import linuxcnc
ini, program, out = sys.argv[1:]
tree = ast.parse(open("/usr/bin/axis").read())
wanted = [n for n in tree.body
          if (isinstance(n, ast.FunctionDef) and n.name == "filter_program")
          or (isinstance(n, ast.Assign) and any(getattr(t, "id", "") == "progress_re" for t in n.targets))]
assert len(wanted) == 2, "AXIS's filter_program or progress_re not found"
seen = []
class Progress:
    def __init__(self, phases, total): pass
    def set_text(self, text): pass
    def update(self, count, *rest): seen.append(count)
    def done(self): pass
class Widget:
    def update(self): pass
space = {"os": os, "re": re, "select": select, "sys": sys, "Progress": Progress, "t": Widget(), "_": lambda s: s}
exec(compile(ast.Module(body=wanted, type_ignores=[]), "/usr/bin/axis", "exec"), space)
ext = os.path.splitext(program)[1][1:]
command = linuxcnc.ini(ini).find("FILTER", ext)
assert command and "arcpress-linuxcnc-filter" in command, command
code, stderr = space["filter_program"](command, program, out)
print("exit", code)
for n in seen: print("progress", n)
sys.stderr.write(stderr)
EOF
}

for machine in inch mm; do
  axis_filter "$work/$machine.ini" "$work/circle.ngc" "$work/circle.$machine.ngc" > "$work/run.txt" 2> "$work/err.txt"
  grep -q "^exit 0$" "$work/run.txt" || no "$machine machine: the filter failed: $(cat "$work/run.txt" "$work/err.txt")"
  grep -q "W-MODEL-UNITS" "$work/err.txt" && no "$machine machine: the units were not taken from its INI file"
  "$arcpress" diff "$work/circle.ngc" "$work/circle.$machine.ngc" --dialect linuxcnc --units $machine \
    --tolerance 0.01 > "$work/diff.txt" 2>&1 || no "$machine machine: diff: $(cat "$work/diff.txt")"
  (cd "$work" && HOME=$work rs274 -i "$work/$machine.ini" -g "circle.$machine.ngc" > rs274.txt 2>&1) ||
    no "$machine machine: rs274 refused the filtered program: $(tail -3 "$work/rs274.txt")"
done
grep -q "^G[23] " "$work/circle.mm.ngc" || no "the mm machine's circle holds no arcs"
grep -q "^G[23] " "$work/circle.inch.ngc" && no "the inch machine's circle holds arcs: its units were read as mm"
# An inch machine whose startup code says G21 starts in mm (a comment saying G20 says nothing).
sed 's/^\[RS274NGC\]/[RS274NGC]\nRS274NGC_STARTUP_CODE = G17 G21 (not G20) G40 G90/' "$work/inch.ini" > "$work/startup.ini"
axis_filter "$work/startup.ini" "$work/circle.ngc" "$work/circle.startup.ngc" > "$work/run.txt" 2> "$work/err.txt"
grep -q "^G[23] " "$work/circle.startup.ngc" || no "the startup code's G21 was not taken: $(cat "$work/err.txt")"

# A large program: arcs, the same path, and AXIS's progress bar from 0 to 100 through
# arcpress's own progress.
axis_filter "$work/mm.ini" "$work/spiral.ngc" "$work/spiral.out.ngc" > "$work/run.txt" 2> "$work/err.txt"
grep -q "^exit 0$" "$work/run.txt" || no "spiral: the filter failed: $(cat "$work/run.txt" "$work/err.txt")"
grep -q "^G[23] " "$work/spiral.out.ngc" || no "spiral: no arcs"
"$arcpress" diff "$work/spiral.ngc" "$work/spiral.out.ngc" --dialect linuxcnc --tolerance 0.01 > "$work/diff.txt" 2>&1 ||
  no "spiral: diff: $(cat "$work/diff.txt")"
progress=$(awk '$1 == "progress" {print $2}' "$work/run.txt" | tr '\n' ' ')
[ "$(awk '$1 == "progress" {print $2; exit}' "$work/run.txt")" = 0 ] || no "spiral: progress does not start at 0: $progress"
[ "$(awk '$1 == "progress" {p = $2} END {print p}' "$work/run.txt")" = 100 ] || no "spiral: progress does not end at 100: $progress"
awk '$1 == "progress" && $2 > 0 && $2 < 100 {found = 1} END {exit !found}' "$work/run.txt" ||
  no "spiral: no progress between 0 and 100: $progress"
awk '$1 == "progress" {if ($2 < last) exit 1; last = $2}' "$work/run.txt" || no "spiral: progress went back: $progress"
grep -q "FILTER_PROGRESS\|MB/s" "$work/err.txt" && no "spiral: progress lines reached the error text"

# A file that is not G-code: loaded as it was, with why on standard error; with --strict,
# the load fails with the message.
head -c 3000 /dev/urandom > "$work/noise.ngc"
axis_filter "$work/mm.ini" "$work/noise.ngc" "$work/noise.out" > "$work/run.txt" 2> "$work/err.txt"
grep -q "^exit 0$" "$work/run.txt" || no "noise: not loaded as it was: $(cat "$work/run.txt")"
cmp -s "$work/noise.ngc" "$work/noise.out" || no "noise: what was loaded is not the file"
grep -q "loaded as it was" "$work/err.txt" || no "noise: no word of why: $(cat "$work/err.txt")"
sed -i 's|arcpress-linuxcnc-filter --arcpress|arcpress-linuxcnc-filter --strict --arcpress|' "$work/mm.ini"
axis_filter "$work/mm.ini" "$work/noise.ngc" "$work/noise.out" > "$work/run.txt" 2> "$work/err.txt"
grep -q "^exit 2$" "$work/run.txt" || no "noise, --strict: the load did not fail with arcpress's exit 2: $(cat "$work/run.txt")"
grep -q "E-INPUT-NOT-GCODE" "$work/err.txt" || no "noise, --strict: arcpress's message is not in the dialog's text"
# No arcpress to run: as it was, or with --strict a failure.
sed -i "s|--arcpress $arcpress|--arcpress $work/no-such-arcpress|" "$work/mm.ini" "$work/inch.ini"
axis_filter "$work/mm.ini" "$work/circle.ngc" "$work/gone.out" > "$work/run.txt" 2> "$work/err.txt"
grep -q "^exit 127$" "$work/run.txt" || no "no arcpress, --strict: $(cat "$work/run.txt")"
axis_filter "$work/inch.ini" "$work/circle.ngc" "$work/gone.out" > "$work/run.txt" 2> "$work/err.txt"
grep -q "^exit 0$" "$work/run.txt" && cmp -s "$work/circle.ngc" "$work/gone.out" ||
  no "no arcpress: the program was not loaded as it was: $(cat "$work/run.txt" "$work/err.txt")"
grep -q "cannot run" "$work/err.txt" || no "no arcpress: no word of why"
exit $fail
