#!/usr/bin/env python3
"""make_expect.py - the CAN decoding oracle's files, from the DBCs in this folder.

    .venv/bin/python tests/input/can/make_expect.py [OUTDIR]

For each NAME.dbc: NAME.map, made by tools/dbc2panel; NAME.log, frames for
its messages (random, all-zero, all-one, sign-bit patterns, every
multiplexer value, every truncated length, one longer than the message) in
the candump -l format, written here from can-utils' documented format; and
NAME.expect, what cantools decodes from each frame (decode_choices=False,
allow_truncated=True; signal by signal where
the signals overlap, which its whole-message decoder refuses), one line per
signal the map has:

    FRAME_INDEX LINE_INDEX NAME VALUE

in frame order, then the map's line order. tests/test_can.c decodes the
same log through the map and compares; tests/tools/test_can_oracle.py
re-runs this script and checks the committed files are what it gives today.
"""

import glob
import importlib.machinery
import importlib.util
import os
import random
import subprocess
import sys

import cantools
from cantools.database.utils import create_encode_decode_formats, decode_data, encode_data

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
DBC2PANEL = os.path.join(ROOT, "tools", "dbc2panel")
T0 = 1700000000  # the logs' first second (candump writes wall-clock times)


def load_dbc2panel():
    loader = importlib.machinery.SourceFileLoader("dbc2panel", DBC2PANEL)
    spec = importlib.util.spec_from_loader("dbc2panel", loader)
    mod = importlib.util.module_from_spec(spec)
    loader.exec_module(mod)
    return mod


def set_raw(data, msg, sig, raw):
    """data with sig's bits set to raw, placed by cantools' own encoder."""
    fmts = create_encode_decode_formats([sig], msg.length)
    ones = encode_data({sig.name: -1 if sig.is_signed else (1 << sig.length) - 1}, [sig], fmts,
                       False)
    val = encode_data({sig.name: raw}, [sig], fmts, False)
    n = int.from_bytes(data, "big")
    n = (n & ~ones) | (val & ones)
    return n.to_bytes(msg.length, "big")


def frames_for(msg, rng):
    """(data) for one message: patterns, random frames, every mux value, truncations."""
    n = msg.length
    base = [bytes(n), b"\xff" * n, bytes([0x80] * n), bytes([0x7f] * n),
            bytes([0x55, 0xaa] * 4)[:n], bytes([0xaa, 0x55] * 4)[:n]]
    base += [bytes(rng.getrandbits(8) for _ in range(n)) for _ in range(24)]
    muxes = [s for s in msg.signals if s.is_multiplexer and not s.multiplexer_signal]
    out = []
    for i, data in enumerate(base):
        for mux in muxes:
            values = sorted({v for s in msg.signals if s.multiplexer_signal == mux.name
                             for v in s.multiplexer_ids})
            raw = int((values[i % len(values)] - mux.offset) / mux.scale)
            data = set_raw(data, msg, mux, raw)
        out.append(data)
    # every truncated length of a few frames, and one frame longer than the message
    for data in out[6:6 + 2 * max(1, len(muxes) * 3)]:
        out += [data[:k] for k in range(n)]
    if n < 8:
        out.append(out[7] + b"\x5a" * (8 - n))
    return out


def decode(msg, data):
    """cantools' decoding of data; signal by signal where its message's signals
    overlap, which cantools' whole-message decoder refuses"""
    try:
        return msg.decode(data, decode_choices=False, allow_truncated=True)
    except cantools.database.DecodeError:
        if any(s.is_multiplexer or s.multiplexer_ids for s in msg.signals):
            raise
    out = {}
    for sig in msg.signals:
        fmts = create_encode_decode_formats([sig], msg.length)
        out.update(decode_data(data, msg.length, [sig], fmts, False, True, True, True))
    return out


def main():
    outdir = sys.argv[1] if len(sys.argv) > 1 else HERE
    mod = load_dbc2panel()
    for dbc in sorted(glob.glob(os.path.join(HERE, "*.dbc"))):
        name = os.path.splitext(os.path.basename(dbc))[0]
        map_path = os.path.join(outdir, name + ".map")
        subprocess.run([sys.executable, DBC2PANEL, dbc, "-o", map_path], check=True,
                       stderr=subprocess.DEVNULL)
        lines = []
        with open(map_path) as f:
            for line in f:
                words = line.split("#")[0].split()
                if words:
                    lines.append(words[3])
        index = {n: i for i, n in enumerate(lines)}

        # the DBC as cantools reads it once dbc2panel has mended its defects
        with open(dbc, encoding="cp1252", newline="") as f:
            text = f.read().replace("\r\n", "\n")
        db = cantools.database.load_string(mod.repair(text, lambda *a, **k: None), "dbc",
                                           strict=False)
        rng = random.Random(name)
        log, expect = [], ["# frame line name value (cantools %s)" % cantools.__version__]
        k = 0
        for msg in db.messages:
            if msg.length > 8:
                continue
            for data in frames_for(msg, rng):
                t = T0 * 1000000 + 10007 * k
                ident = f"{msg.frame_id:08X}" if msg.is_extended_frame else f"{msg.frame_id:03X}"
                log.append(f"({t // 1000000:010d}.{t % 1000000:06d}) can0 "
                           f"{ident}#{data.hex().upper()}")
                decoded = decode(msg, data)
                got = sorted((index[f"{msg.name}.{s}"], f"{msg.name}.{s}", v)
                             for s, v in decoded.items() if f"{msg.name}.{s}" in index)
                for i, full, v in got:
                    expect.append(f"{k} {i} {full} {float(v)!r}")
                k += 1
        with open(os.path.join(outdir, name + ".log"), "w") as f:
            f.write("\n".join(log) + "\n")
        with open(os.path.join(outdir, name + ".expect"), "w") as f:
            f.write("\n".join(expect) + "\n")


if __name__ == "__main__":
    main()
