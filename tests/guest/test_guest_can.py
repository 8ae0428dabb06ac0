"""The SocketCAN backend (devices/can_dev.c) on a real kernel: guest_can runs in the QEMU guest
with vcan, can_raw, canplayer and posture-input, and prints every event the device set gives.

The reference is independent of our decoder: cantools decodes the same candump log through the
vendor's DBC (tests/input/can/panel.dbc, mended as make_expect.py mends it) on the host, and
the event rule of devices/can_input.h (a valuator when its value changes, a button on its
edges; the panel released and its dials stale when the interface goes down or the bus off;
a dial stale once after its stale= time; INPUT_REMOVED when the interface goes) turns those
values into the events we must see. python-can reads the recording posture-input made of the
second half and the half canplayer played, and they must hold the same frames.

The guest map is panel.map with stale=0 on every line (TCG's timing is not the panel's), plus
one dial on id 185 with stale=500, which the guest sends once and then leaves silent: its
stale event can only come from the backend's timer.
"""

import os
import re
import shutil
import sys

import can
import cantools
import pytest

from tier import BUILD, ROOT, assert_checks, require_tier, run_program

CAN_DIR = os.path.join(ROOT, "tests", "input", "can")
sys.path.insert(0, CAN_DIR)
import make_expect  # noqa: E402

SPLIT = 110                 # frames of panel.log played before vcan0 goes down
BTN_TRIGGER_HAPPY1 = 0x2C0  # linux/input-event-codes.h: a button line's default code (can_map.h)
PROBE = ("axis", "185", "0|16@1+", "Extra.Probe", 500)
PROBE_DATA = b"\x34\x12"    # what guest_can sends on 185: little-endian 0x1234


def guest_map(path):
    """panel.map with stale=0 on every line, and the probe dial: (lines as (kind, name))"""
    out, lines = [], []
    with open(os.path.join(CAN_DIR, "panel.map")) as f:
        for line in f:
            words = line.split("#")[0].split()
            if not words:
                out.append(line.rstrip("\n"))
                continue
            words = [w for w in words if not w.startswith("stale=")] + ["stale=0"]
            out.append(" ".join(words))
            lines.append((words[0], words[3]))
    out.append("%s %s %s %s stale=%d" % PROBE)
    lines.append((PROBE[0], PROBE[3]))
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")
    return lines


def cantools_values(frames, lines):
    """per frame: [(line index, value)] in map order, by cantools through the DBC"""
    mod = make_expect.load_dbc2panel()
    with open(os.path.join(CAN_DIR, "panel.dbc"), encoding="cp1252", newline="") as f:
        text = f.read().replace("\r\n", "\n")
    db = cantools.database.load_string(mod.repair(text, lambda *a, **k: None), "dbc",
                                       strict=False)
    index = {name: i for i, (_, name) in enumerate(lines)}
    out = []
    for msg in frames:
        m = db.get_message_by_frame_id(msg.arbitration_id, force_extended_id=msg.is_extended_id)
        got = make_expect.decode(m, bytes(msg.data))
        out.append(sorted((index[f"{m.name}.{s}"], float(v)) for s, v in got.items()
                          if f"{m.name}.{s}" in index))
    return out


class Panel:
    """the event rule of devices/can_input.h, fed cantools' values"""

    def __init__(self, lines):
        self.lines = lines
        self.code = {}
        for i, (kind, _) in enumerate(lines):
            if kind == "button":
                self.code[i] = BTN_TRIGGER_HAPPY1 + sum(1 for k, _ in lines[:i] if k == "button")
        self.value, self.seen, self.stale, self.pressed = {}, set(), set(), set()

    def frame(self, decoded):
        ev = []
        for i, v in decoded:
            if self.lines[i][0] == "button":
                if (v != 0) != (i in self.pressed):
                    ev.append(("button", self.code[i], int(v != 0), 0.0, 0))
                    (self.pressed.add if v != 0 else self.pressed.discard)(i)
            elif i not in self.seen or i in self.stale or self.value[i] != v:
                ev.append(("valuator", i, 0, v, 0))
            self.value[i] = v
            self.seen.add(i)
            self.stale.discard(i)
        return ev + [("frame", 0, 0, 0.0, 0)] if ev else ev

    def silent(self, stale_valuators=True, only=None):
        ev = []
        for i, (kind, _) in enumerate(self.lines):
            if only is not None and i not in only:
                continue
            if kind == "button" and i in self.pressed:
                ev.append(("button", self.code[i], 0, 0.0, 0))
                self.pressed.discard(i)
            elif kind != "button" and stale_valuators and i in self.seen and i not in self.stale:
                ev.append(("valuator", i, 0, self.value[i], 1))
                self.stale.add(i)
        return ev + [("frame", 0, 0, 0.0, 0)] if ev else ev


def segments(out):
    """the guest's events between its marks: {mark: [(kind, code, value, x, flags)]}"""
    seg, cur = {}, None
    for line in out.splitlines():
        if line.startswith("mark "):
            cur = line.split()[1]
            seg[cur] = []
        elif line.startswith("ev ") and cur:
            _, kind, code, value, x, flags = line.split()
            seg[cur].append((kind, int(code), int(value), float(x), int(flags)))
    return seg


def same_events(got, want, where):
    assert len(got) == len(want), "%s: %d events, want %d:\n%s\n%s" % (
        where, len(got), len(want), got[:12], want[:12])
    for k, (g, w) in enumerate(zip(got, want)):
        assert g[:3] == w[:3] and g[4] == w[4], "%s event %d: %s, want %s" % (where, k, g, w)
        assert abs(g[3] - w[3]) <= 1e-9 * max(1.0, abs(w[3])), \
            "%s event %d: %r, cantools %r" % (where, k, g[3], w[3])


def test_guest_can(tmp_path):
    require_tier()
    canplayer = shutil.which("canplayer")
    if canplayer is None:
        pytest.skip("kernel tier: canplayer is not installed (Debian package can-utils)")
    tool = BUILD / "bin" / "posture-input"

    lines = guest_map(tmp_path / "panel.map")
    with open(os.path.join(CAN_DIR, "panel.log")) as f:
        log = [l for l in f if l.startswith("(")]
    (tmp_path / "log1").write_text("".join(log[:SPLIT]))
    (tmp_path / "log2").write_text("".join(log[SPLIT:]))
    n1, n2 = SPLIT, len(log) - SPLIT

    status, output = run_program(
        "guest_can", ["vcan", "can_raw"],
        ["/guest/panel.map", "/guest/log1", n1, "/guest/log2", n2,
         "/usr/local/bin/posture-input"],
        files=["%s:/guest/%s" % (tmp_path / f, f) for f in ("panel.map", "log1", "log2")],
        exes=[canplayer, tool])
    assert_checks(status, output, [
        "missing interface skipped: no such CAN interface", "rescan opens vcan0 as a panel",
        "canplayer first half read", "vcan0 down seen", "canplayer second half read after up",
        "kernel filters", "overflow counted", "vcan0 deleted: the device removed",
        "vcan0 created again (down): a rescan opens it", "vcan0 up after the open: frames read"])
    out = "".join(line + "\n" for line in output)

    # the events, against cantools' values through the event rule
    played = list(can.CanutilsLogReader(os.path.join(CAN_DIR, "panel.log")))
    assert len(played) == len(log)
    values = cantools_values(played, lines)
    panel = Panel(lines)
    seg = segments(out)
    want = [e for v in values[:SPLIT] for e in panel.frame(v)]
    same_events(seg["start"], want, "first half")
    same_events(seg["down"], panel.silent(), "vcan0 down")
    want = [e for v in values[SPLIT:] for e in panel.frame(v)]
    same_events(seg["up"], want, "second half, after up")
    assert seg["filters"] == [] and seg["overflow"] == []
    bus_off = "ok bus-off error frame counted" in out
    same_events(seg["busoff"], panel.silent() if bus_off else [], "bus-off")
    probe = len(lines) - 1
    same_events(seg["probe"], panel.frame([(probe, float(int.from_bytes(PROBE_DATA, "little")))]),
                "probe frame")
    same_events(seg["silent"], panel.silent(only={probe}), "probe stale by the timer")
    same_events(seg["del"], panel.silent(stale_valuators=False)
                + [("removed", 2, 0, 0.0, 0)], "vcan0 deleted")

    # the log lines that say what happened, once each
    for said, times in (("interface vcan0 went down: ", 1),
                        ("interface vcan0 is down: frames will be read when it is up", 1),
                        ("frames again on vcan0", 3 if bus_off else 2),
                        ("the bus is off (error frame: bus-off): ", 1 if bus_off else 0),
                        ("interface vcan0 gone (No such device)", 1)):
        assert out.count("posture: panel (vcan0): device fault: " + said) == times, said
    assert "posture: panel (vcan0): bug: the kernel dropped " in out

    # the recording of the second half: the frames canplayer played, as python-can reads them
    rec = out.split("rec-begin\n", 1)[1].split("rec-end\n", 1)[0]
    assert re.fullmatch(r"(\(\d{10}\.\d{6}\) vcan0 [0-9A-F]{3,8}#[0-9A-F]*\n)+", rec), rec[:300]
    (tmp_path / "rec.log").write_text(rec)
    recorded = list(can.CanutilsLogReader(str(tmp_path / "rec.log")))
    assert len(recorded) == n2
    for r, w in zip(recorded, played[SPLIT:]):
        assert (r.arbitration_id, r.is_extended_id, bytes(r.data)) == \
            (w.arbitration_id, w.is_extended_id, bytes(w.data))
        assert r.channel == "vcan0"
    # canplayer keeps the log's gaps (10 ms): the kernel's receive times show them
    span = recorded[-1].timestamp - recorded[0].timestamp
    want_span = played[-1].timestamp - played[SPLIT].timestamp
    assert abs(span - want_span) < 0.5, (span, want_span)
