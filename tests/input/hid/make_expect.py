#!/usr/bin/env python3
"""Writes <name>.expect for each <name>.rdesc here: a set of input reports
for the descriptor and the field values hid-tools decodes from them, so
tests/test_hid.c can check our decoder against an independent one.

Run with the project's venv (it has hid-tools):
    .venv/bin/python tests/input/hid/make_expect.py [OUTDIR]

Lines of an .expect file:
    L: <report id> <bytes>                    each input report's length (id byte included)
    E: <hex bytes>                            a report; the lines below decode it
    V: <bit> <size> <usage> <value>           a variable field's non-zero value (bit from
                                              the report's first byte, id byte included);
                                              the values not listed are 0
    A: <bit> <size> <count> <v>=<usage> ...   an array field's values, each with the
                                              usage it names ('-' for none)
Constant fields are left out (the kernel ignores them too).

hid-tools 0.12 replaces a first Usage Minimum/Maximum pair by a second one
where the kernel appends the two (drivers/hid/hid-core.c,
hid_parser_local); for the descriptors in KERNEL_RANGES its usages are
wrong, so they are written as '?' and test_hid.c checks those by hand
against the kernel's rule. Values and bit positions are still hid-tools'.
"""
import os
import random
import sys

import hidtools
from hidtools.hid import ReportDescriptor
from hidtools.hidraw import HidrawDevice, HidrawEvent
from hidtools.util import BusType

HERE = os.path.dirname(os.path.abspath(__file__))
KERNEL_RANGES = {"two_ranges"}
ERROR_ROLLOVER = 0x00070001


def read_rdesc(path):
    out = []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0]
            out.extend(int(tok, 16) for tok in line.split())
    return out


def put(buf, start, size, value):
    """Writes value's low `size` bits at bit `start` (little-endian)."""
    value &= (1 << size) - 1
    for i in range(size):
        bit = start + i
        if value >> i & 1:
            buf[bit // 8] |= 1 << (bit % 8)
        else:
            buf[bit // 8] &= ~(1 << (bit % 8)) & 0xFF


def interesting(lo, hi, size):
    """Edge values of a field: the logical range's ends and the usual suspects."""
    cand = [lo, hi, 0, 1, -1, lo + 1, hi - 1, 127, -127, 2047, -2048, 32767, -32768, 255]
    smin, umax = -(1 << (size - 1)), (1 << size) - 1
    seen = []
    for v in cand:
        if smin <= v <= umax and v not in seen:
            seen.append(v)
    return seen


def reports_for(report):
    """The reports to decode: zeros, each button combination or alone, edge
    values of each axis, each array usage, two keys at once, ErrorRollOver,
    and seeded random bytes."""
    nbytes = (report.bitsize + 7) // 8
    data = [f for f in report.fields if not f.type & 1]
    bits = [f for f in data if f.usages is None and f.size == 1]
    wide = [f for f in data if f.usages is None and f.size > 1]
    arrays = [f for f in data if f.usages is not None]

    def blank():
        buf = [0] * nbytes
        if report.numbered:
            buf[0] = report.report_ID
        return buf

    out = [blank()]
    # buttons: every combination of up to 8, else each alone and all
    if 0 < len(bits) <= 8:
        for mask in range(1, 1 << len(bits)):
            buf = blank()
            for i, f in enumerate(bits):
                put(buf, f.start, 1, mask >> i & 1)
            out.append(buf)
    elif bits:
        for f in bits:
            buf = blank()
            put(buf, f.start, 1, 1)
            out.append(buf)
        buf = blank()
        for f in bits:
            put(buf, f.start, 1, 1)
        out.append(buf)
    # axes: their edge values one at a time
    for f in wide:
        for v in interesting(f.logical_min, f.logical_max, f.size):
            buf = blank()
            put(buf, f.start, f.size, v)
            out.append(buf)
    # arrays: each usage in the first slot, two at once, ErrorRollOver
    for f in arrays:
        for k in range(len(f.usages)):
            v = f.logical_min + k
            if v > f.logical_max:
                break
            buf = blank()
            put(buf, f.start, f.size, v)
            out.append(buf)
        if f.count > 1 and len(f.usages) > 6:
            buf = blank()
            put(buf, f.start, f.size, f.logical_min + 4)
            put(buf, f.start + f.size, f.size, f.logical_min + 5)
            out.append(buf)
        if ERROR_ROLLOVER in f.usages:
            buf = blank()
            v = f.logical_min + f.usages.index(ERROR_ROLLOVER)
            for i in range(f.count):
                put(buf, f.start + i * f.size, f.size, v)
            out.append(buf)
    # random bytes
    rng = random.Random(report.report_ID * 7919 + nbytes)
    for _ in range(24):
        buf = [rng.randrange(256) for _ in range(nbytes)]
        if report.numbered:
            buf[0] = report.report_ID
        out.append(buf)
    return out


def decode(report, buf, usages_known):
    lines = []
    for f in report.fields:
        if f.type & 1:
            continue
        values = f.get_values(buf)
        if f.usages is None:
            if values[0] == 0:
                continue
            usage = f"0x{f.usage:08x}" if usages_known else "?"
            lines.append(f"V: {f.start} {f.size} {usage} {values[0]}")
            continue
        items = []
        for v in values:
            k = v - f.logical_min
            if not usages_known:
                u = "?"
            elif f.logical_min <= v <= f.logical_max and 0 <= k < len(f.usages):
                u = f"0x{f.usages[k]:08x}"
            else:
                u = "-"
            items.append(f"{v}={u}")
        lines.append(f"A: {f.start} {f.size} {f.count} " + " ".join(items))
    return lines


def make(name, outdir):
    rdesc = read_rdesc(os.path.join(HERE, name + ".rdesc"))
    rd = ReportDescriptor.from_bytes(rdesc)
    known = name not in KERNEL_RANGES
    out = [
        f"# {name}: input field values as hid-tools {hidtools.__version__} decodes them",
        "# written by make_expect.py from " + name + ".rdesc; do not edit",
    ]
    reports = list(rd.input_reports.values())
    for r in reports:
        out.append(f"L: {max(r.report_ID, 0)} {(r.bitsize + 7) // 8}")
    for r in reports:
        for buf in reports_for(r):
            out.append("E: " + " ".join(f"{b:02x}" for b in buf))
            out.extend(decode(r, buf, known))
    with open(os.path.join(outdir, name + ".expect"), "w") as f:
        f.write("\n".join(out) + "\n")


# the reports of the recordings hid-tools writes: (sec, usec, bytes)
MOUSE_EVENTS = [(0, 0, [0x00, 0x01, 0xFF, 0x00]), (0, 120004, [0x01, 0x00, 0x00, 0x00]),
                (1, 5, [0x00, 0x00, 0x00, 0x01])]
KEYBOARD_EVENTS = [(0, 50000, [0x00, 0x00, 0x04, 0x00, 0x00, 0x00, 0x00, 0x00]),
                   (0, 200000, [0x00] * 8)]


def fake_device(name, rdesc_name, bus, vid, pid, events):
    """A HidrawDevice without a hidraw node: hid-tools' own dump() writes it."""
    dev = HidrawDevice.__new__(HidrawDevice)
    dev.device = None
    dev.name = name
    dev.bustype = BusType(bus)
    dev.vendor_id, dev.product_id = vid, pid
    dev.report_descriptor = ReportDescriptor.from_bytes(
        read_rdesc(os.path.join(HERE, rdesc_name + ".rdesc")))
    dev.events = [HidrawEvent(s, us, b) for s, us, b in events]
    dev._dump_offset = -1
    dev.time_offset = None
    return dev


def make_recordings(outdir):
    """hidtools_mouse.hid: one device, written by HidrawDevice.dump().
    hidtools_two.hid: two devices, with the D: lines hid-recorder
    (hidtools/cli/record.py) prints around each device's dump()."""
    mouse = fake_device("QEMU QEMU USB Mouse", "qemu_mouse", 0x03, 0x0627, 0x0001, MOUSE_EVENTS)
    with open(os.path.join(outdir, "hidtools_mouse.hid"), "w") as f:
        mouse.dump(f)
    devs = [fake_device("QEMU QEMU USB Mouse", "qemu_mouse", 0x03, 0x0627, 0x0001, []),
            fake_device("QEMU QEMU USB Keyboard", "qemu_keyboard", 0x03, 0x0627, 0x0001, [])]
    with open(os.path.join(outdir, "hidtools_two.hid"), "w") as f:
        # record.py: a D: line before each device's header
        for idx, d in enumerate(devs):
            print(f"D: {idx}", file=f)
            d.dump(f)
        # ... and before a device's events when the device changes
        last = -1
        order = [(0, MOUSE_EVENTS[0]), (1, KEYBOARD_EVENTS[0]), (0, MOUSE_EVENTS[1]),
                 (1, KEYBOARD_EVENTS[1])]
        for idx, ev in order:
            devs[idx].events.append(HidrawEvent(*ev))
            if last != idx:
                print(f"D: {idx}", file=f)
                last = idx
            devs[idx].dump(f)


def main():
    outdir = sys.argv[1] if len(sys.argv) > 1 else HERE
    names = sorted(n[:-6] for n in os.listdir(HERE) if n.endswith(".rdesc"))
    for name in names:
        make(name, outdir)
    make_recordings(outdir)
    print(f"{len(names)} expect files and 2 recordings in {outdir}")


if __name__ == "__main__":
    main()
