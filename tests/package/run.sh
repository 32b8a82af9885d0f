#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The library as a user gets it. `installed`: installs the build tree into a temporary prefix
# (cmake --install), builds postproc/examples against it with find_package(arcpress) (C++ on
# the shared and the static library, C on the shared) and runs them. `subdirectory`: builds
# the C example with arcpress added by add_subdirectory. Every example must write what the
# arcpress command writes for the same program and dialect.
#   run.sh installed|subdirectory BUILD_DIR SOURCE_DIR PROGRAM
set -euo pipefail
mode=$1 build=$2 source=$3 program=$4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$build/arcpress" "$program" --dialect fanuc -o "$work/expected.nc"
# The header names the commit each was built from; a build made since the last commit may
# name another than the command's: that word alone is set aside.
same_commit() { sed 's/^(arcpress \([0-9.]*\) commit [^ ]* /(arcpress \1 commit - /' "$1"; }
check() {  # exe...: runs each on the program and compares with the command's output
  for exe in "$@"; do
    "$exe" "$program" "$work/out.nc" fanuc
    cmp <(same_commit "$work/expected.nc") <(same_commit "$work/out.nc")
    echo "$(basename "$exe"): same as the command"
  done
}
case $mode in
  installed)
    cmake --install "$build" --prefix "$work/prefix" >/dev/null
    cmake -S "$source/tests/package/installed" -B "$work/consumer" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
    cmake --build "$work/consumer" -j2 >/dev/null
    # The installed library finds the installed dialects, not the source tree's.
    ARCPRESS_DIALECT_PATH= check "$work/consumer/compress" "$work/consumer/compress_c" "$work/consumer/compress_static"
    test -f "$work/prefix/lib/cmake/arcpress/arcpressConfig.cmake"
    test -f "$work/prefix/share/arcpress/dialects/fanuc.toml"
    ;;
  subdirectory)
    cmake -S "$source/tests/package/subdirectory" -B "$work/consumer" -DCMAKE_BUILD_TYPE=Release >/dev/null
    cmake --build "$work/consumer" -j2 >/dev/null
    check "$work/consumer/compress_c" "$work/consumer/compress"
    ;;
  *) echo "usage: run.sh installed|subdirectory BUILD_DIR SOURCE_DIR PROGRAM" >&2; exit 2 ;;
esac
