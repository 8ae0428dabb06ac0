#!/usr/bin/env python3
"""Input decoding: ours (build/rel/bench/input_bench: evdev records, HID reports of a boot
mouse and an NKRO keyboard, CAN frames through a panel map) beside the Python decoders
the tests use as oracles, on the same kinds of bytes in the same run, for scale:
hid-tools' report parser (the same descriptors) and cantools' message decoder (the DBC the
panel map was made from). Prints every BENCH line and the ratios.
"""
import os
import pathlib
import random
import re
import subprocess
import sys
import time

import cantools
from hidtools.hid import ReportDescriptor

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
N = 20000

def read_hex(path):
    text = "".join(line.split("#")[0] for line in open(path))
    return bytes.fromhex("".join(text.split()))


def per_call_ns(fn, items):
    best = None
    for _ in range(3):
        t0 = time.perf_counter_ns()
        for x in items:
            fn(x)
        ns = (time.perf_counter_ns() - t0) / len(items)
        best = ns if best is None else min(best, ns)
    return best


def hid_tools_ns(rdesc, reports):
    rd = ReportDescriptor.from_bytes(rdesc)
    report = next(iter(rd.input_reports.values()))
    fields = [f for f in report.fields if not f.type & 1]

    def decode(buf):
        for f in fields:
            f.get_values(buf)
    return per_call_ns(decode, reports)


def main():
    proc = subprocess.run([str(BUILD / "bench" / "input_bench"), str(ROOT)],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit(f"input_bench failed ({proc.returncode}):\n{proc.stderr}")
    print(proc.stdout, end="")
    ours = {m.group(1): float(m.group(2))
            for m in re.finditer(r"BENCH (\S+) ns=([0-9.]+)", proc.stdout)}

    def key(name):
        return float(re.search(name + r"=([0-9.]+)", proc.stdout).group(1))
    mouse_ns, nkro_ns = key("mouse_report_ns"), key("nkro_report_ns")
    frame_ns = key("frame_ns")

    rng = random.Random(1)
    mouse = [bytes([(i // 8) % 2, rng.randrange(256), rng.randrange(256)]) for i in range(N)]
    # HID 1.11 Appendix B.2's boot mouse, the descriptor hid_desc_boot builds
    m_ns = hid_tools_ns(read_hex(ROOT / "tests" / "input" / "hid" / "boot_mouse.rdesc"), mouse)
    nkro_desc = read_hex(ROOT / "tests" / "input" / "hid" / "nkro_keyboard.rdesc")
    rd = ReportDescriptor.from_bytes(nkro_desc)
    size = (next(iter(rd.input_reports.values())).bitsize + 7) // 8
    cur = bytearray(size)
    nkro = []
    for _ in range(N):
        cur[1 + rng.randrange(size - 1)] ^= 1 << rng.randrange(8)
        nkro.append(bytes(cur))
    k_ns = hid_tools_ns(nkro_desc, nkro)
    print(f"BENCH input.hid.hidtools mouse_ns={m_ns:.0f} nkro_ns={k_ns:.0f} reports={N}")

    db = cantools.database.load_file(str(ROOT / "tests" / "input" / "can" / "panel.dbc"),
                                     strict=False)
    msgs = [m for m in db.messages if not m.is_container]
    frames = []
    for _ in range(N):
        m = msgs[rng.randrange(len(msgs))]
        frames.append((m, bytes(rng.randrange(256) for _ in range(m.length))))

    def decode(item):
        m, data = item
        try:
            m.decode(data, decode_choices=False, allow_truncated=True)
        except cantools.database.DecodeError:
            pass
    c_ns = per_call_ns(decode, frames)
    print(f"BENCH input.can.cantools ns={c_ns:.0f} frames={N}")
    print(f"input_bench: per event taken from the queue: evdev {ours['input.evdev']:.1f} ns, "
          f"HID {ours['input.hid']:.1f} ns (the worse device), CAN {ours['input.can']:.1f} ns")
    print(f"input_bench: HID boot mouse {mouse_ns:.1f} ns a report (hid-tools "
          f"{m_ns / mouse_ns:.0f}x slower), NKRO {nkro_ns:.1f} ns (hid-tools {k_ns / nkro_ns:.0f}x);"
          f" CAN {frame_ns:.1f} ns a frame (cantools {c_ns / frame_ns:.0f}x)")


if __name__ == "__main__":
    main()
