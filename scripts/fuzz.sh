#!/usr/bin/env bash
# Fuzzes the whole pipeline: builds tests/fuzz/compress_fuzz with clang, libFuzzer and the
# address and undefined-behaviour sanitizers into ./build-fuzz, then runs it for SECONDS
# (default 300). Each input becomes a program and options (tests/random_program.cpp); a
# broken promise (band, read-back, reported kinks) or a sanitizer finding stops the run and
# leaves the input in build-fuzz/crash-*. Replay one: ./build-fuzz/compress_fuzz FILE
# Usage: scripts/fuzz.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --fuzz
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DARCPRESS_FUZZ=ON \
  -DARCPRESS_BUILD_TESTS=OFF -DARCPRESS_BUILD_BENCH=OFF >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target compress_fuzz
mkdir -p build-fuzz/inputs
./build-fuzz/compress_fuzz build-fuzz/inputs -max_total_time="${1:-300}" -max_len=600 -len_control=0 \
  -artifact_prefix=build-fuzz/ -print_final_stats=1
