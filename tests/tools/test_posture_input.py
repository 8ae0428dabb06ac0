"""tools/posture-input against independent readings of the same recordings: the evemu
file's own E: lines, cantools decoding a candump log with the DBC the map came from, and
hid-tools' field values put through the kernel's hid-input rules for --evemu."""
import os
import pathlib
import subprocess

import cantools
import pytest
from hidtools.hid import ReportDescriptor

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
TOOL = BUILD / "bin" / "posture-input"
DATA = ROOT / "tests" / "input"

EV_SYN, EV_KEY, EV_REL, EV_MSC = 0, 1, 2, 4
REL_X, REL_Y, REL_WHEEL, REL_WHEEL_HI_RES, MSC_SCAN, BTN_LEFT = 0, 1, 8, 11, 4, 0x110


def tool(*args, ok=True):
    proc = subprocess.run([str(TOOL), *map(str, args)], capture_output=True, text=True,
                          timeout=60)
    if ok:
        assert proc.returncode == 0, proc.stderr
    return proc


def evemu_events(text):
    """(time, type, code, value) of every E: line"""
    out = []
    for line in text.splitlines():
        if line.startswith("E:"):
            t, ty, co, va = line[2:].split("#")[0].split()
            out.append((t, int(ty, 16), int(co, 16), int(va)))
    return out


@pytest.mark.parametrize("name", ["mouse", "keyboard"])
def test_decode_evemu_gives_each_frames_events(name):
    path = DATA / "evdev" / f"{name}.evemu"
    want_motion, want_keys, frames = [], [], 0
    dx = dy = 0
    for _, ty, co, va in evemu_events(path.read_text()):
        if ty == EV_REL and co == REL_X:
            dx += va
        elif ty == EV_REL and co == REL_Y:
            dy += va
        elif ty == EV_KEY:
            want_keys.append((co, va))
        elif ty == EV_SYN and co == 0:
            frames += 1
            if dx or dy:
                want_motion.append((dx, dy))
            dx = dy = 0
    lines = [l.split() for l in tool("decode", path).stdout.splitlines()]
    got_motion = [(float(l[3]), float(l[4])) for l in lines if l[2] == "motion"]
    got_keys = [l for l in lines if l[2] in ("key", "button")]
    assert got_motion == want_motion
    assert len(got_keys) == len(want_keys)
    assert sum(1 for l in lines if l[2] == "frame") == frames


def test_decode_candump_with_the_map_agrees_with_cantools():
    db = cantools.database.load_file(str(DATA / "can" / "panel.dbc"), strict=False)
    by_id = {m.frame_id | (0x80000000 if m.is_extended_frame else 0): m for m in db.messages}
    want = []
    for line in (DATA / "can" / "panel.log").read_text().splitlines():
        t, _, frame = line.split()[:3]
        ident, data = frame.split("#")
        can_id = int(ident, 16) | (0x80000000 if len(ident) == 8 else 0)
        data = bytes.fromhex(data.replace(".", ""))
        msg = by_id.get(can_id)
        if msg is None or data.startswith(b"R"):
            continue
        try:
            values = msg.decode(data, decode_choices=False, allow_truncated=True)
        except cantools.database.DecodeError:
            continue  # overlapping signals: cantools will not decode the whole message
        if values:
            want.append((t, {f"{msg.name}.{k}": v for k, v in values.items()}))
    got = []
    out = tool("decode", DATA / "can" / "panel.log", "--map", DATA / "can" / "panel.map").stdout
    for line in out.splitlines():
        words = line.split()
        got.append((words[0], {k: float(v) for k, v in (w.split("=") for w in words[2:])}))
    got_by_t = dict(got)
    assert want, "cantools decoded nothing"
    for t, values in want:
        assert t in got_by_t, t
        for k, v in values.items():
            assert got_by_t[t][k] == pytest.approx(v, rel=1e-12, abs=1e-12), (t, k)


def kernel_events(rdesc, reports):
    """hid-input for a mouse, from hid-tools' field values: per report, buttons that
    changed (MSC_SCAN then EV_KEY), REL_X, REL_Y, REL_WHEEL with its 1/120, SYN_REPORT"""
    rd = ReportDescriptor.from_bytes(rdesc)
    report = next(iter(rd.input_reports.values()))
    held = {}
    out = []
    for t, buf in reports:
        evs = []
        for f in report.fields:
            if f.type & 1:
                continue
            values = f.get_values(buf)
            for i, v in enumerate(values):
                usage = f.usages[i] if f.usages else f.usage
                page, u = usage >> 16, usage & 0xFFFF
                if page == 9:
                    if held.get(u, 0) != v:
                        held[u] = v
                        evs += [(EV_MSC, MSC_SCAN, usage), (EV_KEY, BTN_LEFT + u - 1, v)]
                elif page == 1 and u in (0x30, 0x31) and v:
                    evs.append((EV_REL, REL_X if u == 0x30 else REL_Y, v))
                elif page == 1 and u == 0x38 and v:
                    evs += [(EV_REL, REL_WHEEL, v), (EV_REL, REL_WHEEL_HI_RES, 120 * v)]
        if evs:
            out += [(t, *e) for e in evs] + [(t, EV_SYN, 0, 0)]
    return out


def test_decode_evemu_gives_the_events_hid_input_gives(tmp_path):
    rdesc_text = (DATA / "hid" / "qemu_mouse.rdesc").read_text()
    rdesc = bytes.fromhex("".join(l.split("#")[0] for l in rdesc_text.splitlines()))
    reports = [(0, bytes([0, 1, 0xFF, 0])), (120004, bytes([1, 0, 0, 0])),
               (200000, bytes([3, 0x7F, 0x81, 0xFF])), (300001, bytes([2, 0, 0, 0])),
               (400002, bytes([0, 0, 0, 0])), (500003, bytes([0, 0, 0, 3]))]
    rec = tmp_path / "mouse.hid"
    lines = [f"R: {len(rdesc)} " + " ".join(f"{b:02x}" for b in rdesc), "N: test mouse",
             "I: 3 0627 0001"]
    lines += [f"E: {t // 1000000:06d}.{t % 1000000:06d} {len(b)} " + " ".join(f"{x:02x}" for x in b)
              for t, b in reports]
    rec.write_text("\n".join(lines) + "\n")
    got = [(t, ty, co, va) for t, ty, co, va in evemu_events(tool("decode", "--evemu", rec).stdout)]
    want = [(f"{t // 1000000}.{t % 1000000:06d}", ty, co, va)
            for t, ty, co, va in kernel_events(rdesc, reports)]
    assert got == want


@pytest.mark.parametrize("name", ["qemu_mouse", "qemu_keyboard", "nkro_keyboard",
                                  "report_ids", "mouse12"])
def test_describe_gives_hid_tools_field_offsets(name):
    text = (DATA / "hid" / f"{name}.rdesc").read_text()
    rdesc = bytes.fromhex("".join(l.split("#")[0] for l in text.splitlines()))
    rd = ReportDescriptor.from_bytes(rdesc)
    out = tool("describe", DATA / "hid" / f"{name}.rdesc").stdout
    # ours: one line per main item ("bit B: C x S bits, variable|array|constant ...");
    # hid-tools: a field per value of a variable item, one per array or constant item
    ours = []
    id_bits = 8 if "numbered" in out.splitlines()[0] else 0  # hid-tools counts the id byte
    for line in out.splitlines():
        if not line.startswith("  bit "):
            continue
        start = int(line.split(":")[0].split()[1]) + id_bits
        count, _, size = line.split(":")[1].split(",")[0].split()[:3]
        if ", variable" in line:
            ours += [start + i * int(size) for i in range(int(count))]
        else:
            ours.append(start)
    theirs = [f.start for r in rd.input_reports.values() for f in r.fields]
    ours, theirs = sorted(ours), sorted(theirs)
    assert ours == theirs


def test_bad_files_are_refused_clearly(tmp_path):
    junk = tmp_path / "junk.txt"
    junk.write_text("hello\n")
    r = tool("decode", junk, ok=False)
    assert r.returncode == 1 and "not an evemu, hid-recorder or candump recording" in r.stderr
    r = tool("decode", DATA / "can" / "panel.log", ok=False)
    assert r.returncode == 2 and "--map" in r.stderr
    bad = tmp_path / "bad.hid"
    bad.write_text("R: 3 05 01\n")
    r = tool("decode", bad, ok=False)
    assert r.returncode == 1 and "bad.hid:1" in r.stderr
    r = tool("describe", tmp_path / "missing", ok=False)
    assert r.returncode == 1 and "missing" in r.stderr
