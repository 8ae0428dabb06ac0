"""The hidraw backend (devices/hidraw_dev.c) on the real hidapi path, under umockdev.

umockdev-run fakes /sys and /dev: a hidraw node whose HID device, USB interface and USB device
are written (by this test, into tmp_path) from a hid-tools recording (tests/input/hid/
hidtools_mouse.hid: its R:, N: and I: lines), and whose reads replay the recording's E: reports
(a umockdev script, one `r` line a report, 150 ms apart so that no two reports merge in the
byte stream). Through it run hidapi's enumeration (the sysfs descriptor, the usage filter,
the USB interface number), hid_open_path, the reader thread's hid_read_timeout, and our
sysfs reads of the descriptor and the uevent. The recording is the reference: recording the
mocked node must give back its description and its reports, decoding it live what decoding
the file gives.

The device going away, the multipliers and floods are tested through the socketpair seam
(tests/test_hidraw.c) and against the kernel (tests/guest/test_guest_hidraw.py).
"""
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
TOOL = BUILD / "bin" / "posture-input"
RECORDING = ROOT / "tests" / "input" / "hid" / "hidtools_mouse.hid"
UMOCKDEV_RUN = shutil.which("umockdev-run")
sys.path.insert(0, str(ROOT / "tests" / "input" / "hid"))
import hidmock  # noqa: E402
NODE = hidmock.NODE

pytestmark = pytest.mark.skipif(
    UMOCKDEV_RUN is None, reason="umockdev-run is not installed (Debian package umockdev)")


@pytest.fixture(scope="module")
def mock(tmp_path_factory):
    """the .umockdev, .ioctl and .script files of the recorded mouse"""
    d = tmp_path_factory.mktemp("hidmouse")
    desc, name, ids, reports = hidmock.read_recording(RECORDING)
    hidmock.write_mock(d, desc, name, ids, reports)
    return d, desc, name, ids, reports


def mocked(mock, *args, timeout=60):
    d = mock[0]
    cmd = [UMOCKDEV_RUN, "-d", d / "hidmouse.umockdev", "-i", "%s=%s" % (NODE, d / "hidmouse.ioctl"),
           "-s", "%s=%s" % (NODE, d / "hidmouse.script"), "--", TOOL, *args]
    env = dict(os.environ)
    env["ASAN_OPTIONS"] = ":".join(filter(None, [env.get("ASAN_OPTIONS"),
                                                 "verify_asan_link_order=0"]))
    return subprocess.run([str(c) for c in cmd], capture_output=True, text=True,
                          timeout=timeout, env=env)


def lines_of(text, tag):
    return [l[len(tag) + 2:] for l in text.splitlines() if l.startswith(tag + ": ")]


def test_record_gives_back_the_recording(mock):
    _, desc, name, (bus, vid, pid), reports = mock
    proc = mocked(mock, "record", "hidraw:%04x:%04x" % (vid, pid), "--count", len(reports))
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout
    # the description: what hidapi enumerated and we read from the mocked sysfs
    assert lines_of(out, "R") == ["%d %s" % (len(desc), " ".join("%02x" % b for b in desc))]
    assert lines_of(out, "N") == [name]
    assert lines_of(out, "I") == ["%x %04x %04x" % (bus, vid, pid)]
    assert lines_of(out, "P") == ["usb-0000:00:01.2-1/input0"]
    # every report, one E: line each, byte for byte; the first at 0
    events = [l.split() for l in lines_of(out, "E")]
    assert [bytes(int(h, 16) for h in e[2:]) for e in events] == reports
    assert [int(e[1]) for e in events] == [len(r) for r in reports]
    assert events[0][0] == "000000.000000"
    # umockdev paces the script 150 ms a line: the times say so
    times = [float(e[0]) for e in events]
    assert all(0.1 < b - a < 2.0 for a, b in zip(times, times[1:]))
    assert "%d reports in" % len(reports) in proc.stderr


def test_decoding_the_node_equals_decoding_the_file(mock):
    vid, pid = mock[3][1], mock[3][2]
    direct = subprocess.run([str(TOOL), "decode", str(RECORDING)], capture_output=True,
                            text=True, timeout=30)
    assert direct.returncode == 0, direct.stderr
    live = mocked(mock, "record", "hidraw:%04x:%04x" % (vid, pid), "--decode", "--seconds", 1.5)
    assert live.returncode == 0, live.stderr

    def untimed(text):
        return [l.split()[1:] for l in text.splitlines()]
    # the live run ends with the release of what was held when it stopped: nothing here
    assert untimed(live.stdout) == untimed(direct.stdout)


def test_list_matches_by_ids_and_interface(mock):
    _, _, name, (_, vid, pid), _ = mock
    ids = "%04x:%04x" % (vid, pid)
    proc = mocked(mock, "list", "hidraw:" + ids + ":0", "hidraw:" + ids + ":1",
                  "hidraw:dead:beef")
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    assert lines[0] == "0 hidraw %s mouse %s" % (NODE, name)
    assert lines[1].startswith("skipped hidraw:%s:1: " % ids)
    assert lines[2].startswith("skipped hidraw:dead:beef: ")
    assert len(lines) == 3
