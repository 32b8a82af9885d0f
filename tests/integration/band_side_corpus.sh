#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The corpus at 0.01 mm with each one-sided band (on the programmed path, --band program,
# as a printer's firmware chords would cross): every output written, and
# `arcpress diff --band-side` agrees (the same verdict as the plain diff, never DIFFERENT);
# prints the blocks each side costs against both (scripts/docs_figures.sh band-side puts that
# table in docs/fitting.md).
#   band_side_corpus.sh ARCPRESS CORPUS_DIR
set -euo pipefail
arcpress=$1 corpus=$2
[ -d "$corpus/cnc" ] || { echo "no corpus: skipped"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
blocks() { sed -n 's/^  written *\([0-9]*\) G1 + \([0-9]*\) G2\/G3.*/\1 \2/p' "$1" | awk '{print $1 + $2}'; }
printf '%-45s %8s %8s %8s\n' file both left right
for f in "$corpus"/cnc/* "$corpus"/laser/* "$corpus"/printer/*; do
  case $f in *.md) continue ;; esac
  row=$(basename "$f")
  for side in both left right; do
    "$arcpress" "$f" -o "$work/$side.nc" --tolerance 0.01 --band program --band-side "$side" --stats 2> "$work/stats.txt" ||
      fail "$row --band-side $side: exit $?: $(tail -3 "$work/stats.txt")"
    row="$row $(blocks "$work/stats.txt")"
    [ "$side" = both ] && continue
    plain=0; "$arcpress" diff "$f" "$work/$side.nc" --tolerance 0.01 > /dev/null 2>&1 || plain=$?
    sided=0; "$arcpress" diff "$f" "$work/$side.nc" --tolerance 0.01 --band-side "$side" > "$work/diff.txt" 2>&1 || sided=$?
    [ "$sided" != 1 ] || fail "$(basename "$f") --band-side $side: DIFFERENT: $(grep 'band side' "$work/diff.txt")"
    [ "$sided" = "$plain" ] || fail "$(basename "$f") --band-side $side: exit $sided, the plain diff $plain"
  done
  printf '%-45s %8s %8s %8s\n' $row
done
