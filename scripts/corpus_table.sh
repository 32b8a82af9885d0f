#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Prints, for every file of the development corpus, how many G1 moves it has, how many were
# fitted (in runs), the blocks written for them, the measured deviation, and the peak block
# rate over any 1 s of cutting at the programmed feeds, in and out: one Markdown table, by
# `arcpress --stats` at the given tolerance.
#   scripts/corpus_table.sh [TOLERANCE_MM] [ARCPRESS] [CORPUS_DIR] [OPTIONS...]
# OPTIONS are passed to every run (e.g. --dialect rs274 to read printer files as RS274
# rather than as the firmware their flavor line names).
set -euo pipefail
cd "$(dirname "$0")/.."
tol="${1:-0.01}"
exe="${2:-./build/arcpress}"
corpus="${3:-../shared/corpus}"
shift $(( $# < 3 ? $# : 3 ))
extra=("$@")
out="$(mktemp)"
trap 'rm -f "$out"' EXIT
echo "| file | G1 moves in | in runs | blocks out for them | of which G2/G3 | max deviation mm | peak blocks/s in → out |"
echo "|---|---|---|---|---|---|---|"
for f in "$corpus"/*/*.*; do
  case "$f" in *.md) continue ;; esac
  stats="$("$exe" "$f" -o "$out" --tolerance "$tol" --stats "${extra[@]}" 2>&1 >/dev/null || true)"
  g1="$(sed -n 's/^  G1 moves *\([0-9]*\) in the input, \([0-9]*\) in.*/\1 \2/p' <<<"$stats")"
  written="$(sed -n 's/^  written *\([0-9]*\) G1 + \([0-9]*\) G2\/G3.*/\1 \2/p' <<<"$stats")"
  dev="$(sed -n 's/^  deviation *\([0-9.]*\) mm max.*/\1/p' <<<"$stats")"
  rate_in="$(sed -n 's/^ *in: *peak \([0-9]*\) blocks.*/\1/p' <<<"$stats")"
  rate_out="$(sed -n 's/^ *out: *peak \([0-9]*\) blocks.*/\1/p' <<<"$stats")"
  read -r moves fitted <<<"${g1:-? ?}"
  read -r lines arcs <<<"${written:-? ?}"
  blocks="?"; [ "$lines" != "?" ] && blocks=$((lines + arcs))
  echo "| $(basename "$f") | $moves | $fitted | $blocks | $arcs | ${dev:-failed} | ${rate_in:-?} → ${rate_out:-?} |"
done
