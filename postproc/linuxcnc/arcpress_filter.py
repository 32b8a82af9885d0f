#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""arcpress as a LinuxCNC program filter: a program opened in AXIS (or a GUI that filters as
AXIS does) is compressed as it is loaded, its runs of short G1 moves replaced by arcs.

LinuxCNC runs the filter named in the machine's INI file for the program's extension,
`FILTER 'PROGRAM'`, loads what it writes on standard output, moves its progress bar by the
`FILTER_PROGRESS=N` lines it writes on standard error, and on a non-zero exit loads nothing
and shows standard error in a dialog:

    [FILTER]
    PROGRAM_EXTENSION = .ngc,.nc,.tap G-code, arcs fitted by arcpress
    ngc = /usr/local/bin/arcpress-linuxcnc-filter --tolerance 0.01
    nc = /usr/local/bin/arcpress-linuxcnc-filter --tolerance 0.01
    tap = /usr/local/bin/arcpress-linuxcnc-filter --tolerance 0.01

Every option but those below goes to arcpress (`--dialect linuxcnc` unless one is given).
The units a program is in before its first G20 or G21 are the machine's: the last G20 or G21
of RS274NGC_STARTUP_CODE ([EMC], else [RS274NGC]), else [TRAJ] LINEAR_UNITS, read from the INI file
LinuxCNC names in $INI_FILE_NAME (`--units` overrides them).

    --arcpress PATH   the arcpress program (default: `arcpress` beside this file, else on PATH)
    --strict          where arcpress cannot run or refuses, fail the load (exit non-zero, the
                      message in LinuxCNC's dialog) instead of loading the program as it was

Without --strict, a program arcpress cannot compress is loaded as it was, and why is written
on standard error (LinuxCNC prints it on its terminal).
"""

import os
import re
import shutil
import subprocess
import sys
import tempfile

PROGRESS = re.compile(r"\((\d+) %\)")
UNITS_WORD = re.compile(r"G\s*0*2\s*([01])(?![0-9.])", re.IGNORECASE)


def ini_values(path, section, key):
    """Every value of `key` in `section` of a LinuxCNC INI file, in order (LinuxCNC reads
    the first; keys may repeat). Comments start with # or ; at a line's start."""
    values, current = [], None
    with open(path, encoding="utf-8", errors="replace") as f:
        for raw in f:
            line = raw.strip()
            if not line or line[0] in "#;":
                continue
            if line.startswith("[") and "]" in line:
                current = line[1:line.index("]")].strip()
                continue
            if current == section and "=" in line:
                name, value = line.split("=", 1)
                if name.strip() == key:
                    values.append(value.strip())
    return values


def machine_units(ini_path):
    """'mm' or 'inch': what the machine's interpreter reads lengths in before a program's
    first G20 or G21, or None where the INI file does not say."""
    # Where the interpreter finds its startup code: [EMC] first, then [RS274NGC] (as AXIS and
    # milltask of LinuxCNC 2.9 look for it).
    startup = ini_values(ini_path, "EMC", "RS274NGC_STARTUP_CODE") or ini_values(ini_path, "RS274NGC",
                                                                                 "RS274NGC_STARTUP_CODE")
    for code in startup[:1]:
        # Comments in the startup code say nothing.
        words = UNITS_WORD.findall(re.sub(r"\([^)]*\)|;.*", "", code))
        if words:
            return "inch" if words[-1] == "0" else "mm"
    for units in ini_values(ini_path, "TRAJ", "LINEAR_UNITS")[:1]:
        units = units.lower()
        if units in ("mm", "metric"):
            return "mm"
        if units in ("in", "inch", "imperial"):
            return "inch"
    return None


class ProgressRelay:
    """Passes arcpress's standard error on: its progress line (rewritten with carriage
    returns) as LinuxCNC's FILTER_PROGRESS=N lines, everything else as it is."""

    def __init__(self, err):
        self.err = err
        self.pending = b""
        self.last = -1

    def progress(self, percent):
        if percent > self.last:
            self.last = percent
            self.err.write("FILTER_PROGRESS=%d\n" % percent)
            self.err.flush()

    def feed(self, data):
        self.pending += data
        while True:
            cut = min((i for i in (self.pending.find(b"\r"), self.pending.find(b"\n")) if i >= 0), default=-1)
            if cut < 0:
                return
            self.line(self.pending[:cut])
            self.pending = self.pending[cut + 1:]

    def line(self, raw):
        text = raw.decode("utf-8", errors="replace").replace("\x1b[K", "")
        if not text.strip():
            return
        m = PROGRESS.search(text) if text.startswith("arcpress: ") else None
        if m:
            self.progress(min(int(m.group(1)), 99))
        else:
            self.err.write(text + "\n")
            self.err.flush()

    def close(self):
        if self.pending:
            self.line(self.pending)
            self.pending = b""


def split_arguments(argv):
    """(arcpress's options, the program, the arcpress program, strict)."""
    if not argv:
        raise SystemExit("usage: arcpress-linuxcnc-filter [--arcpress PATH] [--strict] [ARCPRESS OPTIONS] PROGRAM")
    program, options = argv[-1], []
    arcpress, strict = None, False
    rest = iter(argv[:-1])
    for word in rest:
        if word == "--arcpress":
            arcpress = next(rest, None)
        elif word.startswith("--arcpress="):
            arcpress = word.split("=", 1)[1]
        elif word == "--strict":
            strict = True
        else:
            options.append(word)
    if not arcpress:
        beside = os.path.join(os.path.dirname(os.path.abspath(__file__)), "arcpress")
        arcpress = beside if os.access(beside, os.X_OK) else shutil.which("arcpress") or "arcpress"
    return options, program, arcpress, strict


def given(options, name):
    return any(o == name or o.startswith(name + "=") for o in options)


def run(argv, out, err):
    options, program, arcpress, strict = split_arguments(argv)
    if not given(options, "--dialect") and not given(options, "--dialect-file"):
        options = ["--dialect", "linuxcnc"] + options
    ini = os.environ.get("INI_FILE_NAME")
    if not given(options, "--units") and ini and os.path.isfile(ini):
        units = machine_units(ini)
        if units:
            options += ["--units", units]
    relay = ProgressRelay(err)
    relay.progress(0)
    folder = tempfile.mkdtemp(prefix="arcpress-filter-")
    compressed = os.path.join(folder, "out.ngc")
    try:
        try:
            p = subprocess.Popen([arcpress, program, "-o", compressed, "--progress"] + options,
                                 stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        except OSError as e:
            code, why = 127, "cannot run %s: %s" % (arcpress, e.strerror)
        else:
            while True:
                data = os.read(p.stderr.fileno(), 65536)
                if not data:
                    break
                relay.feed(data)
            relay.close()
            code = p.wait()
            why = "%s exited with %d" % (os.path.basename(arcpress), code)
        if code == 0 and os.path.isfile(compressed):
            source = compressed
        elif strict:
            err.write("arcpress-linuxcnc-filter: %s: not loaded: %s\n" % (program, why))
            return code if code > 0 else 1
        else:
            err.write("arcpress-linuxcnc-filter: %s: loaded as it was: %s\n" % (program, why))
            source = program
        try:
            with open(source, "rb") as f:
                shutil.copyfileobj(f, out)
            out.flush()
        except OSError as e:
            err.write("arcpress-linuxcnc-filter: %s: %s\n" % (source, e.strerror))
            return 3
        relay.progress(100)
        return 0
    finally:
        shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(run(sys.argv[1:], sys.stdout.buffer, sys.stderr))
