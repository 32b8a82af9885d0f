#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs what is missing, configures and builds arcpress (Release) into ./build: the
# command-line program alone, or with --test also the test suite and the benchmarks, what
# the tests check output against (see install-deps.sh), and the Windows cross build in
# ./build-windows that the `windows` tests run under wine (scripts/build-windows.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh "$@"
everything=OFF
[ "${1:-}" = "--test" ] && everything=ON
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DARCPRESS_BUILD_TESTS=$everything -DARCPRESS_BUILD_BENCH=$everything >/dev/null
cmake --build build -j"$(nproc)"
if [ "$everything" = ON ]; then
  bash scripts/build-windows.sh
fi
