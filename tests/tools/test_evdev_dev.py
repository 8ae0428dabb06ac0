"""The evdev backend (devices/evdev_dev.c) on the real read path, through `posture-input record`.

Under umockdev-run, /dev/input/eventN is a mocked device: its sysfs entry and its ioctl answers
come from tests/input/umockdev/, its events from the evemu recordings in tests/input/evdev/
(written by libevemu, not by us). The recordings are the reference: recording the mocked device
must give their events back, and decoding it live must give what decoding the file gives.

umockdev cannot make a device vanish under an open fd (killing its replay takes the program
under test down with it), so the removal tests stand a pty or a socketpair in for the device fd
(`record --fd N`, the backend's evdev_dev_adopt seam): a pty whose other end is closed answers
read() with EIO, as the kernel's evdev answers ENODEV after an unplug, and a socket's closed peer
is the end of the stream; both must release the held button as events and log a line.
"""
import os
import pathlib
import shutil
import socket
import struct
import subprocess
import time
import tty

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
TOOL = BUILD / "bin" / "posture-input"
EVDEV = ROOT / "tests" / "input" / "evdev"
MOCK = ROOT / "tests" / "input" / "umockdev"
UMOCKDEV_RUN = shutil.which("umockdev-run")

# linux/input-event-codes.h
EV_SYN, EV_KEY, EV_REL, EV_MSC = 0, 1, 2, 4
SYN_REPORT, REL_X, REL_Y, MSC_SCAN, BTN_LEFT = 0, 0, 1, 4, 0x110

# the mocked devices: recording name -> its event node in the umockdev description
NODES = {"mouse": "/dev/input/event9", "keyboard": "/dev/input/event10",
         "tablet": "/dev/input/event11"}

needs_umockdev = pytest.mark.skipif(
    UMOCKDEV_RUN is None, reason="umockdev-run is not installed (Debian package umockdev)")


def record(*args, timeout=30):
    return subprocess.run([str(TOOL), "record", *map(str, args)], capture_output=True,
                          text=True, timeout=timeout)


def mocked(name, *args):
    """posture-input record of the mocked device replaying NAME.evemu"""
    node = NODES[name]
    cmd = [UMOCKDEV_RUN, "-d", MOCK / f"{name}.umockdev", "-i", f"{node}={MOCK / name}.ioctl",
           "-e", f"{node}={EVDEV / name}.evemu", "--", TOOL, "record", f"evdev:{node}", *args]
    # an ASan build runs with umockdev's library preloaded ahead of the sanitizer's runtime
    env = dict(os.environ)
    env["ASAN_OPTIONS"] = ":".join(filter(None, [env.get("ASAN_OPTIONS"),
                                                 "verify_asan_link_order=0"]))
    return subprocess.run(list(map(str, cmd)), capture_output=True, text=True, timeout=60,
                          env=env)


def evemu_events(text):
    """(seconds, type, code, value) of every E: line"""
    out = []
    for line in text.splitlines():
        if line.startswith("E:"):
            t, ty, co, va = line[2:].split("#")[0].split()
            out.append((float(t), int(ty, 16), int(co, 16), int(va)))
    return out


def evemu_lines(text, tag):
    return [l.split("#")[0].split() for l in text.splitlines() if l.startswith(tag + ":")]


def frames(events):
    """the events cut at each SYN_REPORT, without times"""
    out, cur = [], []
    for _, ty, co, va in events:
        cur.append((ty, co, va))
        if ty == EV_SYN and co == SYN_REPORT:
            out.append(cur)
            cur = []
    return out + ([cur] if cur else [])


def decoded(text):
    """decode's lines without their time column"""
    return [l.split()[1:] for l in text.splitlines()]


def rec(ty, co, va, t_us=1000):
    """one struct input_event record (LP64: timeval, u16 type, u16 code, s32 value)"""
    return struct.pack("<qqHHi", t_us // 1000000, t_us % 1000000, ty, co, va)


# ---- recording the mocked device --------------------------------------------------------

@needs_umockdev
@pytest.mark.parametrize("name", ["mouse", "keyboard", "tablet"])
def test_record_gives_back_the_recordings_events(name):
    src = (EVDEV / f"{name}.evemu").read_text()
    want = evemu_events(src)
    proc = mocked(name, "--count", len(want))
    assert proc.returncode == 0, proc.stderr
    got = evemu_events(proc.stdout)
    assert proc.stdout.startswith("# EVEMU 1.3\n")
    # every record, in order, with its type, code and value
    assert [e[1:] for e in got] == [e[1:] for e in want]
    # each frame's records carry one time, and the frames come in the file's order
    assert frames(got) == frames(want)
    for f_got in _timed_frames(got):
        assert len(set(f_got)) == 1
    # times rebased to the first event (evemu-record starts at 0.000001); umockdev paces the
    # replay and stamps the records on its own timer, so later times are its own (the exact
    # rebasing is checked below, on records of known times)
    assert got[0][0] == want[0][0] == 0.000001
    # the description libevdev read from the mocked device is the recording's
    assert evemu_lines(proc.stdout, "N") == evemu_lines(src, "N")
    assert evemu_lines(proc.stdout, "I") == evemu_lines(src, "I")
    # every type's code bits but EV_SYN's (libevdev reports every SYN code; evemu 2.7 did not)
    def bits(text):
        return [l for l in evemu_lines(text, "B") if l[1] != "00"]
    assert bits(proc.stdout) == bits(src)
    assert evemu_lines(proc.stdout, "A") == evemu_lines(src, "A")
    assert evemu_lines(proc.stdout, "P") == evemu_lines(src, "P")


def _timed_frames(events):
    out, cur = [], []
    for t, ty, co, _ in events:
        cur.append(t)
        if ty == EV_SYN and co == SYN_REPORT:
            out.append(cur)
            cur = []
    return out


@needs_umockdev
@pytest.mark.parametrize("name", ["mouse", "keyboard", "tablet"])
def test_decoding_the_device_equals_decoding_the_file(name, tmp_path):
    """the tablet's pointer is normalised by the ranges the backend read from the device"""
    path = EVDEV / f"{name}.evemu"
    direct = subprocess.run([str(TOOL), "decode", str(path)], capture_output=True, text=True,
                            timeout=30)
    assert direct.returncode == 0, direct.stderr
    # live: the backend's read path into the decoder
    live = mocked(name, "--decode", "--seconds", 1.5)
    assert live.returncode == 0, live.stderr
    assert decoded(live.stdout) == decoded(direct.stdout)
    # recorded to a file, then decoded as a file
    out = tmp_path / f"{name}.evemu"
    n = len(evemu_events(path.read_text()))
    rec_proc = mocked(name, "-o", out, "--count", n)
    assert rec_proc.returncode == 0, rec_proc.stderr
    again = subprocess.run([str(TOOL), "decode", str(out)], capture_output=True, text=True,
                           timeout=30)
    assert again.returncode == 0, again.stderr
    assert decoded(again.stdout) == decoded(direct.stdout)


@needs_umockdev
def test_the_clock_the_mock_refuses_is_logged_not_fatal():
    """umockdev answers EVIOCSCLOCKID with an error: the backend says so and reads on"""
    proc = mocked("mouse", "--count", 4)
    assert proc.returncode == 0, proc.stderr
    assert "CLOCK_MONOTONIC" in proc.stderr
    assert len(evemu_events(proc.stdout)) == 4


# ---- refusals -----------------------------------------------------------------------------

def test_a_file_that_is_not_an_evdev_device_is_refused_clearly():
    proc = record("evdev:/dev/null", "--count", 1)
    assert proc.returncode == 1
    assert "/dev/null: not an evdev device" in proc.stderr


def test_a_missing_device_is_refused_clearly(tmp_path):
    proc = record(f"evdev:{tmp_path}/event99", "--count", 1)
    assert proc.returncode == 1
    assert "No such file or directory" in proc.stderr


# ---- the device going away, and stream edge cases, through the fd seam --------------------

def run_on_fd(fd, feed, *args):
    """record --fd --decode on fd (inherited), while feed() writes and closes the other end"""
    proc = subprocess.Popen([str(TOOL), "record", "--fd", str(fd), "--decode", *map(str, args)],
                            pass_fds=[fd], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    os.close(fd)
    feed()
    out, err = proc.communicate(timeout=30)
    return proc.returncode, out, err


HELD_DOWN = rec(EV_MSC, MSC_SCAN, 0x90001) + rec(EV_KEY, BTN_LEFT, 1) + rec(EV_SYN, SYN_REPORT, 0)


def assert_released_and_removed(rc, out, err, why):
    lines = decoded(out)
    # the press the device sent, then (the device gone) its release, a frame, the removal
    assert lines[:2] == [["0", "button", "BTN_LEFT", "1"], ["0", "frame"]]
    assert lines[2:] == [["0", "button", "BTN_LEFT", "0"], ["0", "frame"], ["0", "removed"]]
    assert rc == 1
    log = [l for l in err.splitlines() if l.startswith("posture: ")]
    assert len(log) == 1 and "gone" in log[0] and why in log[0] and "1 key(s)" in log[0]


def test_a_device_gone_mid_drag_eio_releases_its_button():
    master, slave = os.openpty()
    tty.setraw(slave)

    def feed():
        os.write(slave, HELD_DOWN)
        time.sleep(0.3)
        os.close(slave)  # the master now reads EIO, as an unplugged device's fd does
    rc, out, err = run_on_fd(master, feed, "--seconds", 10)
    assert_released_and_removed(rc, out, err, "Input/output error")


def test_a_device_gone_at_the_end_of_its_stream_releases_its_button():
    ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_STREAM)

    def feed():
        ours.sendall(HELD_DOWN)
        time.sleep(0.3)
        ours.close()
    rc, out, err = run_on_fd(theirs.detach(), feed, "--seconds", 10)
    assert_released_and_removed(rc, out, err, "end of the stream")


def test_a_record_split_across_reads_is_joined():
    """the kernel hands out whole records; a stream standing in for it may not"""
    ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_STREAM)
    frame = rec(EV_REL, REL_X, 3) + rec(EV_REL, REL_Y, -2) + rec(EV_SYN, SYN_REPORT, 0)

    def feed():
        ours.sendall(frame[:30])
        time.sleep(0.3)
        ours.sendall(frame[30:])
        time.sleep(0.3)
        ours.close()
    rc, out, err = run_on_fd(theirs.detach(), feed, "--seconds", 10)
    assert decoded(out)[:2] == [["0", "motion", "3", "-2"], ["0", "frame"]]
    assert "short" not in err and "refused" not in err


def test_a_flood_is_read_in_bounded_batches_and_nothing_is_lost():
    """thousands of frames written at once: the backend takes them a batch a call, all of them"""
    ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_STREAM)
    n = 3000
    flood = b"".join(rec(EV_REL, REL_X, 1, 1000 + i) + rec(EV_SYN, SYN_REPORT, 0, 1000 + i)
                     for i in range(n))

    def feed():
        ours.sendall(flood)
        time.sleep(0.5)
        ours.close()
    rc, out, err = run_on_fd(theirs.detach(), feed, "--seconds", 20)
    lines = decoded(out)
    motion = [l for l in lines if l[1] == "motion"]
    assert sum(int(l[2]) for l in motion) == n
    assert sum(1 for l in lines if l[1] == "frame") == n
    assert lines[-1] == ["0", "removed"]
    # the summary line: at most the cap a read, so at least records / cap reads, some full
    summary = [l for l in err.splitlines() if " reads (" in l][0].split()
    records, reads, capped, cap = int(summary[1]), int(summary[4]), int(summary[6][1:]), 64
    assert records == 2 * n
    assert reads >= records / cap and capped >= 1


def test_recorded_times_start_at_the_first_event():
    """evemu-record's convention: the first event at 0.000001, the rest at their distance"""
    ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_STREAM)
    t0 = 5123400000
    frames_in = [rec(EV_REL, REL_X, 3, t0) + rec(EV_SYN, SYN_REPORT, 0, t0),
                 rec(EV_REL, REL_Y, -2, t0 + 10250) + rec(EV_SYN, SYN_REPORT, 0, t0 + 10250)]

    def feed():
        ours.sendall(b"".join(frames_in))
        time.sleep(0.3)
        ours.close()
    fd = theirs.detach()
    proc = subprocess.Popen([str(TOOL), "record", "--fd", str(fd), "--seconds", "10"],
                            pass_fds=[fd], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    os.close(fd)
    feed()
    out, _ = proc.communicate(timeout=30)
    assert out.startswith("# EVEMU 1.3\n")
    assert evemu_events(out) == [(0.000001, EV_REL, REL_X, 3), (0.000001, EV_SYN, SYN_REPORT, 0),
                                 (0.010251, EV_REL, REL_Y, -2),
                                 (0.010251, EV_SYN, SYN_REPORT, 0)]


@needs_umockdev
def test_list_says_what_the_daemon_would_open_and_skip():
    node = NODES["mouse"]
    cmd = [UMOCKDEV_RUN, "-d", MOCK / "mouse.umockdev", "-i", f"{node}={MOCK / 'mouse'}.ioctl",
           "-e", f"{node}={EVDEV / 'mouse'}.evemu", "--", TOOL, "list", f"evdev:{node}",
           "evdev:/dev/null"]
    r = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, timeout=30)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert lines[0] == f"0 evdev {node} mouse Posture Test 3-Button Wheel Mouse"
    # under umockdev the ioctls on /dev/null fail otherwise than on a real system: a reason
    assert lines[1].startswith("skipped /dev/null: /dev/null: ") and len(lines[1]) > 40
    bad = subprocess.run([str(TOOL), "list", "bluetooth:aa"], capture_output=True, text=True)
    assert bad.returncode == 2 and "auto, none, evdev:PATH" in bad.stderr
