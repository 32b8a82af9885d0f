#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The Debian package as cpack makes it from BUILD_DIR: its files, its dependencies, the
# program run from the unpacked tree (finding the package's own dialects), and lintian.
#   deb.sh BUILD_DIR PROGRAM
set -euo pipefail
build=$1 program=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
(cd "$build" && cpack -G DEB -B "$work/pkg" >/dev/null)
deb=$(ls "$work/pkg"/arcpress_*_amd64.deb)
dpkg-deb -x "$deb" "$work/root"
for f in usr/bin/arcpress usr/share/arcpress/dialects/marlin.toml usr/lib/libarcpress.so usr/include/arcpress/arcpress.h \
         usr/include/arcpress/arcpress.hpp usr/lib/cmake/arcpress/arcpressConfig.cmake usr/share/doc/arcpress/copyright; do
  [ -e "$work/root/$f" ] || fail "the package has no /$f"
done
depends=$(dpkg-deb -f "$deb" Depends)
for d in libfmt9 libtomlplusplus3 libstdc++6 libeigen3-dev; do
  [[ $depends == *"$d"* ]] || fail "Depends ($depends) names no $d"
done
ARCPRESS_DIALECT_PATH= "$work/root/usr/bin/arcpress" dialects | grep -q '^marlin' || fail "the unpacked program finds no dialects"
"$work/root/usr/bin/arcpress" "$program" -o "$work/out.nc"
"$build/arcpress" "$program" -o "$work/expected.nc"
cmp "$work/out.nc" "$work/expected.nc" || fail "the packaged program writes other bytes"
lintian --tag-display-limit 0 "$deb" > "$work/lintian.txt" 2>&1 || true
cat "$work/lintian.txt"
! grep -q '^E:' "$work/lintian.txt" || fail "lintian reports errors"
echo "$(basename "$deb"): Depends: $depends; lintian: no errors"
