#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Many programs at once (arcpress FILES --in-place, arcpress DIR -o OUTDIR): every program is
# written as one run of its own would write it, a bad one in the middle is named, left
# untouched and costs only itself, names with spaces survive, and the summary says so.
#   batch.sh ARCPRESS SOURCE_DIR CORPUS_DIR
set -euo pipefail
arcpress=$(realpath "$1") source=$2 corpus=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
in="$work/jobs"
mkdir -p "$in/sub dir/deeper" "$in/other"
cp "$source/samples/contour.nc" "$in/a contour.nc"
for f in ps_benchy_snippet_m83.gcode pycam-0.5.1_ShapeOko_Calibration_Pattern.ngc; do
  [ -f "$corpus/printer/$f" ] && cp "$corpus/printer/$f" "$in/sub dir/$f"
  [ -f "$corpus/cnc/$f" ] && cp "$corpus/cnc/$f" "$in/sub dir/deeper/$f"
done
sed 's/X/x/' "$source/samples/contour.nc" > "$in/sub dir/deeper/lower case.ngc"
# The bad one, in the middle of the order: not G-code at all.
head -c 20000 /dev/urandom > "$in/other/m broken.gcode"
echo "not a program" > "$in/notes.md"  # no G-code extension: not taken
echo "not a program" > "$in/other/readme.txt"  # nor .txt, which notes have too
chmod -R u+w "$in"
cp -r "$in" "$work/pristine"

# A folder into another folder.
rc=0
"$arcpress" "$in" -o "$work/out" -j 2 > "$work/summary.txt" 2> "$work/err.txt" || rc=$?
cat "$work/summary.txt"
[ "$rc" = 2 ] || fail "exit $rc with one unreadable program (want 2)"
grep -q "m broken.gcode: cannot be read, not written" "$work/err.txt" || fail "the bad program is not named: $(cat "$work/err.txt")"
[ ! -e "$work/out/other/m broken.gcode" ] || fail "the bad program's destination was written"
[ ! -e "$work/out/notes.md" ] && [ ! -e "$work/out/other/readme.txt" ] || fail "a file without a G-code extension was taken"
n=0
while IFS= read -r -d '' f; do
  rel=${f#"$in"/}
  [ "$rel" = "other/m broken.gcode" ] || [ "$rel" = notes.md ] || [ "$rel" = other/readme.txt ] && continue
  "$arcpress" "$f" -o "$work/one.out"
  cmp "$work/one.out" "$work/out/$rel" || fail "$rel: not the bytes of a run of its own"
  grep -qF "$f" "$work/summary.txt" || fail "$rel is not in the summary"
  n=$((n + 1))
done < <(find "$in" -type f -print0)
[ "$n" -ge 2 ] || fail "only $n programs compared"
grep -q "$n of $((n + 1)) programs written" "$work/summary.txt" || fail "the summary's count"
diff -r "$work/pristine" "$in" > /dev/null || fail "an input changed"

# The same files in place, named one by one, with --json: the bad one untouched.
rc=0
(cd "$in" && find . -type f -name '*.*' ! -name '*.md' ! -name '*.txt' -print0 | xargs -0 "$arcpress" --in-place -j 2 --json) \
  > "$work/summary.json" 2> "$work/err.txt" || rc=$?
[ "$rc" = 123 ] || [ "$rc" = 2 ] || fail "in place: exit $rc (want 2, through xargs 123)"
python3 - "$work/summary.json" <<'PY' || fail "the JSON summary"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["exit_code"] == 2, s["exit_code"]
bad = [f for f in s["files"] if not f["written"]]
assert len(bad) == 1 and bad[0]["input"].endswith("m broken.gcode") and bad[0]["exit_code"] == 2, bad
assert all(f["bytes_out"] > 0 and f["max_deviation_mm"] is not None for f in s["files"] if f["written"])
PY
cmp "$work/pristine/other/m broken.gcode" "$in/other/m broken.gcode" || fail "the bad program was changed in place"
for rel in "a contour.nc" "sub dir/deeper/lower case.ngc"; do
  "$arcpress" "$work/pristine/$rel" -o "$work/one.out"
  cmp "$work/one.out" "$in/$rel" || fail "$rel in place: not the bytes of a run of its own"
done
[ -z "$(find "$in" -name '*.arcpress-*')" ] || fail "a temporary file was left"

# --glob picks a folder's files by name; a file for -o with several programs is refused.
"$arcpress" "$work/pristine" --glob '*case*' -o "$work/globbed" > "$work/summary.txt"
[ "$(find "$work/globbed" -type f | wc -l)" = 1 ] || fail "--glob '*case*' took $(find "$work/globbed" -type f)"
rc=0; "$arcpress" "$work/pristine/a contour.nc" "$work/pristine/a contour.nc" --in-place 2> "$work/err.txt" || rc=$?
[ "$rc" = 2 ] && grep -q 'would both be written' "$work/err.txt" || fail "the same program twice: exit $rc"
rc=0; "$arcpress" "$work/pristine" -o "$work/pristine/a contour.nc" 2> "$work/err.txt" || rc=$?
[ "$rc" = 2 ] && grep -q 'is a file' "$work/err.txt" || fail "-o naming a file for a folder: exit $rc"
rc=0; "$arcpress" "$work/pristine" 2> "$work/err.txt" || rc=$?
[ "$rc" = 2 ] && grep -q -- '--in-place or -o FOLDER' "$work/err.txt" || fail "a folder without -o: exit $rc"
# Interrupted while two programs are being written at once: no temporary file is left of
# either, and the program ends as the signal ends it.
mkdir -p "$work/big" "$work/bigout"
big="$corpus/printer/prusaslicer-2.5_bunny_marlin.gcode"
[ -f "$big" ] || { for _ in $(seq 1500); do cat "$source/samples/contour.nc"; done > "$work/one.nc"; big="$work/one.nc"; }
for k in 1 2 3 4; do cp "$big" "$work/big/part $k.gcode"; done
"$arcpress" "$work/big" -o "$work/bigout" -j 2 -q > /dev/null 2>&1 &
runner=$!
for _ in $(seq 200); do [ -n "$(find "$work/bigout" -name '*.arcpress-*')" ] && break; sleep 0.05; done
[ -n "$(find "$work/bigout" -name '*.arcpress-*')" ] || fail "no temporary file appeared"
kill -INT "$runner"
rc=0; wait "$runner" || rc=$?
[ "$rc" = 130 ] || fail "exit $rc after SIGINT (want 130)"
[ -z "$(find "$work/bigout" -name '*.arcpress-*')" ] || fail "SIGINT left temporary files: $(find "$work/bigout" -name '*.arcpress-*')"
echo "$n programs written as runs of their own would write them; the bad one named and left as it was; SIGINT left no temporary"
