"""Malformed and hostile input: each is answered with the right error code (or, for
half lines, with nothing), the daemon's state stays exactly as it was, and other clients
are not disturbed.

One daemon serves the whole module. Its state is set up once (two humans, constraints,
stale ids, files and symbolic links in the state directory); after every case the test
compares `list figures`, `list constraints` and every `get posture` with the snapshot
taken before the first case, and a bystander client that stayed connected throughout
must still get its replies.
"""
import os
import socket
import time
from dataclasses import dataclass, field

import pytest

from daemon import ConnectionClosed, Daemon, snapshot, wait_closed

LIMIT_LINE = 65536


@dataclass
class Case:
    """One hostile input.

    ``data``: the bytes sent (``{NAME}`` fields are filled from the setup); ``codes``:
    the error codes of the replies expected, in order (empty: no reply at all);
    ``close``: the daemon must close the connection after them; ``hangup``: the client
    closes right after sending; ``halfclose``: the client shuts down its sending side
    (the daemon sees end of file but could still answer); ``absent``: paths (relative to the daemon's directory)
    that must not exist afterwards.
    """
    name: str
    data: bytes
    codes: tuple = ()
    close: bool = False
    hangup: bool = False
    halfclose: bool = False
    absent: tuple = field(default_factory=tuple)


def line(text, *codes, **kw):
    """A case of one request line (newline added) answered with codes."""
    return Case(name=kw.pop("name", text[:60]), data=text.encode() + b"\n", codes=codes, **kw)


CASES = [
    # ---- unknown verbs and objects
    line("frobnicate", "unknown-command"),
    line("frobnicate jack knee_l 1", "unknown-command"),
    line("get nothing jack", "unknown-command"),
    line("list", "unknown-command"),
    line("load", "unknown-command"),
    line("set joints jack knee_l 1", "unknown-command"),
    line("unload constraint hold", "unknown-command"),
    line('"" posture jack', "unknown-command", name="empty quoted verb"),
    line("é posture jack", "unknown-command", name="non-ascii verb"),
    Case("invalid utf-8 verb", b"\xff\xfe\xfd posture jack\n", ("unknown-command",)),
    # ---- arity
    line("get joint jack", "arity"),
    line("get joint jack knee_l extra", "arity"),
    line("set joint jack", "arity"),
    line("set joint jack knee_l 1 2", "arity"),
    line("status now", "arity"),
    line("unload figure", "arity"),
    line("undo please", "arity"),
    line("move goal hold 1 2", "arity"),
    line("get posture", "arity"),
    line("set location jack 1 2", "arity"),
    line("help a b c", "arity"),
    line("help " + " ".join(["x"] * 64), "arity", name="65 words"),
    # ---- numbers
    line("set joint jack knee_l abc", "bad-number"),
    line("set joint jack knee_l nan", "bad-number"),
    line("set joint jack knee_l NaN", "bad-number"),
    line("set joint jack knee_l inf", "bad-number"),
    line("set joint jack knee_l -inf", "bad-number"),
    line("set joint jack knee_l Infinity", "bad-number"),
    line("set joint jack knee_l 1e999", "bad-number"),
    line("set joint jack knee_l -1e400", "bad-number"),
    line("set joint jack knee_l 0x1p-2", "bad-number"),
    line("set joint jack knee_l 1e", "bad-number"),
    line("set joint jack knee_l 1..2", "bad-number"),
    line("set joint jack knee_l --1", "bad-number"),
    line("set joint jack knee_l 1,2", "bad-number"),
    line('set joint jack knee_l ""', "bad-number"),
    line("set joint jack knee_l 30degs", "bad-number"),
    line("set joint jack knee_l 30kg", "bad-number"),
    line("set joint jack knee_l 1cm", "bad-number", name="length unit for an angle"),
    line("set location jack 1 2 3deg", "bad-number", name="angle unit for a length"),
    line("set location jack 1 2 3 yaw=nan", "bad-number"),
    line("add constraint jack effector=hand_l.palm goal=1,2,inf", "bad-number"),
    line("load human as tall stature=abc", "bad-number"),
    line("settle frames=nan", "bad-number"),
    line("move goal hold 1e309 0 0", "bad-number"),
    # ---- arguments out of range or not taken
    line("set joint jack knee_l -1", "bad-argument", name="below the joint limit"),
    line("set joint jack knee_l 3", "bad-argument", name="above the joint limit"),
    line("load human as 9lives", "bad-argument"),
    line("load human as bad-name", "bad-argument"),
    line("load human as " + "n" * 48, "bad-argument", name="48-byte name"),
    line("load human sex=robot", "bad-argument"),
    line("load human height=2", "bad-argument"),
    line("load human mass=-5", "bad-argument"),
    line("add constraint jack effector=hand_l.palm pos=banana", "bad-argument"),
    line("add constraint jack effector=hand_l.palm pos=none ori=none", "bad-argument"),
    line("add constraint jack effector=hand_l.palm weight=-1", "bad-argument"),
    line("set location jack 1 2 3 rot=0,0,0,1", "bad-argument", name="zero rotation axis"),
    line("set location jack 1 2 3 spin=1", "bad-argument"),
    line("settle frames=0", "bad-argument"),
    line("subscribe gossip", "bad-argument"),
    # ---- names and ids
    line("get posture nobody", "not-found"),
    line("get joint jack nojoint", "not-found"),
    line("get site jack pelvis.nosite", "not-found"),
    line("enable constraint ghost", "not-found"),
    line("show figure f15.1", "not-found", name="id of an unused slot"),
    line("get posture f99.1", "not-found", name="id beyond the slots"),
    line("get posture {STALE_FIG}", "stale-id"),
    line("delete constraint {STALE_CON}", "stale-id"),
    line("load human as jack", "exists"),
    line("add constraint jack effector=hand_l.palm as hold", "exists"),
    line("redo", "nothing"),
    # ---- behaviours (jack behaves, jill does not)
    line("grab jack right nobody", "not-found"),
    line("grab jack right jack", "bad-argument"),
    line("grab jill right jack", "bad-argument", name="grab by a figure that does not behave"),
    line("hold hand jack left jill.nosegment", "not-found"),
    line("hold foot jack sideways jill", "bad-argument"),
    line("release hand jack middle", "bad-argument"),
    line("set behavior jack stability=nan", "bad-number"),
    line("set behavior jack stability=5", "bad-number"),
    line("set behavior jack seated=perhaps torso=free", "bad-argument",
         name="one bad key among good ones"),
    line("set behavior jill foot=pivot", "bad-argument", name="behaviours off"),
    line("bend torso jack 10deg 0 0 initiator=spine_99", "bad-argument"),
    line("bend torso jack 10deg 0 0 bottom=spine_9 top=spine_3", "bad-argument"),
    line("move com jack nan 0", "bad-number"),
    line("move foot jack left 1,2", "bad-number"),
    # ---- files and paths
    line("load posture jack missing.pst", "not-found"),
    line("save posture jack {OUT}/abs.pst", "denied", absent=("outside/abs.pst",)),
    line("save posture jack ../up.pst", "denied", absent=("up.pst",)),
    line("save posture jack sub/../../up2.pst", "denied", absent=("up2.pst",)),
    line("save session ../../../../../../tmp/{TAG}.ses", "denied"),
    line("save posture jack outside/via-link.pst", "denied", absent=("outside/via-link.pst",)),
    line("save posture jack dangling.pst", "denied", absent=("outside/dangling-target",)),
    line("load posture jack /etc/passwd", "denied"),
    line("load posture jack evil.pst", "denied", name="symlink to /etc/passwd"),
    line("load figure /etc/hostname", "denied"),
    line("load posture jack junk.txt", "bad-file"),
    line("load posture jack empty.txt", "bad-file"),
    line("load posture jack random.bin", "bad-file"),
    line("load posture jack newer.pst", "bad-file"),
    line("load session newer.ses", "bad-file"),
    line("load session good.pst", "bad-file", name="a posture file as a session"),
    line("load figure junk.txt", "bad-file"),
    # ---- words
    line('get posture "jack', "parse", name="unbalanced quote"),
    line('get posture "ja\\ck"', "parse", name="bad escape"),
    line("# status", "parse", name="empty tag"),
    line("add constraint jack =1", "parse", name="empty key"),
    # ---- several bad lines in one write: one reply each, in order
    Case("three errors in one write", b"frobnicate\nstatus now\nget posture nobody\n",
         ("unknown-command", "arity", "not-found")),
    # ---- framing: too long, control bytes (the connection is then closed)
    Case("70000-byte line", b"help " + b"x" * 70000 + b"\n", ("too-long",), close=True),
    Case("65537-byte line", b"h" * (LIMIT_LINE + 1) + b"\n", ("too-long",), close=True),
    Case("1 MiB without a newline", b"x" * (1 << 20), ("too-long",), close=True),
    Case("NUL byte", b"get posture ja\x00ck\n", ("binary",), close=True),
    Case("SOH byte", b"status\x01\n", ("binary",), close=True),
    Case("escape sequence", b"\x1b[A\x1b[2J status\n", ("binary",), close=True),
    Case("bare carriage return inside", b"status\rstatus\n", ("binary",), close=True),
    Case("binary then a valid line", b"\x00\x01\x02\nunload figure jack\n", ("binary",),
         close=True),
    # DEL (0x7f) is a control byte too (docs/protocol.md, Framing)
    Case("DEL byte", b"get posture ja\x7fck\n", ("binary",), close=True),
    # ---- half lines, then the client goes away: nothing runs, nothing is answered
    Case("half a set joint, hang up", b"set joint jack knee_l 1", hangup=True),
    Case("half an unload, hang up", b"unload figure jill", hangup=True),
    Case("half a load, hang up", b"load human as late", hangup=True),
    Case("errors then half a delete", b"frobnicate\nstatus now\ndelete constraint hold",
         ("unknown-command", "arity"), hangup=True),
    Case("half an undo, half-close", b"undo", close=True, halfclose=True),
]


@pytest.fixture(scope="module")
def env():
    """A daemon with a prepared state, a baseline snapshot and a bystander client."""
    d = Daemon()
    d.start()
    outside = d.dir / "outside"
    outside.mkdir()
    st = d.state_dir
    (st / "sub").mkdir()
    (st / "junk.txt").write_text("neither a figure, a posture nor a session\n")
    (st / "empty.txt").write_text("")
    (st / "random.bin").write_bytes(os.urandom(4096))
    (st / "newer.pst").write_text("posture 99\nfigure human_male\nend\n")
    (st / "newer.ses").write_text("session 99\n")
    (st / "outside").symlink_to(outside)
    (st / "evil.pst").symlink_to("/etc/passwd")
    (st / "dangling.pst").symlink_to(outside / "dangling-target")
    fields = {"OUT": str(outside), "TAG": d.dir.name}
    with d.client() as c:
        # stale ids: a figure and a constraint whose slots were reused
        stale_fig = c.request("load human as temp")["figure"]
        c.request("unload figure temp")
        c.request("load human as jack")
        assert c.request("list figures")["figures"][0]["figure"].split(".")[0] == \
            stale_fig.split(".")[0], "the freed figure slot is reused"
        stale_con = c.request("add constraint jack effector=hand_l.palm as tmp")["constraint"]
        c.request("delete constraint tmp")
        hold = c.request("add constraint jack effector=foot_l.balance as hold")["constraint"]
        assert hold.split(".")[0] == stale_con.split(".")[0], "the freed constraint slot is reused"
        c.request("add constraint jack effector=hand_r.palm goal=-0.3,1.2,0.3 as reach")
        c.request("load human as jill sex=female stature=1.62")
        c.request("set joint jill knee_r 20deg")
        c.request("set joint jack elbow_l 0.5")
        c.request("behave jack on")
        c.request("settle")
        c.request("disable constraint reach")
        c.request("save posture jack good.pst")
        fields.update(STALE_FIG=stale_fig, STALE_CON=stale_con)
        base = snapshot(c)
        time.sleep(0.2)
        assert snapshot(c) == base, "the state is still moving: no baseline to compare with"
    bystander = d.client(timeout=10)
    yield {"daemon": d, "base": base, "fields": fields, "bystander": bystander}
    bystander.close()
    try:
        d.stop()
    finally:
        d.cleanup()


def test_there_are_enough_cases():
    assert len(CASES) >= 60


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_hostile_input(env, case):
    """The case's replies carry the expected codes; the state is unchanged; others are
    served."""
    d = env["daemon"]
    data = case.data
    for key, value in env["fields"].items():
        data = data.replace(b"{" + key.encode() + b"}", value.encode())
    c = d.client(timeout=10)
    try:
        try:
            c.send_raw(data)
        except ConnectionClosed:
            assert case.close, "the daemon closed the connection while the request was sent"
        if case.halfclose:
            c.sock.shutdown(socket.SHUT_WR)
        codes = []
        for _ in case.codes:
            reply = c.read_reply(timeout=10)
            assert reply["ok"] is False, reply
            codes.append(reply["error"]["code"])
            assert isinstance(reply["error"].get("message"), str)
        assert tuple(codes) == case.codes
        if case.hangup:
            c.close()
        elif case.close:
            assert wait_closed(c, 5), "the daemon must close the connection"
        else:
            # the connection still works, and nothing else was answered
            assert c.request("#after status", timeout=10)["figures"] == 2
    finally:
        c.close()
    time.sleep(0.02)  # lets a (wrongly) executed half line land before the check
    with d.client() as checker:
        assert snapshot(checker) == env["base"], "the state changed"
    for rel in case.absent:
        assert not (d.dir / rel).exists(), f"{rel} was written outside the state directory"
    tag = f"b{time.monotonic_ns()}"
    assert env["bystander"].request("get joint jill knee_r", tag=tag)["values"] == \
        [0.3490658503988659]


def test_slow_and_stalled_clients_do_not_block_others(env):
    """A client that sends half a line and stalls, one that trickles bytes, and one that
    sends 60 KB of an unfinished line do not delay anyone else."""
    d = env["daemon"]
    stalled = [d.client() for _ in range(3)]
    try:
        stalled[0].send_raw(b"set joint jack knee_l 1")
        stalled[1].send_raw(b"x" * 60000)
        for byte in b"get posture ja":
            stalled[2].send_raw(bytes([byte]))
        t0 = time.monotonic()
        for _ in range(50):
            env["bystander"].request("get posture jill")
        assert time.monotonic() - t0 < 5
        stalled[2].send_raw(b"ck\n")
        assert stalled[2].read_reply(timeout=5)["ok"] is True
    finally:
        for c in stalled:
            c.close()
    with d.client() as checker:
        assert snapshot(checker) == env["base"]


def test_client_that_does_not_read_is_dropped(env):
    """A client that floods requests and never reads is disconnected once its queued
    output passes the limit; the bystander is served meanwhile."""
    d = env["daemon"]
    flood = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    flood.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
    flood.connect(str(d.socket))
    flood.settimeout(0.5)
    request = b"get posture jack\n" * 500
    sent, dropped = 0, False
    t0 = time.monotonic()
    while time.monotonic() - t0 < 30:
        try:
            flood.sendall(request)
            sent += len(request)
        except (BrokenPipeError, ConnectionResetError):
            dropped = True
            break
        except socket.timeout:
            pass  # the daemon stopped reading from us: check that others still get served
        env["bystander"].request("status", timeout=5)
    flood.close()
    assert dropped, f"still connected after {sent} bytes of requests"
    with d.client() as checker:
        assert snapshot(checker) == env["base"]


def test_client_limit(env):
    """64 clients at once: the next is answered `limit` and closed; once one leaves,
    a new one gets in."""
    d = env["daemon"]
    with d.client() as probe:
        present = probe.status()["clients"]  # the bystander and the probe
    clients = []
    try:
        for _ in range(64 - (present - 1)):
            c = d.client(timeout=10)
            c.request("status")
            clients.append(c)
        extra = d.client(timeout=10)
        reply = extra.read_reply(timeout=10)
        assert reply["ok"] is False and reply["error"]["code"] == "limit"
        assert wait_closed(extra, 5)
        extra.close()
        clients.pop().close()
        time.sleep(0.1)
        with d.client(timeout=10) as again:
            assert again.status()["clients"] == 64
    finally:
        for c in clients:
            c.close()


def test_restart_after_hostile_input_gives_the_same_state(env):
    """Nothing the hostile inputs did reached the journal: kill -9 and restart give the
    baseline back. (Runs last: it restarts the module's daemon.)"""
    d = env["daemon"]
    env["bystander"].close()
    d.restart()
    with d.client() as c:
        assert snapshot(c) == env["base"]
    env["bystander"] = d.client(timeout=10)
