#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# postproc/cura/ArcPress.py run as Cura 4.13 (Debian's cura package) runs a post-processing
# script: installed by postproc/cura/install.sh, loaded from the scripts folder as Cura's
# PostProcessingPlugin loads one (by file name, beside its own Script base class), its
# settings set up in Uranium's setting containers from the script's own definition, and
# execute() given a sliced program as Cura's list of chunks (header, start G-code, one per
# layer, end G-code). Cura's application is stood in for by what the script's settings need
# of it (a container registry); the rest is Cura's own code.
# Checked: the chunks come back as many, each beginning as it did, and together the bytes
# the command line writes for the whole program, with the tolerance and firmware set; the
# result holds arcs and `arcpress diff` finds it the same as the sliced program; where
# arcpress cannot run or fails, the G-code comes back as it was, and the script says why; a
# chunk whose first line the output lacks comes back empty, its text in the chunk before.
# Skipped (exit 77) where Cura is not installed, or the corpus's Cura program is not there.
#   cura_script.sh ARCPRESS SOURCE_DIR PROGRAM
set -euo pipefail
arcpress=$1 source=$2 program=$3
plugins=/usr/lib/cura/plugins
if [ ! -f "$plugins/PostProcessingPlugin/Script.py" ] || ! /usr/bin/python3 -c "import UM" 2>/dev/null; then
  echo "Cura is not installed: skipped"
  exit 77
fi
if [ ! -f "$program" ]; then
  echo "no Cura program at $program (the corpus): skipped"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
HOME="$work/home" bash "$source/postproc/cura/install.sh" "$work/scripts"
# Without a folder: the installed Cura's version names it, where no Cura has run yet.
version=$(/usr/bin/python3 -c "from cura.CuraVersion import CuraVersion; print('.'.join(CuraVersion.split('.')[:2]))")
HOME="$work/home" bash "$source/postproc/cura/install.sh"
cmp "$source/postproc/cura/ArcPress.py" "$work/home/.local/share/cura/$version/scripts/ArcPress.py"
export ARCPRESS=$arcpress PROGRAM=$program SCRIPTS="$work/scripts" WORK=$work CURA_PLUGINS=$plugins
PYTHONWARNINGS=ignore QT_QPA_PLATFORM=offscreen /usr/bin/python3 - <<'PY'
import importlib.util, os, subprocess, sys
sys.path.insert(0, os.environ["CURA_PLUGINS"])
import PostProcessingPlugin.PostProcessingPlugin as plugin_module  # Cura's plugin, and its Script
import UM.Settings.ContainerStack, UM.Settings.InstanceContainer
from UM.Settings.ContainerRegistry import ContainerRegistry
from UM.VersionUpgradeManager import VersionUpgradeManager

# What Cura's application sets up for settings: a container registry, and no upgrades to run.
class Host:
    def callLater(self, f, *args): f(*args)
registry = ContainerRegistry(Host())
UM.Settings.InstanceContainer.setContainerRegistry(registry)
UM.Settings.ContainerStack.setContainerRegistry(registry)
class NoUpgrades:
    def updateFilesData(self, *args, **kwargs): return None
VersionUpgradeManager.getInstance = classmethod(lambda cls: NoUpgrades())

# Loaded as PostProcessingPlugin.loadScripts() loads a script from a scripts folder.
path = os.path.join(os.environ["SCRIPTS"], "ArcPress.py")
spec = importlib.util.spec_from_file_location(plugin_module.__name__ + ".ArcPress", path)
module = importlib.util.module_from_spec(spec)
spec.loader.exec_module(module)
ArcPress = getattr(module, "ArcPress")

def script(**values):
    s = ArcPress()
    data = s.getSettingData()
    assert data["key"] == "ArcPress" and data["name"].startswith("arcpress"), data
    s.initialize()
    for key, value in values.items():
        s._instance.setProperty(key, "value", value)
    return s

# The program as Cura's list: the header, the start G-code, each layer, the end G-code.
lines = open(os.environ["PROGRAM"]).read().splitlines(keepends=True)
starts = [0] + [i for i, l in enumerate(lines) if l.startswith((";Generated with", ";LAYER:"))]
starts.append(max(i for i, l in enumerate(lines) if l.startswith(";TIME_ELAPSED")) + 1)
chunks = ["".join(lines[a:b]) for a, b in zip(starts, starts[1:] + [len(lines)])]
assert len(chunks) > 60, len(chunks)
whole = "".join(chunks)

def command(*options):
    run = subprocess.run([os.environ["ARCPRESS"], "-", "--quiet", *options], input=whole.encode(), capture_output=True)
    assert run.returncode == 0, run.stderr
    return run.stdout.decode()

# The defaults: the firmware from the FLAVOR line, a 0.01 mm band.
s = script(program=os.environ["ARCPRESS"])
assert s.getSettingValueByKey("tolerance") == 0.01 and s.getSettingValueByKey("dialect") == "auto"
out = s.execute(list(chunks))
assert len(out) == len(chunks), (len(out), len(chunks))
for before, after in zip(chunks, out):
    assert after.split("\n", 1)[0] == before.split("\n", 1)[0], (before[:40], after[:40])
assert "".join(out) == command("--tolerance", "0.01"), "the bytes of the command line"
assert any(l.startswith(("G2 ", "G3 ")) for l in "".join(out).splitlines()), "arcs"
for name, text in (("before.gcode", whole), ("after.gcode", "".join(out))):
    open(os.path.join(os.environ["WORK"], name), "w").write(text)
diff = subprocess.run([os.environ["ARCPRESS"], "diff", os.path.join(os.environ["WORK"], "before.gcode"),
                       os.path.join(os.environ["WORK"], "after.gcode")], capture_output=True, text=True)
assert diff.returncode == 0 and diff.stdout.splitlines()[-1].startswith("SAME"), diff.stdout[-500:]

# The tolerance and the firmware as set.
wide = script(program=os.environ["ARCPRESS"], tolerance=0.05, dialect="klipper").execute(list(chunks))
assert "".join(wide) == command("--tolerance", "0.05", "--dialect", "klipper")
assert "".join(wide) != "".join(out)

# Refusals: the G-code comes back as Cura sliced it, and the script says why.
missing = script(program=os.path.join(os.environ["WORK"], "no-such-arcpress"))
assert missing.execute(list(chunks)) == chunks and "cannot run" in missing.refused, missing.refused
failing = os.path.join(os.environ["WORK"], "failing.sh")
open(failing, "w").write("#!/bin/sh\ncat >/dev/null\necho 'x.gcode: error: E-VERIFY: out of band' >&2\nexit 1\n")
os.chmod(failing, 0o755)
refused = script(program=failing)
assert refused.execute(list(chunks)) == chunks and "E-VERIFY" in refused.refused and "exit 1" in refused.refused
bad = script(program=os.environ["ARCPRESS"], tolerance=1000)  # beyond what arcpress takes
assert bad.execute(list(chunks)) == chunks and "--tolerance" in bad.refused and "exit 2" in bad.refused, bad.refused
# A chunk whose first line the output lacks (as a move arcpress replaced would be) comes back
# empty, its text in the chunk before: the whole is what the program wrote.
dropping = os.path.join(os.environ["WORK"], "dropping.sh")
open(dropping, "w").write("#!/bin/sh\nsed '/^;LAYER:7$/d'\n")
os.chmod(dropping, 0o755)
seven = next(i for i, c in enumerate(chunks) if c.startswith(";LAYER:7\n"))
cut = script(program=dropping).execute(list(chunks))
assert len(cut) == len(chunks) and cut[seven] == "" and cut[seven - 1] == chunks[seven - 1] + chunks[seven].split("\n", 1)[1]
assert "".join(cut) == whole.replace(";LAYER:7\n", "", 1)
assert cut[:seven - 1] == chunks[:seven - 1] and cut[seven + 1:] == chunks[seven + 1:]
print("ArcPress.py: {} chunks back as they began, the command line's bytes, arcs, SAME; refusals keep the "
      "G-code".format(len(out)))
PY
