"""Recorded devices: a keyboard and a mouse read directly (evdev, under umockdev,
replaying evemu files written here) type and drag at the kiosk while the daemon records; the
recording keeps their bytes as evemu files and every call into their decoders in the frame
log, and its replay feeds the same bytes through the same decoders to the same postures.

The references: the evemu files umockdev played (the kernel's records, which must come out of
the recording's device files in the same order), and the live daemon's posture hash."""
import re
import subprocess
import time

import pytest

from daemon import POSTURED
from test_kiosk_recorded import KEYBOARD, MOUSE, UMOCKDEV_RUN, typing, umockdev_daemon
from test_input import kernel_codes

pytestmark = pytest.mark.skipif(
    UMOCKDEV_RUN is None, reason="umockdev-run is not installed (Debian package umockdev)")

REPLAY_LINE = re.compile(r"replay: frames=(\d+) posture=([0-9a-f]{16}) divergences=(\d+)$")


def events_of(text):
    """(type, code, value) of every E: line of an evemu file"""
    out = []
    for ln in text.splitlines():
        m = re.match(r"E: \d+\.\d{6} ([0-9a-f]{4}) ([0-9a-f]{4}) (-?\d+)", ln)
        if m:
            out.append((int(m[1], 16), int(m[2], 16), int(m[3])))
    return out


def test_a_keyboard_and_mouse_read_directly_replay_through_their_decoders(tmp_path):
    codes = kernel_codes()
    keys, t = typing("load human as rec", 2.5, codes)
    keys += [(t, 1, codes["KEY_ENTER"], 1), (t + 0.03, 1, codes["KEY_ENTER"], 0)]
    more, t = typing("behave rec on", t + 0.3, codes)
    keys += more + [(t, 1, codes["KEY_ENTER"], 1), (t + 0.03, 1, codes["KEY_ENTER"], 0)]
    more, t = typing("manipulate hand rec right", t + 0.3, codes)
    keys += more + [(t, 1, codes["KEY_ENTER"], 1), (t + 0.03, 1, codes["KEY_ENTER"], 0)]
    drag_at = t + 0.5
    keys += [(drag_at + 1.2, 1, codes["KEY_ESC"], 1), (drag_at + 1.23, 1, codes["KEY_ESC"], 0)]
    mouse = [(drag_at, 1, codes["BTN_LEFT"], 1)]
    mouse += [(drag_at + 0.02 * (i + 1), 2, 0, 3) for i in range(25)]  # REL_X
    mouse += [(drag_at + 0.6, 1, codes["BTN_LEFT"], 0)]
    rec = tmp_path / "rec"
    d = umockdev_daemon(tmp_path, keys, mouse, fps=1000, extra=("--record", str(rec)))
    d.start()
    try:
        with d.client() as c:
            c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
            deadline = time.monotonic() + 30
            while time.monotonic() < deadline and c.request("get kiosk")["mode"] != "hand":
                time.sleep(0.05)
            while time.monotonic() < deadline and c.request("get kiosk")["mode"] != "none":
                time.sleep(0.05)
            assert c.request("get kiosk")["mode"] == "none", "the session did not run through"
            time.sleep(0.3)
            live = c.request("status")["posture"]
            assert [f["name"] for f in c.request("list figures")["figures"]] == ["rec"]
    finally:
        d.stop()
        d.cleanup()
    manifest = (rec / "manifest").read_text()
    files = re.findall(r"^file (dev\d+\.evemu) evemu device (\d+): (\S+)", manifest, re.M)
    assert sorted(p for _, _, p in files) == sorted([MOUSE, KEYBOARD]), manifest
    # the recording's device files hold what the kernel passed on, in order
    for name, _, path in files:
        source = (tmp_path / ("mouse.evemu" if path == MOUSE else "keys.evemu")).read_text()
        want = [e for e in events_of(source) if e != (0, 0, 0)]
        got = [e for e in events_of((rec / name).read_text()) if e != (0, 0, 0)]
        assert got == want, name
        head = (rec / name).read_text()
        assert head.startswith("# EVEMU 1.3") and "\nN: " in head and "\nB: " in head
    log = (rec / "frames").read_text()
    assert re.search(r"^dev \d+ bytes \d+ \d+$", log, re.M)
    assert re.search(r"^event \d+ \d+ 6 ", log, re.M) is None  # no device arrived mid-recording
    p = subprocess.run([str(POSTURED), "--replay", str(rec)], capture_output=True, text=True,
                       timeout=120)
    assert p.returncode == 0, p.stderr
    m = REPLAY_LINE.search(p.stdout)
    assert m and m[2] == live and m[3] == "0", (p.stdout, p.stderr)


def test_a_hid_mouse_read_through_hidapi_is_recorded_as_hid_recorder_does(tmp_path):
    """the hidraw backend recorded: its reports in a hid-recorder file that hid-tools' own
    hid-decode reads (the reports the mock played, in order), and the replay's posture the
    live one"""
    import shutil
    import sys as _sys
    from daemon import ROOT, Daemon
    _sys.path.insert(0, str(ROOT / "tests" / "input" / "hid"))
    import hidmock
    desc, name, ids, _ = hidmock.read_recording(ROOT / "tests" / "input" / "hid" /
                                                "hidtools_mouse.hid")
    reports = [bytes([1, 0, 0, 0])] + [bytes([1, 8, 0, 0])] * 12 + [bytes([0, 0, 0, 0])]
    paths = hidmock.write_mock(tmp_path, desc, name, ids, reports, first_ms=3000, pace_ms=40)
    rec = tmp_path / "rec"
    d = Daemon(fps=1000, extra=("--input", "hidraw:%04x:%04x" % (ids[1], ids[2]),
                                "--record", str(rec)))
    d.argv = [UMOCKDEV_RUN] + hidmock.umockdev_args(paths) + ["--"] + d.argv
    d.start()
    try:
        with d.client() as c:
            c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
            c.request("load human as hid")
            c.request("manipulate figure hid")
            deadline = time.monotonic() + 20
            while time.monotonic() < deadline and not c.request("get kiosk")["step"]:
                time.sleep(0.02)
            while time.monotonic() < deadline and c.request("get kiosk")["step"]:
                time.sleep(0.02)
            time.sleep(0.2)
            live = c.request("status")["posture"]
    finally:
        d.stop()
        d.cleanup()
    files = re.findall(r"^file (dev\d+\.hid) hid-recorder device", (rec / "manifest").read_text(),
                       re.M)
    assert len(files) == 1
    text = (rec / files[0]).read_text()
    got = [bytes(int(h, 16) for h in ln.split()[3:]) for ln in text.splitlines()
           if ln.startswith("E: ")]
    assert got == reports
    decode = shutil.which("hid-decode", path=str(ROOT / ".venv" / "bin")) or shutil.which(
        "hid-decode")
    if decode:  # hid-tools' own parser reads the file's descriptor back, item by item
        p = subprocess.run([decode, str(rec / files[0])], capture_output=True, text=True,
                           timeout=60)
        assert p.returncode == 0, p.stderr
        assert "R: %d %s" % (len(desc), " ".join("%02x" % b for b in desc)) in p.stdout
        assert "Usage (Wheel)" in p.stdout
    p = subprocess.run([str(POSTURED), "--replay", str(rec)], capture_output=True, text=True,
                       timeout=120)
    assert p.returncode == 0, p.stderr
    m = REPLAY_LINE.search(p.stdout)
    assert m and m[2] == live and m[3] == "0", (p.stdout, p.stderr)
