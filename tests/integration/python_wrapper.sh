#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The Python example's failures: a file error is exit 3 with a message (never a traceback,
# never 1, which means the check failed), and it leaves nothing behind and overwrites nothing;
# and a program that jumps and calls, read ahead as the command reads it.
#   python_wrapper.sh LIBRARY SOURCE_DIR PROGRAM ARCPRESS
set -uo pipefail
lib=$(realpath "$1") source=$(realpath "$2") program=$(realpath "$3") arcpress=$(realpath "$4")
work=$(mktemp -d)
trap 'umount "$work/small" 2>/dev/null; rm -rf "$work"' EXIT
py() { python3 "$source/postproc/python/arcpress_compress.py" "$@" --library "$lib"; }
fail=0
expect() {  # expected-exit what command...
  local want=$1 what=$2; shift 2
  "$@" > "$work/out.txt" 2> "$work/err.txt"; local got=$?
  if [ "$got" != "$want" ]; then echo "FAIL $what: exit $got, wanted $want"; cat "$work/err.txt"; fail=1; fi
  if grep -q Traceback "$work/err.txt"; then echo "FAIL $what: a traceback"; cat "$work/err.txt"; fail=1; fi
}
expect 3 "a missing input" py "$work/no-such.nc" "$work/o.nc"
grep -q "no-such.nc" "$work/err.txt" || { echo "FAIL: the missing file is not named"; fail=1; }
expect 3 "an output folder that is not there" py "$program" "$work/nowhere/o.nc"
mkdir "$work/here" && cd "$work/here"
expect 3 "a folder as the output" py "$program" .
[ -z "$(ls -A "$work/here")" ] || { echo "FAIL: the folder output left $(ls -A)"; fail=1; }
# An existing OUT.partial is someone's file: never touched.
echo mine > "$work/o.nc.partial"
expect 0 "a good run" py "$program" "$work/o.nc"
[ "$(cat "$work/o.nc.partial")" = mine ] || { echo "FAIL: o.nc.partial was overwritten"; fail=1; }
ls "$work" | grep -q '^o\.nc\..*\.partial$' && { echo "FAIL: a temporary was left"; fail=1; }
# A file that is not G-code: bad input, and the old output is kept.
echo kept > "$work/keep.nc"
head -c 4000 /dev/urandom > "$work/noise.bin"
expect 2 "a file that is not G-code" py "$work/noise.bin" "$work/keep.nc"
[ "$(cat "$work/keep.nc")" = kept ] || { echo "FAIL: the output was clobbered"; fail=1; }
[ "$(ls "$work" | grep -c partial)" = 1 ] || { echo "FAIL: a temporary was left: $(ls "$work")"; fail=1; }
# A full disk: a 16 KiB file system (where this machine lets us mount one), and an output
# larger than it.
if mkdir "$work/small" && mount -t tmpfs -o size=16k tmpfs "$work/small" 2>/dev/null; then
  python3 -c "print('G21 G90\nG0 X0 Y0\nG1 F100\n' + ''.join('G1 X%d Y%d ; step %d\n' % (k, k % 2, k) for k in range(3000)))" \
    > "$work/long.nc"
  expect 3 "a full disk" py "$work/long.nc" "$work/small/out.nc"
  grep -q "No space left" "$work/err.txt" || { echo "FAIL: the full disk is not said"; fail=1; }
  [ -z "$(ls -A "$work/small")" ] || { echo "FAIL: the full disk kept $(ls -A "$work/small")"; fail=1; }
  umount "$work/small"
else
  echo "python wrapper: no small file system could be mounted here: the full disk is not tried"
fi
# A Fanuc program whose subprogram after M30 returns in G90 (the quarter circle after its call
# is one arc), and a loop back in G18 to a block the quarter starts at (its moves are written
# as they are, with a warning): the wrapper reads both ahead, as the command does.
python3 -c "
import math
q = ''.join('X%.4f Y%.4f\\n' % (20 * math.cos(math.pi * i / 60) - 20, 20 * math.sin(math.pi * i / 60)) for i in range(1, 31))
print('G90 G17 G21\\nG0 X0 Y0 Z0\\nG1 F300\\nM98 P2000\\n' + q + 'N10 G90 G1 X0 Y0\\n' + q + 'G18\\nIF [#1 LT 3] GOTO 10\\nM30\\nO2000\\nG91 G1 X1.\\nG90\\nM99', end='')
" > "$work/jumps.nc"
expect 0 "a program that jumps and calls" py "$work/jumps.nc" "$work/py-jumps.nc" --dialect fanuc
grep -q W-FLOW-LOOP-MODES "$work/err.txt" || { echo "FAIL: the loop back in G18 is not told"; cat "$work/err.txt"; fail=1; }
"$arcpress" "$work/jumps.nc" -o "$work/cli-jumps.nc" --dialect fanuc 2> /dev/null
cmp -s "$work/py-jumps.nc" "$work/cli-jumps.nc" || { echo "FAIL: the wrapper wrote otherwise than the command"; fail=1; }
[ "$(grep -c '^G3' "$work/py-jumps.nc")" = 1 ] || { echo "FAIL: not one arc after the call"; cat "$work/py-jumps.nc"; fail=1; }
[ $fail = 0 ] && echo "python wrapper: every failure said, nothing left behind, a program that jumps read as the command reads it"
exit $fail
