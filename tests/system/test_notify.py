"""sd_notify as systemd sees it (Type=notify, WatchdogSec=): READY=1 once and no WATCHDOG=1
before it (a ping would arm systemd's watchdog); then a ping every half WATCHDOG_USEC, and
STOPPING=1 last; no pings when WATCHDOG_PID names another process. That READY=1 waits for
the first frame cannot be told apart here, where that frame is quick; the guest's package
test (tests/guest/test_guest_package.py) sees it under a real systemd, where the first
frame takes 10 s."""
import socket
import time

from daemon import ROOT, daemon_factory  # noqa: F401 (fixture)

VIEW_INIT = ROOT / "tools" / "kiosk.init"


def messages(sock, seconds):
    """The datagrams sent to sock within seconds, in order."""
    got, deadline = [], time.monotonic() + seconds
    while time.monotonic() < deadline:
        sock.settimeout(max(0.01, deadline - time.monotonic()))
        try:
            got.append(sock.recv(4096).decode())
        except socket.timeout:
            break
    return got


def notify_socket(tmp_path):
    s = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
    s.bind(str(tmp_path / "notify"))
    return s


def test_ready_once_before_any_watchdog_ping_then_pings_at_half_the_period(
        daemon_factory, tmp_path, monkeypatch):
    s = notify_socket(tmp_path)
    monkeypatch.setenv("NOTIFY_SOCKET", str(tmp_path / "notify"))
    monkeypatch.setenv("WATCHDOG_USEC", "400000")
    monkeypatch.delenv("WATCHDOG_PID", raising=False)
    d = daemon_factory(extra=["--init", str(VIEW_INIT), "--frames", str(tmp_path / "frames")])
    got = messages(s, 2.0)
    d.stop()
    got += messages(s, 0.5)
    assert got and got[0] == "READY=1", got
    assert got.count("READY=1") == 1, got
    pings = got.count("WATCHDOG=1")
    assert 5 <= pings <= 12, got  # 2 s at one a 0.2 s
    assert got[-1] == "STOPPING=1", got


def test_no_pings_for_another_process(daemon_factory, tmp_path, monkeypatch):
    s = notify_socket(tmp_path)
    monkeypatch.setenv("NOTIFY_SOCKET", str(tmp_path / "notify"))
    monkeypatch.setenv("WATCHDOG_USEC", "400000")
    monkeypatch.setenv("WATCHDOG_PID", "1")
    d = daemon_factory()
    got = messages(s, 1.0)
    d.stop()
    assert got == ["READY=1"], got
