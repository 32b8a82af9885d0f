#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Rewrites the tables of figures in the README and docs/ from the program and the benches,
# so that none goes stale: each table sits between `<!-- figures: NAME -->` and
# `<!-- /figures -->` and is replaced whole by what its command prints now.
#   scripts/docs_figures.sh [NAME...]     (default: every table; needs `scripts/build.sh --test`)
# Tables: corpus (README: scripts/corpus_table.sh 0.01), throughput and stages
# (docs/streaming.md: bench_throughput, bench_throughput --stages), memory (docs/streaming.md: bench_memory, about a minute), and the
# benches' own output in docs/benchmarks.md: curves (bench_curves 1, about a minute), diff
# (bench_diff), pathological (bench_pathological); printers and printer-causes in
# docs/printers.md (bench_printers, about a minute); band-side in docs/fitting.md (the corpus
# with each one-sided band, tests/integration/band_side_corpus.sh); vs-arcwelder and
# vs-arcwelder-instructions in docs/benchmarks.md (bench_vs_arcwelder, and with
# --instructions under valgrind, a few minutes), and printers-vs-arcwelder in
# docs/printers.md (bench_vs_arcwelder --printers, about a minute): with ARCWELDER set to
# the path of ArcWelder's console program, built from its source in a folder of your own;
# grbl, klipper, marlin, prusa, prusa-mk3 and smoothieware in docs/dialects.md (tests/integration/grbl_accepts.sh,
# klipper_executed.sh and marlin_executed.sh, a minute each): with GRBL_VALIDATOR set to
# grbl-sim's validator, built likewise (and GRBL_TRACE to it linked with
# tests/integration/grbl_trace.c, for the paths Grbl plans), KLIPPER_SOURCE to a clone of
# Klipper, MARLIN_SOURCE to one of Marlin, BUDDY_SOURCE to one of Prusa-Firmware-Buddy,
# MK3_SOURCE to one of Prusa-Firmware and SMOOTHIEWARE_SOURCE to one of Smoothieware.
# None is among the defaults.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/bench/bench_throughput ] || { echo "docs_figures: build with 'bash scripts/build.sh --test' first" >&2; exit 2; }

# replace FILE NAME: the table named NAME in FILE becomes standard input.
replace() {
  python3 -c "$replacer" "$1" "$2"
}
replacer=$(cat <<'PY'
import re, sys
path, name = sys.argv[1], sys.argv[2]
table = sys.stdin.read().rstrip("\n")
text = open(path).read()
pattern = re.compile(r"(<!-- figures: %s -->\n).*?(<!-- /figures -->)" % re.escape(name), re.S)
if not pattern.search(text):
    sys.exit("docs_figures: no table '%s' in %s" % (name, path))
open(path, "w").write(pattern.sub(lambda m: m.group(1) + table + "\n" + m.group(2), text, count=1))
print("docs_figures: %s in %s" % (name, path))
PY
)

wanted=("$@")
[ ${#wanted[@]} -eq 0 ] && wanted=(corpus throughput stages memory curves diff pathological printers printer-causes band-side)
# A bench's own output, as a block of text.
as_text() { printf '```text\n%s\n```\n' "$(cat)"; }
for name in "${wanted[@]}"; do
  case $name in
    corpus) bash scripts/corpus_table.sh 0.01 | replace README.md corpus ;;
    throughput) ./build/bench/bench_throughput --markdown | replace docs/streaming.md throughput ;;
    stages) ./build/bench/bench_throughput --markdown --stages | replace docs/streaming.md stages ;;
    memory)
      out=$(./build/bench/bench_memory --markdown) || { echo "$out" >&2; echo "docs_figures: bench_memory failed" >&2; exit 1; }
      replace docs/streaming.md memory <<<"$out" ;;
    curves) ./build/bench/bench_curves 1 | as_text | replace docs/benchmarks.md curves ;;
    diff) ./build/bench/bench_diff | as_text | replace docs/benchmarks.md diff ;;
    pathological) ./build/bench/bench_pathological | as_text | replace docs/benchmarks.md pathological ;;
    printers) ./build/bench/bench_printers --markdown | replace docs/printers.md printers ;;
    band-side) bash tests/integration/band_side_corpus.sh ./build/arcpress ../shared/corpus | as_text | replace docs/fitting.md band-side ;;
    printer-causes) ./build/bench/bench_printers --causes | replace docs/printers.md printer-causes ;;
    vs-arcwelder)
      [ -x "${ARCWELDER:-}" ] || { echo "docs_figures: set ARCWELDER to ArcWelder's console program" >&2; exit 2; }
      ./build/bench/bench_vs_arcwelder "$ARCWELDER" 5 | replace docs/benchmarks.md vs-arcwelder ;;
    vs-arcwelder-instructions)
      [ -x "${ARCWELDER:-}" ] || { echo "docs_figures: set ARCWELDER to ArcWelder's console program" >&2; exit 2; }
      command -v valgrind >/dev/null || { echo "docs_figures: vs-arcwelder-instructions needs valgrind" >&2; exit 2; }
      ./build/bench/bench_vs_arcwelder "$ARCWELDER" --instructions | replace docs/benchmarks.md vs-arcwelder-instructions ;;
    grbl)
      [ -x "${GRBL_VALIDATOR:-}" ] || { echo "docs_figures: set GRBL_VALIDATOR to grbl-sim's gvalidate.exe" >&2; exit 2; }
      bash tests/integration/grbl_accepts.sh ./build/arcpress "$GRBL_VALIDATOR" ../shared/corpus ${GRBL_TRACE:-} |
        as_text | replace docs/dialects.md grbl ;;
    klipper)
      [ -f "${KLIPPER_SOURCE:-}/klippy/extras/gcode_arcs.py" ] || { echo "docs_figures: set KLIPPER_SOURCE to a clone of Klipper3d/klipper" >&2; exit 2; }
      bash tests/integration/klipper_executed.sh ./build/arcpress "$KLIPPER_SOURCE" ../shared/corpus | as_text | replace docs/dialects.md klipper ;;
    marlin)
      [ -f "${MARLIN_SOURCE:-}/Marlin/src/gcode/motion/G2_G3.cpp" ] || { echo "docs_figures: set MARLIN_SOURCE to a clone of MarlinFirmware/Marlin" >&2; exit 2; }
      bash tests/integration/marlin_executed.sh ./build/arcpress "$MARLIN_SOURCE" ../shared/corpus | as_text | replace docs/dialects.md marlin ;;
    prusa)
      [ -f "${BUDDY_SOURCE:-}/lib/Marlin/Marlin/src/gcode/motion/G2_G3.cpp" ] || { echo "docs_figures: set BUDDY_SOURCE to a clone of prusa3d/Prusa-Firmware-Buddy" >&2; exit 2; }
      bash tests/integration/marlin_executed.sh ./build/arcpress "$BUDDY_SOURCE" ../shared/corpus | as_text | replace docs/dialects.md prusa ;;
    prusa-mk3)
      [ -f "${MK3_SOURCE:-}/Firmware/motion_control.cpp" ] || { echo "docs_figures: set MK3_SOURCE to a clone of prusa3d/Prusa-Firmware" >&2; exit 2; }
      bash tests/integration/marlin_executed.sh ./build/arcpress "$MK3_SOURCE" ../shared/corpus | as_text | replace docs/dialects.md prusa-mk3 ;;
    smoothieware)
      [ -f "${SMOOTHIEWARE_SOURCE:-}/src/modules/robot/Robot.cpp" ] || { echo "docs_figures: set SMOOTHIEWARE_SOURCE to a clone of Smoothieware/Smoothieware" >&2; exit 2; }
      bash tests/integration/marlin_executed.sh ./build/arcpress "$SMOOTHIEWARE_SOURCE" ../shared/corpus | as_text | replace docs/dialects.md smoothieware ;;
    printers-vs-arcwelder)
      [ -x "${ARCWELDER:-}" ] || { echo "docs_figures: set ARCWELDER to ArcWelder's console program" >&2; exit 2; }
      ./build/bench/bench_vs_arcwelder "$ARCWELDER" --printers | replace docs/printers.md printers-vs-arcwelder ;;
    *) echo "docs_figures: no table '$name' (corpus, throughput, stages, memory, curves, diff, pathological, printers, printer-causes, band-side, vs-arcwelder, vs-arcwelder-instructions, printers-vs-arcwelder, grbl, klipper, marlin, prusa, prusa-mk3, smoothieware)" >&2; exit 2 ;;
  esac
done
