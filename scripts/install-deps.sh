#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs the Debian packages arcpress builds with; with --test, also the real
# interpreters, slicers, CAM system and browser the test suite checks output against (LinuxCNC's rs274,
# PrusaSlicer, Cura, FreeCAD, Chromium), clang (the fuzz build's compiler, whose C++ the suite checks), the
# Windows cross compiler and wine, and lintian; with --windows, the cross compiler and wine
# alone (scripts/build-windows.sh); with --fuzz, clang and its sanitizer and libFuzzer runtimes
# (scripts/fuzz.sh).
# Idempotent: installs only what is missing. Run as root (or through sudo).
set -euo pipefail
packages=(g++ cmake make libeigen3-dev libcgal-dev libcli11-dev libfmt-dev catch2 libtomlplusplus-dev)
if [ "${1:-}" = "--test" ]; then
  packages+=(linuxcnc-uspace chromium prusa-slicer freecad cura clang)
fi
# The Windows cross build and what runs its tests (scripts/build-windows.sh); the test suite
# builds it too, and checks the Debian package with lintian.
windows=(g++-mingw-w64-x86-64-posix wine wine64)
if [ "${1:-}" = "--windows" ]; then
  packages+=("${windows[@]}")
fi
if [ "${1:-}" = "--test" ]; then
  packages+=("${windows[@]}" lintian dpkg-dev zip unzip)
fi
if [ "${1:-}" = "--fuzz" ]; then
  packages+=(clang libclang-rt-14-dev)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
# Another apt run (unattended upgrades, a second shell) holds the lock: wait for it.
lock=(-o DPkg::Lock::Timeout=900)
$sudo apt-get "${lock[@]}" update -q
$sudo apt-get "${lock[@]}" install -y -q --no-install-recommends "${missing[@]}"
echo "install-deps: done"
