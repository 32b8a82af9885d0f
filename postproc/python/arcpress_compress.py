#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Compresses a G-code file through arcpress's C library (libarcpress.so) with ctypes.

    arcpress_compress.py INPUT OUTPUT [--dialect NAME] [--tolerance MM] [--library PATH]

The library is looked for at --library, then $ARCPRESS_LIBRARY, then by the system's usual
rules (ldconfig, LD_LIBRARY_PATH). Exit 0 written; otherwise arcpress's status (1 the check
failed, 2 bad input, 3 a file could not be read or written, 4 anything else) with a message,
and OUTPUT as it was: the output is written to a new temporary file beside it, renamed into
place only when all is written, and removed on any failure.
"""
import argparse
import ctypes
import ctypes.util
import os
import sys
import tempfile

OK = 0
IO_ERROR = 3


class Stats(ctypes.Structure):
    _fields_ = [("bytes_in", ctypes.c_size_t), ("bytes_out", ctypes.c_size_t), ("blocks_in", ctypes.c_size_t),
                ("g1_moves", ctypes.c_size_t), ("lines_out", ctypes.c_size_t), ("arcs_out", ctypes.c_size_t),
                ("max_deviation_mm", ctypes.c_double), ("verified", ctypes.c_int)]


def load(path):
    path = path or os.environ.get("ARCPRESS_LIBRARY") or ctypes.util.find_library("arcpress")
    if not path:
        sys.exit("arcpress_compress: libarcpress.so not found (use --library or ARCPRESS_LIBRARY)")
    lib = ctypes.CDLL(path)
    p = ctypes.c_void_p
    lib.arcpress_options_new.restype = p
    lib.arcpress_options_free.argtypes = [p]
    lib.arcpress_options_last_error.argtypes = [p]
    lib.arcpress_options_last_error.restype = ctypes.c_char_p
    lib.arcpress_options_set_tolerance.argtypes = [p, ctypes.c_double]
    lib.arcpress_options_set_dialect.argtypes = [p, ctypes.c_char_p]
    lib.arcpress_options_set_units.argtypes = [p, ctypes.c_char_p]
    lib.arcpress_compressor_new.argtypes = [p, ctypes.c_char_p, ctypes.POINTER(p)]
    lib.arcpress_compressor_free.argtypes = [p]
    lib.arcpress_push.argtypes = [p, ctypes.c_char_p, ctypes.c_size_t]
    lib.arcpress_read_jumps.argtypes = [p, ctypes.c_char_p, ctypes.c_size_t, ctypes.c_uint]
    lib.arcpress_read_loops.argtypes = [p, ctypes.c_char_p, ctypes.c_size_t]
    lib.arcpress_take.argtypes = [p, ctypes.POINTER(ctypes.c_char_p), ctypes.POINTER(ctypes.c_size_t)]
    lib.arcpress_finish.argtypes = [p]
    lib.arcpress_get_stats.argtypes = [p, ctypes.POINTER(Stats)]
    lib.arcpress_diagnostics.argtypes = [p]
    lib.arcpress_diagnostics.restype = ctypes.c_char_p
    lib.arcpress_last_error.argtypes = [p]
    lib.arcpress_last_error.restype = ctypes.c_char_p
    return lib


def compress(lib, source, target, dialect, tolerance, units=None):
    options = lib.arcpress_options_new()
    compressor = ctypes.c_void_p()
    partial = None
    try:
        if (lib.arcpress_options_set_tolerance(options, tolerance) != OK or
                lib.arcpress_options_set_dialect(options, dialect.encode()) != OK or
                (units and lib.arcpress_options_set_units(options, units.encode()) != OK) or
                lib.arcpress_compressor_new(options, source.encode(), ctypes.byref(compressor)) != OK):
            print("arcpress_compress:", lib.arcpress_options_last_error(options).decode(), file=sys.stderr)
            return 2
        if os.path.isdir(target):
            print(f"arcpress_compress: cannot write '{target}': it is a folder", file=sys.stderr)
            return IO_ERROR
        text, length = ctypes.c_char_p(), ctypes.c_size_t()
        status = OK
        with open(source, "rb") as src:
            # The program's jumps first, whole lines at a time, and the subprograms after its
            # end; then, where it jumps, its loops, from the whole text (up to 64 MB), as the
            # command reads a file.
            lines = b""
            while status == OK:
                chunk = src.read(1 << 20)
                if not chunk:
                    break
                lines += chunk
                last = lines.rfind(b"\n") + 1
                status = lib.arcpress_read_jumps(compressor, lines[:last], last, 0)
                lines = lines[last:]
            if status == OK:
                status = lib.arcpress_read_jumps(compressor, lines, len(lines), 0)
            if status == OK and os.path.getsize(source) <= 64 << 20:
                src.seek(0)
                whole = src.read()
                status = lib.arcpress_read_loops(compressor, whole, len(whole))
                del whole
            src.seek(0)
            # A name of its own beside the target: an existing file is never overwritten.
            folder = os.path.dirname(os.path.abspath(target))
            fd, partial = tempfile.mkstemp(prefix=os.path.basename(target) + ".", suffix=".partial", dir=folder)
            with os.fdopen(fd, "wb") as out:
                def take():
                    if lib.arcpress_take(compressor, ctypes.byref(text), ctypes.byref(length)) == OK and length.value:
                        out.write(ctypes.string_at(text, length.value))
                while status == OK:
                    chunk = src.read(1 << 20)
                    if not chunk:
                        break
                    status = lib.arcpress_push(compressor, chunk, len(chunk))
                    take()
                if status == OK:
                    status = lib.arcpress_finish(compressor)
                take()
                out.flush()
                os.fsync(out.fileno())
        sys.stderr.write(lib.arcpress_diagnostics(compressor).decode())
        if status != OK:
            print("arcpress_compress:", lib.arcpress_last_error(compressor).decode(), file=sys.stderr)
            return status
        os.replace(partial, target)
        partial = None
        stats = Stats()
        lib.arcpress_get_stats(compressor, ctypes.byref(stats))
        print(f"arcpress_compress: {stats.bytes_in} -> {stats.bytes_out} bytes, {stats.arcs_out} arcs, "
              f"deviation {stats.max_deviation_mm:.6f} mm", file=sys.stderr)
        return OK
    except OSError as e:
        # A missing input, a folder that is not there, a full disk: a file error, said as one.
        name = e.filename if e.filename else target
        print(f"arcpress_compress: '{name}': {e.strerror or e}", file=sys.stderr)
        return IO_ERROR
    finally:
        if partial is not None:
            try:
                os.remove(partial)
            except OSError:
                pass
        lib.arcpress_compressor_free(compressor)
        lib.arcpress_options_free(options)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--dialect", default="rs274")
    parser.add_argument("--tolerance", type=float, default=0.01)
    parser.add_argument("--units", choices=["mm", "inch"],
                        help="the units the program is in until its first G20 or G21 (default: the dialect's)")
    parser.add_argument("--library")
    args = parser.parse_args()
    return compress(load(args.library), args.input, args.output, args.dialect, args.tolerance, args.units)


if __name__ == "__main__":
    sys.exit(main())
