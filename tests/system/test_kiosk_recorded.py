"""The kiosk end to end through recorded input: under umockdev a keyboard and a
mouse replay evemu recordings made here (the kernel's codes from its own header) on the
daemon's real evdev path: the keyboard types commands at the edit line, the mouse drags
the figure in the mode they started, the keyboard's ESC ends it. Then a HID mouse (a
hid-tools recording's descriptor) replays reports through hidapi's hidraw path and drags.
The journal holds the typed commands and the drags' steps; the pictures go to the test
output."""
import shutil
import time

import pytest

from daemon import Daemon, ROOT, journal_records, write_picture
from kiosk_keys import key_lines
from test_input import kernel_codes

EVDEV = ROOT / "tests" / "input" / "evdev"
MOCK = ROOT / "tests" / "input" / "umockdev"
UMOCKDEV_RUN = shutil.which("umockdev-run")
MOUSE, KEYBOARD = "/dev/input/event9", "/dev/input/event10"

pytestmark = pytest.mark.skipif(
    UMOCKDEV_RUN is None, reason="umockdev-run is not installed (Debian package umockdev)")


def evemu(template, events):
    """template's description lines and events (t seconds, type, code, value), a frame each"""
    head = [ln for ln in template.read_text().splitlines() if not ln.startswith("E:")]
    out = head + ["E: 0.000000 0000 0000 0000"]
    for t, typ, code, value in events:
        us = int(round(t * 1e6))
        stamp = f"{us // 1000000}.{us % 1000000:06d}"
        out.append(f"E: {stamp} {typ:04x} {code:04x} {value:04d}")
        out.append(f"E: {stamp} 0000 0000 0000")
    return "\n".join(out) + "\n"


def umockdev_daemon(tmp_path, keys, mouse, fps=None, extra=()):
    """A daemon reading a keyboard and a mouse under umockdev, which replay the key and mouse
    events (t seconds, type, code, value) as evemu files written into tmp_path."""
    (tmp_path / "keys.evemu").write_text(evemu(EVDEV / "keyboard.evemu", keys))
    (tmp_path / "mouse.evemu").write_text(evemu(EVDEV / "mouse.evemu", mouse))
    d = Daemon(fps=fps, extra=("--input", f"evdev:{MOUSE}", "--input", f"evdev:{KEYBOARD}",
                               *extra))
    d.argv = [UMOCKDEV_RUN, "-d", str(MOCK / "mouse.umockdev"), "-d", str(MOCK / "keyboard.umockdev"),
              "-i", f"{MOUSE}={MOCK}/mouse.ioctl", "-i", f"{KEYBOARD}={MOCK}/keyboard.ioctl",
              "-e", f"{MOUSE}={tmp_path}/mouse.evemu", "-e", f"{KEYBOARD}={tmp_path}/keys.evemu",
              "--"] + d.argv
    return d


def typing(text, start, codes):
    """the key events a US keyboard sends for text, 30 ms apart"""
    events, t = [], start
    for line in key_lines(text):
        _, _, name, how = line.split()
        events.append((t, 1, codes[name], 1 if how == "down" else 0))
        t += 0.03
    return events, t


def test_a_recorded_keyboard_and_mouse_drive_the_kiosk(tmp_path):
    codes = kernel_codes()
    keys, t = typing("load human as rec", 3.0, codes)
    keys += [(t, 1, codes["KEY_ENTER"], 1), (t + 0.03, 1, codes["KEY_ENTER"], 0)]
    more, t = typing("manipulate figure rec", t + 0.5, codes)
    keys += more + [(t, 1, codes["KEY_ENTER"], 1), (t + 0.03, 1, codes["KEY_ENTER"], 0)]
    drag_at = t + 0.5
    keys += [(drag_at + 1.0, 1, codes["KEY_ESC"], 1), (drag_at + 1.03, 1, codes["KEY_ESC"], 0)]
    mouse = [(drag_at, 1, codes["BTN_LEFT"], 1)]
    mouse += [(drag_at + 0.02 * (i + 1), 2, 0, 4) for i in range(20)]  # REL_X, 80 counts
    mouse += [(drag_at + 0.5, 1, codes["BTN_LEFT"], 0)]
    d = umockdev_daemon(tmp_path, keys, mouse)
    d.start()
    try:
        with d.client() as c:
            c.request("add view front width=480 height=320 eye=0,1,3 target=0,1,0")
            assert [x["class"] for x in c.request("list devices")["devices"]] == ["mouse", "keyboard"]
            deadline = time.monotonic() + 20
            while time.monotonic() < deadline and c.request("get kiosk")["mode"] != "figure":
                time.sleep(0.05)
            assert [f["name"] for f in c.request("list figures")["figures"]] == ["rec"]
            start = c.request("get manip")["position"]
            while time.monotonic() < deadline and c.request("get kiosk")["mode"] != "none":
                time.sleep(0.05)
            moved = c.request("get site rec pelvis.root")["position"]
            write_picture(c, "front", "kiosk_recorded.png")
        assert moved[0] - start[0] > 0.05, (start, moved)  # dragged along x, to the right
        assert moved[1:] == pytest.approx(start[1:], abs=1e-9)
        marks = [(k, b) for _, k, b in journal_records(d.state_dir) if k in "CBE"]
        assert marks[:2] == [("C", "add view front width=480 height=320 eye=0,1,3 target=0,1,0"),
                             ("C", "load human as rec")]
        assert [k for k, _ in marks[2:]] == ["B", "E"]
    finally:
        d.stop()
        d.cleanup()


def test_a_hid_mouse_replayed_through_hidapi_drags_in_the_kiosk(tmp_path):
    """the same through the hidraw backend: a HID mouse (the hid-tools recording's
    descriptor, name and ids) under umockdev replays reports written here, 4 bytes each as
    its descriptor lays them out (buttons, x, y, wheel): the left button down, 12 steps of
    8 counts right, up"""
    import sys
    sys.path.insert(0, str(ROOT / "tests" / "input" / "hid"))
    import hidmock
    desc, name, ids, _ = hidmock.read_recording(ROOT / "tests" / "input" / "hid" / "hidtools_mouse.hid")
    reports = [bytes([1, 0, 0, 0])] + [bytes([1, 8, 0, 0])] * 12 + [bytes([0, 0, 0, 0])]
    paths = hidmock.write_mock(tmp_path, desc, name, ids, reports, first_ms=3000, pace_ms=40)
    d = Daemon(extra=("--input", "hidraw:%04x:%04x" % (ids[1], ids[2])))
    d.argv = [UMOCKDEV_RUN] + hidmock.umockdev_args(paths) + ["--"] + d.argv
    d.start()
    try:
        with d.client() as c:
            c.request("add view front width=480 height=320 eye=0,1,3 target=0,1,0")
            c.request("load human as hid")
            assert [x["backend"] for x in c.request("list devices")["devices"]] == ["hidraw"]
            c.request("manipulate figure hid")
            start = c.request("get manip")["position"]
            deadline = time.monotonic() + 20
            while time.monotonic() < deadline and not c.request("get kiosk")["step"]:
                time.sleep(0.02)
            while time.monotonic() < deadline and c.request("get kiosk")["step"]:
                time.sleep(0.02)
            moved = c.request("get manip")["position"]
            write_picture(c, "front", "kiosk_recorded_hid.png")
        assert moved[0] - start[0] > 0.02, (start, moved)
        assert moved[1:] == pytest.approx(start[1:], abs=1e-9)
        kinds = [k for _, k, _ in journal_records(d.state_dir)]
        assert [k for k in kinds if k in "BE"] == ["B", "E"]
    finally:
        d.stop()
        d.cleanup()
