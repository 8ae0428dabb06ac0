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

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
TOOL = BUILD / "bin" / "posture-input"
RECORDING = ROOT / "tests" / "input" / "hid" / "hidtools_mouse.hid"
UMOCKDEV_RUN = shutil.which("umockdev-run")
NODE = "/dev/hidraw0"
HID_MAX_DESCRIPTOR_SIZE = 4096

pytestmark = pytest.mark.skipif(
    UMOCKDEV_RUN is None, reason="umockdev-run is not installed (Debian package umockdev)")


def read_recording(path):
    """(descriptor bytes, name, (bus, vid, pid), [report bytes]) of a one-device recording"""
    desc, name, ids, reports = None, None, None, []
    for line in path.read_text().splitlines():
        tag, _, rest = line.partition(": ")
        if tag == "R":
            n, *hexes = rest.split()
            desc = bytes(int(h, 16) for h in hexes)
            assert len(desc) == int(n)
        elif tag == "N":
            name = rest
        elif tag == "I":
            ids = tuple(int(x, 16) for x in rest.split())
        elif tag == "E":
            _, n, *hexes = rest.split()
            reports.append(bytes(int(h, 16) for h in hexes))
            assert len(reports[-1]) == int(n)
    return desc, name, ids, reports


def script_bytes(data):
    """umockdev's script escaping: bytes below 32 as ^ and b + 64, '^' as ^`"""
    out = bytearray()
    for b in data:
        if b < 32:
            out += bytes([ord("^"), b + 64])
        elif b == ord("^"):
            out += b"^`"
        else:
            out.append(b)
    return bytes(out)


@pytest.fixture(scope="module")
def mock(tmp_path_factory):
    """the .umockdev, .ioctl and .script files of the recorded mouse"""
    d = tmp_path_factory.mktemp("hidmouse")
    desc, name, (bus, vid, pid), reports = read_recording(RECORDING)
    usb = "/devices/pci0000:00/0000:00:01.2/usb1/1-1"
    intf = usb + "/1-1:1.0"
    hid = intf + "/%04X:%04X:%04X.0001" % (bus, vid, pid)
    (d / "hidmouse.umockdev").write_text("\n".join([
        "P: " + hid + "/hidraw/hidraw0",
        "N: hidraw0",
        "E: DEVNAME=" + NODE,
        "E: MAJOR=240",
        "E: MINOR=0",
        "E: SUBSYSTEM=hidraw",
        "A: dev=240:0\\n",
        "L: device=../../../%04X:%04X:%04X.0001" % (bus, vid, pid),
        "",
        "P: " + hid,
        "E: DRIVER=hid-generic",
        "E: HID_ID=%04X:%08X:%08X" % (bus, vid, pid),
        "E: HID_NAME=" + name,
        "E: HID_PHYS=usb-0000:00:01.2-1/input0",
        "E: HID_UNIQ=",
        "E: MODALIAS=hid:b%04Xg0001v%08Xp%08X" % (bus, vid, pid),
        "E: SUBSYSTEM=hid",
        "H: report_descriptor=" + desc.hex().upper(),
        "",
        "P: " + intf,
        "E: DEVTYPE=usb_interface",
        "E: DRIVER=usbhid",
        "E: SUBSYSTEM=usb",
        "A: bInterfaceNumber=00\\n",
        "A: bInterfaceClass=03\\n",
        "",
        "P: " + usb,
        "E: DEVTYPE=usb_device",
        "E: DRIVER=usb",
        "E: SUBSYSTEM=usb",
        "A: idVendor=%04x\\n" % vid,
        "A: idProduct=%04x\\n" % pid,
        "A: manufacturer=QEMU\\n",
        "A: product=QEMU USB Mouse\\n",
        "A: bcdDevice=0000\\n",
        "",
    ]))
    # hid_open_path asks the node for its descriptor: struct hidraw_report_descriptor
    size = len(desc).to_bytes(4, "little")
    full = size + desc + bytes(HID_MAX_DESCRIPTOR_SIZE - len(desc))
    (d / "hidmouse.ioctl").write_text("@DEV %s\nHIDIOCGRDESCSIZE 0 %s\nHIDIOCGRDESC 0 %s\n" % (
        NODE, size.hex().upper(), full.hex().upper()))
    with open(d / "hidmouse.script", "wb") as f:
        for r in reports:
            f.write(b"r 150 " + script_bytes(r) + b"\n")
    return d, desc, name, (bus, vid, pid), reports


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
