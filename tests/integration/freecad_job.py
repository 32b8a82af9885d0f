# SPDX-License-Identifier: GPL-3.0-or-later
# Run by freecadcmd (tests/integration/freecad_job.sh): a small Path job, a stock box and a
# custom operation cutting a circle of radius 20 mm as 180 G1 moves, posted once with FreeCAD's
# own linuxcnc_post and once with arcpress_post. Paths come from the environment; the
# outcome is written to $RESULT ("ok ..." or the error), as freecadcmd's exit status does not
# tell.
import math
import os
import sys
import traceback

try:
    import FreeCAD
    from PathScripts import PathCustom, PathJob
    from PathScripts.post import linuxcnc_post

    doc = FreeCAD.newDocument("job")
    stock = doc.addObject("Part::Box", "Stock")
    doc.recompute()
    job = PathJob.Create("Job", [stock], None)
    op = PathCustom.Create("Circle", parentJob=job)
    gcode = ["G0 X20 Y0 Z5", "G1 Z-1 F5"]
    for k in range(1, 181):
        t = math.radians(2 * k)
        gcode.append("G1 X%.4f Y%.4f F10" % (20 * math.cos(t), 20 * math.sin(t)))
    op.Gcode = gcode + ["G0 Z5"]
    doc.recompute()
    objects = list(job.Tools.Group) + list(job.Operations.Group)
    linuxcnc_post.export(objects, os.environ["PLAIN"], "--no-show-editor")
    sys.path.insert(0, os.environ["POST_DIR"])
    import arcpress_post

    text = arcpress_post.export(objects, os.environ["OUT"], "--no-show-editor --tolerance 0.01")
    arcs = sum(1 for line in text.splitlines() if line.startswith(("G2", "G3")))
    result = "ok %d arcs" % arcs
except Exception:
    result = traceback.format_exc()
with open(os.environ["RESULT"], "w") as f:
    f.write(result)
