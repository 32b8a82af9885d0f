#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs arcpress's LinuxCNC program filter as arcpress-linuxcnc-filter: into /usr/local/bin
# as root, else ~/.local/bin (or into --bin FOLDER). With machine INI files, names it in each
# one's [FILTER] section for .ngc, .nc and .tap programs (the file is kept as INI.arcpress-backup
# first; a line already naming the filter is left as it is, and an extension another filter
# already has is left to it); without, prints the lines to add.
#   bash postproc/linuxcnc/install.sh [--bin FOLDER] [--options "ARCPRESS OPTIONS"] [MACHINE.ini ...]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=$([ "$(id -u)" = 0 ] && echo /usr/local/bin || echo "$HOME/.local/bin")
options="--tolerance 0.01"
inis=()
while [ $# -gt 0 ]; do
  case $1 in
    --bin) bin=$2; shift 2 ;;
    --options) options=$2; shift 2 ;;
    -h|--help) sed -n '3,8p' "$0"; exit 0 ;;
    *) inis+=("$1"); shift ;;
  esac
done
mkdir -p "$bin"
bin=$(cd "$bin" && pwd)
filter="$bin/arcpress-linuxcnc-filter"
install -m 755 "$here/arcpress_filter.py" "$filter"
echo "installed $filter"
command -v arcpress >/dev/null || [ -x "$bin/arcpress" ] ||
  echo "note: no arcpress on the PATH: give the filter --arcpress /path/to/arcpress in --options"

line="$filter${options:+ $options}"
extensions=(ngc nc tap)
if [ ${#inis[@]} -eq 0 ]; then
  echo "add to the [FILTER] section of your machine's INI file:"
  echo "PROGRAM_EXTENSION = .ngc,.nc,.tap G-code, arcs fitted by arcpress"
  for e in "${extensions[@]}"; do echo "$e = $line"; done
  exit 0
fi
for ini in "${inis[@]}"; do
  [ -f "$ini" ] || { echo "$ini: no such file" >&2; exit 3; }
  python3 - "$ini" "$line" "${extensions[@]}" <<'EOF'
import os, re, shutil, sys
path, line, extensions = sys.argv[1], sys.argv[2], sys.argv[3:]
text = open(path, encoding="utf-8").read()
lines = text.splitlines()
section = None
taken = {}
start = None
for i, raw in enumerate(lines):
    s = raw.strip()
    if s.startswith("[") and "]" in s:
        section = s[1:s.index("]")].strip()
        if section == "FILTER" and start is None:
            start = i
        continue
    if section == "FILTER" and "=" in s and s[0] not in "#;":
        name, value = (x.strip() for x in s.split("=", 1))
        taken.setdefault(name, value)
mine = "arcpress-linuxcnc-filter"
add = [e for e in extensions if e not in taken]
for e in extensions:
    if e in taken and mine not in taken[e]:
        print("%s: .%s already goes through %s: left as it is" % (path, e, taken[e]))
if not add:
    print("%s: nothing to add" % path)
    sys.exit(0)
new = ["PROGRAM_EXTENSION = %s G-code, arcs fitted by arcpress" % ",".join("." + e for e in add)]
new += ["%s = %s" % (e, line) for e in add]
if start is None:
    lines += ["", "[FILTER]"] + new
else:
    lines[start + 1:start + 1] = new
shutil.copy2(path, path + ".arcpress-backup")
with open(path + ".arcpress-new", "w", encoding="utf-8") as f:
    f.write("\n".join(lines) + "\n")
os.replace(path + ".arcpress-new", path)
print("%s: [FILTER] %s (the file as it was: %s.arcpress-backup)" % (path, ", ".join("." + e for e in add), path))
EOF
done
