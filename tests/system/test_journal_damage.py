"""A damaged journal: its tail is dropped, nothing before it is lost, damage in the middle is
refused.

A daemon writes a real journal (commands, a file record, the solver's postures, a kiosk
drag's step marks) and is killed with SIGKILL after a last command whose record is known.
That journal is then damaged as a crash, a full disk or a failing disk leaves one: the last
record torn at several points, bytes of it flipped, zero bytes over its end or after it. A
daemon started on each must start, say in exactly one line what it dropped and from which
byte, and hold exactly the state of a reference daemon started on the journal cut after its
last whole record (compared bit for bit, the undo history's depth included); the bytes
before the damage stay as they were and the journal goes on from there. Damage with whole
records after it (a flipped byte in an earlier record) is refused, naming the byte, and
the journal is left untouched.
"""
import json
import math
import re
import resource
import shutil
import sys

import pytest

from daemon import Daemon, DaemonError, journal_records, snapshot
from test_crash import canonical, describe_difference

LAST = "set joint jack knee_l 30deg"  # the last command: its record is the one damaged
DAMAGE_LINE = re.compile(r"postured: journal \S+: the last (\d+) bytes \(from byte (\d+), "
                         r"(after record (\d+)|before any whole record)\) are not a whole "
                         r"record \((.+)\): dropped$")


def observe(client):
    """The observable state and the depth of the undo and redo histories."""
    state = snapshot(client)
    status = client.request("status")
    state["history"] = [status.get("undo"), status.get("redo")]
    return canonical(state)


@pytest.fixture(scope="module")
def journal():
    """The journal's bytes as the killed daemon left them."""
    d = Daemon()
    try:
        d.start()
        with d.client() as c:
            c.request("load human as jack")
            c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
            c.request("set joint jack elbow_r 40deg")
            c.request("save posture jack bent.pst")
            c.request("set joint jack elbow_r 0")
            c.request("load posture jack bent.pst")  # an F record, then its C record
            # the solver's postures (P records), then no constraint left to move anything
            c.request("add constraint jack effector=hand_l.palm goal=0.3,1.1,0.3 as reach")
            c.request("settle frames=20")
            c.request("delete constraint reach")
            # a kiosk drag: its step marks B and E
            c.request("manipulate figure jack view=front")
            c.request("input pointer front 160 120")
            c.request("input button left down")
            for x in (175, 190, 210):
                c.request(f"input pointer front {x} 121")
            c.request("input button left up")
            c.request("status")
            c.request(LAST)
        d.kill9()
        data = (d.state_dir / "journal").read_bytes()
    finally:
        d.cleanup()
    kinds = {line.split(b" ")[1] for line in data.splitlines()}
    assert {b"C", b"F", b"P", b"B", b"E"} <= kinds, kinds
    assert data.endswith(b"\n") and data.splitlines()[-1].split(b" ", 2)[2].startswith(
        LAST.encode()), data[-200:]
    return data


def run_on(data):
    """A daemon started on a state directory holding only this journal: (state, its stderr,
    the journal's bytes after the start, the daemon, still running)."""
    d = Daemon()
    (d.state_dir / "journal").write_bytes(data)
    d.start()
    with d.client() as c:
        state = observe(c)
    log = d.log_path.read_text(errors="replace")
    return state, log, (d.state_dir / "journal").read_bytes(), d


_references = {}


def reference(data):
    """The state a daemon reaches from an undamaged journal (cached)."""
    if data not in _references:
        state, log, _, d = run_on(data)
        d.stop()
        d.cleanup()
        assert "not a whole record" not in log, log
        _references[data] = state
    return _references[data]


def last_record(data):
    """(start, end) of the last record's bytes, its newline included."""
    start = data.rstrip(b"\n").rfind(b"\n") + 1
    return start, len(data)


def flip(data, at, bit):
    b = bytearray(data)
    b[at] ^= 1 << bit
    return bytes(b)


def damages(data):
    """(name, damaged journal, bytes of whole records it keeps) for each way of damage."""
    a, b = last_record(data)
    line = data[a:b]
    body = a + line.index(b"30deg")
    seq_len = line.index(b" ")
    cases = []
    for name, cut in (("torn in its number", a + 1), ("torn after its kind", a + seq_len + 3),
                      ("torn mid-command", body), ("torn before its checksum", b - 10),
                      ("torn mid-checksum", b - 5), ("torn before its newline", b - 1)):
        cases.append((name, data[:cut], a))
    cases += [
        ("30deg flipped to 10deg", flip(data, body + 0, 1), a),   # '3' -> '1': still a command
        ("its number flipped", flip(data, a + seq_len - 1, 0), a),
        ("its kind flipped", flip(data, a + seq_len + 1, 1), a),  # 'C' -> 'A'
        ("its checksum flipped", flip(data, b - 3, 2), a),
        ("its newline flipped", flip(data, b - 1, 5), a),
        ("its end zeroed", data[:b - 12] + bytes(12), a),
        ("all of it zeroed", data[:a] + bytes(b - a), a),
        ("zeros over it and on", data[:a + 5] + bytes(4096), a),
        ("zeros appended", data + bytes(4096), b),
    ]
    return cases


CASES = ["torn in its number", "torn after its kind", "torn mid-command",
         "torn before its checksum", "torn mid-checksum", "torn before its newline",
         "30deg flipped to 10deg", "its number flipped", "its kind flipped",
         "its checksum flipped", "its newline flipped", "its end zeroed", "all of it zeroed",
         "zeros over it and on", "zeros appended"]


@pytest.mark.parametrize("case", CASES)
def test_a_damaged_tail_recovers_to_the_last_whole_record(journal, case):
    name, damaged, keep = next(x for x in damages(journal) if x[0] == case)
    want = reference(journal[:keep])
    state, log, after, d = run_on(damaged)
    try:
        damage = [m for m in map(DAMAGE_LINE.match, log.splitlines()) if m]
        others = [x for x in log.splitlines() if "journal record" in x]
        assert len(damage) == 1 and not others, f"{case}: the log says\n{log}"
        m = damage[0]
        assert int(m.group(2)) == keep and int(m.group(1)) == len(damaged) - keep, m.group(0)
        whole = journal[:keep].splitlines()
        assert m.group(4) == whole[-1].split(b" ")[0].decode(), m.group(0)
        assert state == want, f"{case}: " + describe_difference(state, want)
        # nothing before the damage changed; the journal goes on from there
        assert after == journal[:keep]
        with d.client() as c:
            c.request("set joint jack knee_r 10deg")
            goes_on = observe(c)
        d.restart()
        with d.client() as c:
            assert observe(c) == goes_on
        assert d.log().count("not a whole record") == 1
    finally:
        d.cleanup()


def test_the_whole_journal_is_the_last_commands_state(journal):
    """the reference itself: the last record is the last command, and it changes the state"""
    a, _ = last_record(journal)
    assert reference(journal) != reference(journal[:a])


def test_damage_in_the_middle_is_refused_and_the_journal_left_as_it_was(journal):
    lines = journal.splitlines(keepends=True)
    k = next(i for i, x in enumerate(lines) if b" C load posture " in x)
    at = sum(map(len, lines[:k]))
    damaged = flip(journal, at + lines[k].index(b"bent"), 0)
    d = Daemon()
    (d.state_dir / "journal").write_bytes(damaged)
    try:
        with pytest.raises(DaemonError):
            d.start()
        log = d.log_path.read_text(errors="replace")
        assert f"byte {at}: its checksum does not match, and whole records follow it" in log, log
        assert f"truncate -s {at}" in log, log
        assert (d.state_dir / "journal").read_bytes() == damaged
        # the way out it names: cut there, and it starts with the records before it
        shutil.copy(d.state_dir / "journal", d.dir / "journal.damaged")
        with open(d.state_dir / "journal", "r+b") as f:
            f.truncate(at)
        d.start()
        with d.client() as c:
            assert observe(c) == reference(journal[:at])
    finally:
        d.cleanup()


# the daemon under a limit on the size of the files it writes (RLIMIT_FSIZE, SIGXFSZ ignored:
# a write past it fails with EFBIG, as on a full disk), raised later with prlimit
LIMITED = ("import os, resource, signal, sys\n"
           "signal.signal(signal.SIGXFSZ, signal.SIG_IGN)\n"
           "resource.setrlimit(resource.RLIMIT_FSIZE, (int(sys.argv[1]), resource.RLIM_INFINITY))\n"
           "os.execv(sys.argv[2], sys.argv[2:])\n")


def test_a_record_the_disk_had_no_room_for_leaves_no_piece_behind():
    """A write that fails part way (a full disk) writes the part that fits: cut back, so the
    records written once there is room again do not follow a piece of one (damage in the
    middle, which a restart would refuse)."""
    d = Daemon()
    (d.state_dir / "journal").write_bytes(b"")
    limit = 2000
    d.argv = [sys.executable, "-c", LIMITED, str(limit)] + d.argv
    try:
        d.start()
        with d.client() as c:
            c.request("load human as jack")
            for k in range(100):  # until the journal has no room for the next record
                c.request(f"set joint jack knee_l {k % 90}deg")
                if "File too large" in d.log_path.read_text():
                    break
            else:
                pytest.fail("the journal never reached its limit\n" + d.log())
            resource.prlimit(d.pid, resource.RLIMIT_FSIZE,
                             (resource.RLIM_INFINITY, resource.RLIM_INFINITY))
            c.request("set joint jack elbow_r 20deg")
            c.request("set joint jack elbow_l 30deg")
        data = (d.state_dir / "journal").read_bytes()
        assert data.endswith(b"\n") and journal_records(d.state_dir)[-1][2] == \
            "set joint jack elbow_l 30deg", data[-300:]
        d.restart()
        with d.client() as c:
            got = json.loads(observe(c))
        assert "not a whole record" not in d.log()
        posture = got["postures"][next(iter(got["postures"]))]
        assert posture["elbow_l"] == pytest.approx([math.radians(30)], abs=1e-12)
        assert posture["elbow_r"] == pytest.approx([math.radians(20)], abs=1e-12)
    finally:
        d.cleanup()
