#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Fuzzes the whole pipeline with clang's libFuzzer and the address and undefined-behaviour
# sanitizers, built into ./build-fuzz, each target for SECONDS (default 300):
#   compress_fuzz  a program and options made from the bytes (tests/random_program.cpp),
#                  compressed with verification: band, read-back, reported kinks;
#   text_fuzz      the bytes taken as program text, whatever they are (G-code words from
#                  tests/fuzz/gcode.dict): passed through unchanged, compressed inside the
#                  band or refused, and never different from itself in `arcpress diff`.
# A broken promise, a sanitizer finding or an input slower than 10 s stops a target and
# leaves the input in build-fuzz/<target>-crash-* (or -timeout-*). Replay one:
#   ./build-fuzz/<target> FILE
# Keep what it found as a regression test: compress_fuzz inputs in tests/fuzz/found,
# text_fuzz inputs in tests/fuzz/found-text (the test suite replays both).
# Usage: scripts/fuzz.sh [SECONDS] [TARGET]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-300}"
targets=("${2:-compress_fuzz}")
[ $# -lt 2 ] && targets=(compress_fuzz text_fuzz)
bash scripts/install-deps.sh --fuzz
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DARCPRESS_FUZZ=ON \
  -DARCPRESS_BUILD_TESTS=OFF -DARCPRESS_BUILD_BENCH=OFF >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target "${targets[@]}"
for target in "${targets[@]}"; do
  mkdir -p "build-fuzz/inputs-$target"
  extra=()
  if [ "$target" = text_fuzz ]; then
    # Seeds: the samples and the texts found before.
    cp samples/*.nc tests/fuzz/found-text/* "build-fuzz/inputs-$target/" 2>/dev/null || true
    extra=(-dict=tests/fuzz/gcode.dict -max_len=4096)
  else
    extra=(-max_len=600 -len_control=0)
  fi
  echo "fuzz.sh: $target for $seconds s"
  "./build-fuzz/$target" "build-fuzz/inputs-$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
    "${extra[@]}" -artifact_prefix="build-fuzz/$target-" -print_final_stats=1
done
