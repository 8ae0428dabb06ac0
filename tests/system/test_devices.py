"""The daemon reading an evdev device itself (--input evdev:PATH), on the real open/read path
under umockdev: a mocked mouse replays an evemu recording written by libevemu, and a
subscriber gets the events `posture-input decode` gives for the same file, from device 0;
`list devices` says what is open and what was skipped."""
import os
import pathlib
import shutil
import subprocess

import pytest

from daemon import Daemon, ROOT

BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
EVDEV = ROOT / "tests" / "input" / "evdev"
MOCK = ROOT / "tests" / "input" / "umockdev"
UMOCKDEV_RUN = shutil.which("umockdev-run")
NODE = "/dev/input/event9"

pytestmark = pytest.mark.skipif(
    UMOCKDEV_RUN is None, reason="umockdev-run is not installed (Debian package umockdev)")


def delayed(src, dest, seconds):
    """the recording with its events moved `seconds` later behind an empty frame at 0, so
    that the replay, which starts when the daemon opens the device, waits for a subscriber"""
    out = []
    first = True
    for line in src.read_text().splitlines():
        if line.startswith("E:"):
            if first:
                out.append("E: 0.000000 0000 0000 0000")
                first = False
            t, rest = line[2:].split(None, 1)
            sec, usec = t.split(".")
            total = int(sec) * 1000000 + int(usec) + int(seconds * 1e6)
            line = f"E: {total // 1000000}.{total % 1000000:06d} {rest}"
        out.append(line)
    dest.write_text("\n".join(out) + "\n")


def expected(path):
    """(kind, values...) of every non-frame event, by our decoder straight from the file"""
    out = subprocess.run([str(BUILD / "bin" / "posture-input"), "decode", str(path)],
                         capture_output=True, text=True, check=True).stdout
    return [tuple(line.split()[2:]) for line in out.splitlines()
            if line.split()[2] != "frame"]


def as_tuple(ev):
    if ev["kind"] == "motion":
        return ("motion", f"{ev['dx']:g}", f"{ev['dy']:g}")
    if ev["kind"] in ("button", "key"):
        return (ev["kind"], ev["name"], str(ev["value"]))
    if ev["kind"] == "wheel":
        return ("wheel", ev["axis"], str(ev["detents"]), f"{ev['hires']:g}")
    return (ev["kind"],)


def test_a_mocked_mouse_reaches_subscribers(tmp_path):
    rec = tmp_path / "mouse.evemu"
    delayed(EVDEV / "mouse.evemu", rec, 3.0)
    d = Daemon(extra=("--input", f"evdev:{NODE}", "--input", "evdev:/dev/input/event77"))
    d.argv = [UMOCKDEV_RUN, "-d", str(MOCK / "mouse.umockdev"), "-i", f"{NODE}={MOCK}/mouse.ioctl",
              "-e", f"{NODE}={rec}", "--"] + d.argv
    d.start()
    try:
        with d.client() as c:
            c.subscribe("input")
            listed = c.request("list devices")
            assert [(x["device"], x["path"], x["class"], x["backend"]) for x in listed["devices"]] \
                == [(0, NODE, "mouse", "evdev")]
            assert listed["devices"][0]["name"] == "Posture Test 3-Button Wheel Mouse"
            assert [s["what"] for s in listed["skipped"]] == ["/dev/input/event77"]
            want = expected(EVDEV / "mouse.evemu")
            got = []
            for ev in c.events(timeout=10):
                assert ev["device"] == 0, ev
                if ev["kind"] not in ("frame", "added"):  # added: if it came after subscribe
                    got.append(as_tuple(ev))
                if len(got) == len(want):
                    break
            assert got == [tuple(w) for w in want]
    finally:
        d.stop()
        d.cleanup()


def test_motion_in_pixels_follows_the_mouses_dpi_from_udev(tmp_path):
    """udev's MOUSE_DPI (hwdb form, default marked '*') reaches `list devices` through
    libudev, and motion in pixels is the counts * gain * 1000 / DPI with the fractions
    kept; the raw counts stay beside them."""
    desc = tmp_path / "mouse.umockdev"
    text = (MOCK / "mouse.umockdev").read_text()
    desc.write_text(text.replace("E: ID_INPUT_MOUSE=1\n",
                                 "E: ID_INPUT_MOUSE=1\nE: MOUSE_DPI=400@125 *800@125 1600@125\n", 1))
    rec = tmp_path / "mouse.evemu"
    delayed(EVDEV / "mouse.evemu", rec, 3.0)
    d = Daemon(extra=("--input", f"evdev:{NODE}", "--pointer-gain", "2"))
    d.argv = [UMOCKDEV_RUN, "-d", str(desc), "-i", f"{NODE}={MOCK}/mouse.ioctl",
              "-e", f"{NODE}={rec}", "--"] + d.argv
    d.start()
    try:
        with d.client() as c:
            c.subscribe("input")
            listed = c.request("list devices")
            assert listed["devices"][0]["dpi"] == 800
            assert listed["devices"][0]["reads"] >= 0 and listed["devices"][0]["errors"] == 0
            want = [w for w in expected(EVDEV / "mouse.evemu") if w[0] == "motion"]
            got = []
            for ev in c.events(timeout=10):
                if ev["kind"] == "motion":
                    got.append(ev)
                if len(got) == len(want):
                    break
            assert [(f"{e['dx']:g}", f"{e['dy']:g}") for e in got] == [w[1:] for w in want]
            k = 2 * 1000 / 800  # 2.5 px a count
            for axis, pix in (("dx", "px"), ("dy", "py")):
                rem = 0.0
                for e in got:
                    rem += k * e[axis]
                    whole = int(rem)
                    rem -= whole
                    assert e[pix] == whole, (axis, e)
    finally:
        d.stop()
        d.cleanup()
