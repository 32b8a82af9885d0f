#!/usr/bin/env bash
# Installs what is missing, configures and builds arcpress (Release) into ./build.
# --test: also install what the test suite checks output against (see install-deps.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh "$@"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
