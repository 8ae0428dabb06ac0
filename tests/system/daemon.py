"""The real postured for system tests: start, stop (SIGTERM, exit status checked), kill -9.

Builds nothing: the daemon is $POSTURE_BUILD/bin/postured (default build/rel), built by
`make build/rel/bin/postured`. Each Daemon gets a short private directory under /tmp
(a Unix socket path must fit in 108 bytes) holding its socket, its state directory and
its stderr log; the log is shown when the daemon misbehaves.

Fixtures: ``daemon`` (a fresh daemon per test) and ``daemon_factory`` (start as many as
a test needs, with options). Helpers: :func:`snapshot` (the observable state), :func:`journal_records`.
"""
import os
import pathlib
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
POSTURED = BUILD / "bin" / "postured"
sys.path.insert(0, str(ROOT / "tools"))

from posture import Client, ConnectionClosed, PostureError  # noqa: E402  (after sys.path)

START_TIMEOUT = 20.0  # seconds for the socket to appear
STOP_TIMEOUT = 20.0   # seconds for SIGTERM to end the daemon


class DaemonError(AssertionError):
    """The daemon did not start, did not stop, or stopped with a bad exit status."""


def free_tcp_port():
    """A TCP port on 127.0.0.1 that was free a moment ago."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Daemon:
    """One postured process and the files it owns.

    ``fps``, ``tcp`` (True for a free port, or a port number), ``token`` and ``frames``
    become the matching options; ``extra`` is appended to the command line. The state
    directory outlives restarts, so :meth:`kill9` + :meth:`start` tests persistence.
    """

    def __init__(self, fps=None, tcp=None, token=None, frames=None, extra=()):
        if not POSTURED.exists():
            pytest.fail(f"{POSTURED} does not exist; build it first "
                        f"(make {POSTURED.relative_to(ROOT)})", pytrace=False)
        self.dir = pathlib.Path(tempfile.mkdtemp(prefix="pd-", dir="/tmp"))
        self.state_dir = self.dir / "state"
        self.state_dir.mkdir()
        self.socket = self.dir / "sock"
        self.log_path = self.dir / "stderr.log"
        self.tcp_port = free_tcp_port() if tcp is True else tcp
        self.token = token or ("t0k3n-" + os.urandom(8).hex() if self.tcp_port else None)
        self.argv = [str(POSTURED), "--socket", str(self.socket), "--state-dir", str(self.state_dir)]
        if fps is not None:
            self.argv += ["--fps", str(fps)]
        if self.tcp_port:
            self.argv += ["--tcp", str(self.tcp_port), "--token", self.token]
        if frames is not None:
            self.argv += ["--frames", str(frames)]
        if "--input" not in extra:  # the machine's own mice and keyboards stay out of tests
            self.argv += ["--input", "none"]
        self.argv += list(extra)
        self.proc = None
        self.starts = 0

    # ---- life cycle ----------------------------------------------------------

    def start(self, timeout=START_TIMEOUT):
        """Starts the daemon and returns once its socket accepts a connection."""
        assert self.proc is None, "already running"
        log = open(self.log_path, "ab")
        log.write(f"==== start {self.starts}: {' '.join(self.argv)}\n".encode())
        log.flush()
        self.proc = subprocess.Popen(self.argv, stdin=subprocess.DEVNULL, stdout=log, stderr=log,
                                     cwd=self.dir)
        log.close()
        self.starts += 1
        deadline = time.monotonic() + timeout
        while True:
            if self.proc.poll() is not None:
                code, self.proc = self.proc.returncode, None
                raise DaemonError(f"postured exited with status {code} during start-up\n"
                                  + self.log())
            if self._connectable():
                return self
            if time.monotonic() > deadline:
                self.kill9()
                raise DaemonError(f"socket {self.socket} not ready after {timeout} s\n" + self.log())
            time.sleep(0.005)

    def stop(self, timeout=STOP_TIMEOUT):
        """SIGTERM, then waits; raises DaemonError unless the exit status is 0."""
        if self.proc is None:
            return
        proc, self.proc = self.proc, None
        proc.send_signal(signal.SIGTERM)
        try:
            code = proc.wait(timeout)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
            raise DaemonError(f"postured ignored SIGTERM for {timeout} s\n" + self.log()) from None
        if code != 0:
            raise DaemonError(f"postured exited with status {code} after SIGTERM\n" + self.log())

    def kill9(self):
        """SIGKILL: the daemon gets no chance to clean up. Returns the wait status."""
        if self.proc is None:
            return None
        proc, self.proc = self.proc, None
        proc.kill()
        return proc.wait()

    def restart(self):
        """kill -9, then start again on the same state directory and socket."""
        self.kill9()
        return self.start()

    def cleanup(self):
        """Kills a daemon still running and removes its directory."""
        self.kill9()
        shutil.rmtree(self.dir, ignore_errors=True)

    @property
    def running(self):
        """True while the process lives."""
        return self.proc is not None and self.proc.poll() is None

    @property
    def pid(self):
        return self.proc.pid if self.proc else None

    # ---- talking to it -------------------------------------------------------

    def client(self, timeout=30.0):
        """A new Client on the daemon's Unix socket."""
        return Client(socket_path=str(self.socket), timeout=timeout)

    def tcp_client(self, token=None, timeout=30.0):
        """A new Client over TCP (authenticating with the daemon's token unless told)."""
        return Client(tcp=self.tcp_port, token=token or self.token, timeout=timeout)

    def log(self):
        """The daemon's stderr so far (for failure messages)."""
        try:
            text = self.log_path.read_text(errors="replace")
        except OSError:
            return "(no log)"
        return "---- postured stderr ----\n" + text[-8000:]

    def _connectable(self):
        s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        try:
            s.connect(str(self.socket))
            return True
        except OSError:
            return False
        finally:
            s.close()


@pytest.fixture
def daemon_factory():
    """Makes started daemons (``daemon_factory(fps=..., tcp=True)``); each is stopped
    with SIGTERM at the end of the test and must exit with status 0."""
    made = []

    def make(start=True, **options):
        d = Daemon(**options)
        made.append(d)
        return d.start() if start else d

    yield make
    errors = []
    for d in made:
        try:
            d.stop()
        except DaemonError as e:
            errors.append(str(e))
        finally:
            d.cleanup()
    if errors:
        pytest.fail("\n".join(errors), pytrace=False)


@pytest.fixture
def daemon(daemon_factory):
    """A fresh daemon with an empty state directory."""
    return daemon_factory()


def snapshot(client):
    """The observable state: figures, constraints, every figure's posture, and the
    behaviours of the figures that behave.

    Returns {"figures": [...], "constraints": [...], "postures": {figure id: {...}},
    "behaviours": {figure id: {...}}} exactly as the daemon reports them (floats are
    compared bit for bit).
    """
    figures = client.request("list figures")["figures"]
    constraints = client.request("list constraints")["constraints"]
    postures, behaviours = {}, {}
    for fig in figures:
        fid = fig["figure"]
        postures[fid] = client.request(f"get posture {fid}")["posture"]
        reply = client.request_reply(f"get behavior {fid}")
        if reply["ok"]:
            behaviours[fid] = reply["result"]
    return {"figures": figures, "constraints": constraints, "postures": postures,
            "behaviours": behaviours}


def journal_records(state_dir):
    """The records of a state directory's journal as (number, kind, body): each line is
    "SEQ KIND BODY CRC", CRC its checksum (src/daemon/journal_scan.h), checked here."""
    import zlib
    out = []
    for line in (pathlib.Path(state_dir) / "journal").read_bytes().splitlines():
        head, crc = line.rsplit(b" ", 1)
        assert int(crc, 16) == zlib.crc32(head), f"a journal record with a bad checksum: {line!r}"
        seq, kind, body = head.decode().split(" ", 2)
        out.append((int(seq), kind, body))
    return out


def wait_closed(client, timeout=5.0):
    """True when the daemon closes the connection within timeout (data before EOF is
    discarded); False if it stays open."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            client.read_message(timeout=max(0.01, deadline - time.monotonic()))
        except (ConnectionClosed, ConnectionError):
            return True
        except TimeoutError:
            return False
    return False


__all__ = ["Daemon", "DaemonError", "daemon", "daemon_factory", "snapshot", "wait_closed",
           "free_tcp_port", "journal_records", "Client", "PostureError", "ConnectionClosed", "ROOT", "BUILD",
           "POSTURED"]


def write_picture(client, view, name):
    """Renders a view now and writes it to the test output ($POSTURE_BUILD/test-output/NAME),
    where a person looks at what a scenario did. Returns the PNG's bytes."""
    import base64
    data = base64.b64decode(client.request(f"render view {view}")["png"])
    out = pathlib.Path(os.environ.get("POSTURE_BUILD", "build/rel")) / "test-output"
    out.mkdir(parents=True, exist_ok=True)
    (out / name).write_bytes(data)
    return data
