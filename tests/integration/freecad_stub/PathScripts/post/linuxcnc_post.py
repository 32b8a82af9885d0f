# SPDX-License-Identifier: GPL-3.0-or-later
# A stand-in for FreeCAD's linuxcnc_post, for testing arcpress_post.py without FreeCAD: its
# export() writes (and returns) the program named by $STUB_PROGRAM, as the real one writes
# the posted job, unless the file name is "-".
import os


def export(objectslist, filename, argstring):
    with open(os.environ["STUB_PROGRAM"]) as f:
        gcode = f.read()
    if filename != "-":
        with open(filename, "w") as f:
            f.write(gcode)
    return gcode
