#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs arcpress_post.py into FreeCAD's user macro folder, where FreeCAD finds post
# processors: the folder FreeCAD itself names (freecadcmd), else ~/.local/share/FreeCAD/Macro.
#   bash postproc/freecad/install.sh [FOLDER]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
folder=${1:-}
if [ -z "$folder" ] && command -v freecadcmd >/dev/null; then
  folder=$(freecadcmd -c "import FreeCAD; print(FreeCAD.getUserMacroDir(True))" 2>/dev/null | tail -1 || true)
fi
folder=${folder:-$HOME/.local/share/FreeCAD/Macro}
mkdir -p "$folder"
install -m 644 "$here/arcpress_post.py" "$folder/arcpress_post.py"
echo "installed $folder/arcpress_post.py: choose 'arcpress' as the post processor of a Path job"
