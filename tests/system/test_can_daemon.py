"""The daemon with a CAN panel spec (--input can:IFACE:MAPFILE) on a machine whose kernel
cannot give it one: with no CAN in the kernel (socket(PF_CAN) fails with EAFNOSUPPORT, as on
the build machines) or no such interface, it says so once and runs on without the panel, and
`list devices` gives the reason; a bad map is a configuration error that stops it at start.
The panel on a real kernel is tests/guest/test_guest_can.py's."""
import errno
import os
import socket

import pytest

from daemon import Daemon, DaemonError, ROOT

PANEL_MAP = ROOT / "tests" / "input" / "can" / "panel.map"
IFACE = "posture9"  # a name no machine has


def no_can_reason():
    """what the kernel answers a CAN_RAW socket here: the skip reason the daemon must give"""
    try:
        s = socket.socket(socket.PF_CAN, socket.SOCK_RAW, socket.CAN_RAW)
    except OSError as e:
        if e.errno == errno.EAFNOSUPPORT:
            return "no CAN in this kernel (socket(PF_CAN): %s)" % os.strerror(e.errno)
        raise
    s.close()
    return "no such CAN interface"


def test_no_panel_here_the_daemon_runs_on():
    d = Daemon(extra=("--input", f"can:{IFACE}:{PANEL_MAP}"))
    d.start()
    try:
        with d.client() as c:
            listed = c.request("list devices")
            assert listed["devices"] == []
            assert listed["skipped"] == [{"what": IFACE, "why": no_can_reason()}]
            # it still serves
            assert c.request("help") is not None
    finally:
        d.stop()
        log = d.log()
        d.cleanup()
    assert log.count(f"postured: input {IFACE} skipped: {no_can_reason()}") == 1


def test_a_bad_map_stops_the_start(tmp_path):
    bad = tmp_path / "bad.map"
    bad.write_text("axis 181 0|16@1+ Dial\naxis 999 0|8@1+ Other\n")
    d = Daemon(extra=("--input", f"can:{IFACE}:{bad}"))
    try:
        with pytest.raises(DaemonError) as e:
            d.start()
        assert f"{bad}:2: " in str(e.value)
    finally:
        d.cleanup()
