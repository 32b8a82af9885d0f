#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs ArcPress.py into Cura's scripts folder, where Cura's post-processing finds scripts
# (Extensions > Post Processing > Modify G-Code): FOLDER if given; else the scripts folder of
# every Cura version that has run for this user (~/.local/share/cura/VERSION, on macOS
# ~/Library/Application Support/cura/VERSION); else that of the Cura installed here (its
# version read from Cura itself).
#   bash postproc/cura/install.sh [FOLDER]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
folders=()
if [ $# -gt 0 ]; then
  folders=("$1")
else
  for d in "$HOME"/.local/share/cura/*/ "$HOME/Library/Application Support/cura"/*/; do
    [ -d "$d" ] && folders+=("${d%/}/scripts")
  done
  if [ ${#folders[@]} -eq 0 ]; then
    version=""
    for py in /usr/bin/python3 python3; do  # (Cura runs on the system's Python)
      version=$("$py" -c "from cura.CuraVersion import CuraVersion; print('.'.join(CuraVersion.split('.')[:2]))" \
        2>/dev/null || true)
      [ -n "$version" ] && break
    done
    if [ -z "$version" ]; then
      echo "install.sh: no Cura found for this user or on this machine; give the scripts folder (Cura: Help >" \
           "Show Configuration Folder, then scripts)" >&2
      exit 2
    fi
    folders=("$HOME/.local/share/cura/$version/scripts")
  fi
fi
for folder in "${folders[@]}"; do
  mkdir -p "$folder"
  install -m 644 "$here/ArcPress.py" "$folder/ArcPress.py"
  echo "installed $folder/ArcPress.py: restart Cura, then Extensions > Post Processing > Modify G-Code > Add a script > arcpress"
done
