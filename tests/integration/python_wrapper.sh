#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The Python example's failures: a file error is exit 3 with a message (never a traceback,
# never 1, which means the check failed), and it leaves nothing behind and overwrites nothing.
#   python_wrapper.sh LIBRARY SOURCE_DIR PROGRAM
set -uo pipefail
lib=$(realpath "$1") source=$(realpath "$2") program=$(realpath "$3")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
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
[ $fail = 0 ] && echo "python wrapper: every failure said, nothing left behind"
exit $fail
