# SPDX-License-Identifier: GPL-3.0-or-later
# FreeCAD Path post-processor: LinuxCNC G-code, compressed by arcpress.
#
# Posts with FreeCAD's own linuxcnc_post, then runs arcpress on the result: runs of small
# G1 moves become G2/G3 arcs within the band, tangent where the path is smooth; every other
# line is kept as it was. Choose "arcpress" as the post processor of a Path job. Arguments
# (the job's post-processor arguments): --tolerance MM (0.01), --dialect NAME (linuxcnc),
# --arcpress PATH (the program; default $ARCPRESS, else `arcpress` on PATH); the rest go to
# linuxcnc_post. Install: bash postproc/freecad/install.sh
import os
import shlex
import shutil
import subprocess
import tempfile

TOOLTIP = """LinuxCNC G-code from linuxcnc_post, with runs of small G1 moves compressed into arcs by arcpress."""
TOOLTIP_ARGS = """--tolerance MM   the band the arcs stay in (default 0.01)
--dialect NAME   the controller arcpress writes for (default linuxcnc)
--arcpress PATH  the arcpress program (default $ARCPRESS, else arcpress on PATH)
Other arguments go to linuxcnc_post."""


def _linuxcnc_post():
    try:
        from PathScripts.post import linuxcnc_post  # FreeCAD 0.19 to 0.21
    except ImportError:
        from Path.Post.scripts import linuxcnc_post  # FreeCAD 1.0
    return linuxcnc_post


def _split(argstring):
    """(arcpress options, linuxcnc_post's argument string)."""
    own = {"--tolerance": "0.01", "--dialect": "linuxcnc", "--arcpress": os.environ.get("ARCPRESS", "arcpress")}
    rest = []
    words = shlex.split(argstring or "")
    k = 0
    while k < len(words):
        if words[k] in own and k + 1 < len(words):
            own[words[k]] = words[k + 1]
            k += 2
        else:
            rest.append(words[k])
            k += 1
    return own, " ".join(shlex.quote(w) for w in rest)


def export(objectslist, filename, argstring):
    own, rest = _split(argstring)
    program = shutil.which(own["--arcpress"]) or own["--arcpress"]
    posted = _linuxcnc_post().export(objectslist, filename, rest)
    if posted is None:
        return None
    command = [program, "--tolerance", own["--tolerance"], "--dialect", own["--dialect"], "--quiet"]
    if filename == "-":
        # FreeCAD asked for the text only: compress it through a pipe.
        done = subprocess.run(command, input=posted, capture_output=True, text=True)
        if done.returncode != 0:
            raise RuntimeError("arcpress failed (exit %d): %s" % (done.returncode, done.stderr.strip()))
        return done.stdout
    done = subprocess.run(command + [filename, "--in-place"], capture_output=True, text=True)
    if done.returncode != 0:
        # The file is as linuxcnc_post wrote it: arcpress replaces it only once it is checked.
        raise RuntimeError("arcpress failed (exit %d) on %s: %s" % (done.returncode, filename, done.stderr.strip()))
    with open(filename) as f:
        return f.read()
