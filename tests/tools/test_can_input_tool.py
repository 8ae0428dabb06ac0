"""posture-input with CAN specs where the kernel has no CAN panel to give (the build machines:
socket(PF_CAN) fails with EAFNOSUPPORT): `list can:IFACE:MAP` reports the skip and its reason,
`record can:IFACE` fails saying why, and a bad map or spec is refused before any socket.
Recording a real interface is tests/guest/test_guest_can.py's."""
import errno
import os
import pathlib
import socket
import subprocess

ROOT = pathlib.Path(__file__).resolve().parents[2]
TOOL = ROOT / os.environ.get("POSTURE_BUILD", "build/rel") / "bin" / "posture-input"
PANEL_MAP = ROOT / "tests" / "input" / "can" / "panel.map"
IFACE = "posture9"  # a name no machine has


def tool(*args):
    return subprocess.run([str(TOOL), *map(str, args)], capture_output=True, text=True,
                          timeout=30)


def no_can_reason():
    """the kernel's own answer to a CAN_RAW socket, as the skip reason must give it"""
    try:
        socket.socket(socket.PF_CAN, socket.SOCK_RAW, socket.CAN_RAW).close()
    except OSError as e:
        assert e.errno == errno.EAFNOSUPPORT
        return "no CAN in this kernel (socket(PF_CAN): %s)" % os.strerror(e.errno)
    return "no such CAN interface"


def test_list_skips_with_the_reason():
    r = tool("list", f"can:{IFACE}:{PANEL_MAP}")
    assert r.returncode == 0, r.stderr
    assert r.stdout == f"skipped {IFACE}: {no_can_reason()}\n"


def test_record_says_why_it_cannot():
    r = tool("record", f"can:{IFACE}", "--count", "1")
    assert r.returncode == 1
    assert r.stdout == ""
    assert r.stderr == f"posture-input: {IFACE}: {no_can_reason()}\n"


def test_bad_map_and_spec_refused_before_any_socket(tmp_path):
    bad = tmp_path / "bad.map"
    bad.write_text("axis 181 0|16@1+ Dial\nbutton 181 99.0 Nope\n")
    r = tool("list", f"can:{IFACE}:{bad}")
    assert r.returncode == 2
    assert f"{bad}:2: " in r.stderr
    r = tool("list", f"can:{IFACE}")
    assert r.returncode == 2
    assert "expected can:IFACE:MAPFILE" in r.stderr
    r = tool("record", f"can:{IFACE}:{bad}")
    assert r.returncode == 2
    assert f"{bad}:2: " in r.stderr
