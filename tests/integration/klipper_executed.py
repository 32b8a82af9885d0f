#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Klipper's own arc code as a judge of the path a program makes on a Klipper printer.

Writes the program again with each G2/G3 block replaced by the G1 moves Klipper's
klippy/extras/gcode_arcs.py (imported from a Klipper source tree, not copied) makes of it,
as Klipper's host sends them on: the path the printer moves along, which `arcpress diff`
then measures (klipper_executed.sh). Fails, as Klipper does, on an arc in R form or under
G91, and on a block whose first word after its number is no command (modal motion).

    klipper_executed.py KLIPPER_SOURCE_DIR PROGRAM > EXECUTED
"""
import re
import sys

sys.path.insert(0, sys.argv[1] + "/klippy/extras")
import gcode_arcs  # noqa: E402  (Klipper's module)

WORD = re.compile(r"([A-Za-z])\s*([-+]?(?:\d+\.?\d*|\.\d+))")


class Error(Exception):
    pass


class Command:
    """What gcode_arcs reads of a G2/G3 block (Klipper's GCodeCommand, as far as it asks)."""

    def __init__(self, words):
        self.words = words

    def get_float(self, name, default=None, **_):
        return self.words.get(name, default)

    def error(self, text):
        return Error(text)


class Machine:
    """The position and modes a G-code stream leaves, as Klipper's gcode_move keeps them;
    also the printer, config and gcode objects gcode_arcs asks for."""

    def __init__(self):
        self.pos = [0.0, 0.0, 0.0, 0.0]
        self.absolute = True
        self.absolute_e = True
        self.sent = []
        self.known = set()  # axes the program has set: Klipper's own start position is not the program's

    # (the config and printer gcode_arcs is loaded with)
    def get_printer(self):
        return self

    def getfloat(self, _name, default, **_):
        return default

    def load_object(self, _config, _name):
        return self

    def lookup_object(self, _name):
        return self

    def register_command(self, *_):
        pass

    # (gcode and gcode_move)
    def create_gcode_command(self, _cmd, _line, params):
        return params

    def get_status(self):
        return {"absolute_coordinates": self.absolute, "gcode_position": list(self.pos),
                "absolute_extrude": self.absolute_e}

    def cmd_G1(self, params):
        self.sent.append(params)
        for k, axis in enumerate("XYZ"):
            if params.get(axis) is not None:
                self.pos[k] = params[axis]
        if params.get("E") is not None:
            self.pos[3] = params["E"] if self.absolute_e else self.pos[3] + params["E"]

    def follow(self, words):
        """A block other than an arc: the position and modes after it."""
        g = [v for k, v in words if k == "G"]
        m = [v for k, v in words if k == "M"]
        values = dict(words)
        if 90 in g:
            self.absolute = True
        if 91 in g:
            self.absolute = False
        if 82 in m:
            self.absolute_e = True
        if 83 in m:
            self.absolute_e = False
        self.known |= {axis for axis, _ in words if axis in "XYZE"}
        if 92 in g:  # set position: these axes take the values given
            for k, axis in enumerate("XYZE"):
                if axis in values:
                    self.pos[k] = values[axis]
            return
        if any(v in (0, 1) for v in g) or (not g and any(k in "XYZE" for k, _ in words)):
            for k, axis in enumerate("XYZ"):
                if axis in values:
                    self.pos[k] = values[axis] if self.absolute else self.pos[k] + values[axis]
            if "E" in values:
                self.pos[3] = values["E"] if self.absolute_e else self.pos[3] + values["E"]


def number(v):
    return f"{v:.10f}".rstrip("0").rstrip(".")


def main():
    machine = Machine()
    arcs = gcode_arcs.ArcSupport(machine)
    out = sys.stdout
    for line in open(sys.argv[2], encoding="utf-8", errors="replace"):
        code = line.split(";", 1)[0]
        words = [(k.upper(), float(v)) for k, v in WORD.findall(code)]
        # Klipper reads a block's first word after its number as its command: no modal motion.
        first = next((k for k, _ in words if k != "N"), None)
        if first is not None and first in "XYZEIJKFR":
            raise Error("a block without a command: " + line.strip())
        g = [v for k, v in words if k == "G"]
        if g and g[0] in (2, 3):
            machine.sent = []
            getattr(arcs, "cmd_G%d" % int(g[0]))(Command(dict(words)))
            machine.known |= {axis for axis, _ in words if axis in "XYZ"}
            for p in machine.sent:
                # (An axis the program never set stays where the printer is: not written.)
                text = " ".join(f"{a}{number(p[a])}" for a in "XYZEF"
                                if p.get(a) is not None and (a in "EF" or a in machine.known))
                out.write(f"G1 {text}\n")
            continue
        if g and g[0] in (17, 18, 19):
            getattr(arcs, "cmd_G%d" % int(g[0]))(None)
        machine.follow(words)
        out.write(line if line.endswith("\n") else line + "\n")


if __name__ == "__main__":
    main()
