#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Cross-builds arcpress for 64-bit Windows into ./build-windows with Debian's mingw-w64
# (cmake/toolchain-mingw64.cmake), installing it and wine (to run what it builds) first:
# arcpress.exe (static: it imports only system DLLs), arcpress.dll with its import library
# libarcpress.dll.a, the C example compress_c.exe, and dialects\ beside them. With --package,
# also the zip (cpack): build-windows/arcpress-VERSION-win64.zip.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --windows
cmake -S . -B build-windows -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-mingw64.cmake -DCMAKE_BUILD_TYPE=Release \
  -DARCPRESS_BUILD_TESTS=OFF -DARCPRESS_BUILD_BENCH=OFF >/dev/null
cmake --build build-windows -j"$(nproc)"
if [ "${1:-}" = "--package" ]; then
  (cd build-windows && cpack -G ZIP >/dev/null)
  ls build-windows/arcpress-*-win64.zip
fi
