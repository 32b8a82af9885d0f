# SPDX-License-Identifier: GPL-3.0-or-later
"""arcpress as an Ultimaker Cura post-processing script.

Extensions > Post Processing > Modify G-Code > Add a script > arcpress. Cura hands the
sliced program over as a list of chunks (its header, the start G-code, one per layer, the
end G-code); the script runs the arcpress program on all of it at once (each layer starts
where the one before left the nozzle, in the extrusion mode and at the feed it set), and
hands the result back cut where the chunks began (each begins with a comment, ";LAYER:3", or
a command arcpress leaves as it is; a chunk that began with a move arcpress replaced comes
back empty, its text in the chunk before). Where arcpress refuses (its check found the output
outside the band, or the program cannot be read), the G-code is saved as Cura sliced it, and
the reason is shown and logged. Run it after the scripts that edit the G-code: they read the
moves Cura wrote.

Installed by postproc/cura/install.sh into Cura's scripts folder (Help > Show Configuration
Folder, then scripts). Cura loads a script by its file name, which names its class.
"""
import json
import subprocess

from ..Script import Script

# The printer dialects shipped with arcpress (dialects/*.toml); "auto" takes the one the
# program names for itself (Cura's ";FLAVOR:" line).
DIALECTS = {
    "auto": "From the G-code's FLAVOR line",
    "marlin": "Marlin",
    "prusa": "Prusa Buddy (MK4, MK3.5, MINI, XL, CORE One)",
    "klipper": "Klipper",
    "reprapfirmware": "RepRapFirmware",
    "smoothieware": "Smoothieware",
}


def command(program, tolerance_mm, dialect):
    """The arcpress command line that reads the program from standard input and writes it
    compressed to standard output."""
    line = [program, "-", "--tolerance", repr(float(tolerance_mm)), "--quiet"]
    if dialect and dialect != "auto":
        line += ["--dialect", dialect]
    return line


def cut_like(chunks, text):
    """`text` cut into as many chunks as `chunks`: each from where that chunk's first line
    stands in `text` as a whole line, after the chunk before's. (Cura's chunks begin with a
    comment, ";LAYER:3", or a command such as "M140 S0", which arcpress leaves as they are.)
    A chunk whose first line is not found (a move arcpress replaced), or that was empty, comes
    back empty, its text at the end of the chunk before: the whole is the same."""
    starts, after = [0], 1 if chunks and chunks[0] else 0  # per chunk, where it starts (None: empty)
    for chunk in chunks[1:]:
        first = chunk.split("\n", 1)[0].rstrip("\r")
        at = text.find(first, after) if first else -1
        while at >= 0 and not ((at == 0 or text[at - 1] == "\n") and
                               text[at + len(first):at + len(first) + 1] in ("", "\n", "\r")):
            at = text.find(first, at + 1)
        starts.append(at if at >= 0 else None)
        if at >= 0:
            after = at + 1
    pieces = []
    for i, start in enumerate(starts):
        end = next((s for s in starts[i + 1:] if s is not None), len(text))
        pieces.append("" if start is None else text[start:end])
    return pieces


class ArcPress(Script):
    def getSettingDataString(self):
        return json.dumps({
            "name": "arcpress: lines and arcs (G2/G3)",
            "key": "ArcPress",
            "metadata": {},
            "version": 2,
            "settings": {
                "tolerance": {
                    "label": "Tolerance",
                    "description": "How far the compressed path may lie from the sliced one, either way (mm).",
                    "unit": "mm",
                    "type": "float",
                    "default_value": 0.01,
                    "minimum_value": "0.00001",
                    "maximum_value": "100",
                    "maximum_value_warning": "0.1",
                },
                "dialect": {
                    "label": "Firmware",
                    "description": "The firmware whose rules the arcs follow.",
                    "type": "enum",
                    "options": DIALECTS,
                    "default_value": "auto",
                },
                "program": {
                    "label": "arcpress program",
                    "description": "The arcpress command, or its full path (on Windows, arcpress.exe in the "
                                   "folder it was unpacked to).",
                    "type": "str",
                    "default_value": "arcpress",
                },
            },
        })

    def execute(self, data):
        if not data:
            return data
        line = command(self.getSettingValueByKey("program") or "arcpress", self.getSettingValueByKey("tolerance"),
                       self.getSettingValueByKey("dialect"))
        try:
            # (On Windows, without a console window flashing up.)
            run = subprocess.run(line, input="".join(data).encode("utf-8"), capture_output=True,
                                 creationflags=getattr(subprocess, "CREATE_NO_WINDOW", 0))
        except OSError as e:
            return self._refused(data, "cannot run {}: {}".format(line[0], e))
        if run.returncode != 0:
            why = run.stderr.decode("utf-8", "replace").strip()
            return self._refused(data, "{} (exit {})".format(why, run.returncode))
        return cut_like(data, run.stdout.decode("utf-8"))

    def _refused(self, data, why):
        """Leaves the G-code as Cura sliced it, and says why."""
        text = "arcpress did not compress the G-code, which is saved as sliced: " + why
        try:
            from UM.Logger import Logger
            Logger.log("e", text)
            from UM.Message import Message
            Message(text, title="arcpress").show()
        except Exception:  # (outside Cura's window: nothing to show it in)
            pass
        self.refused = text
        return data
