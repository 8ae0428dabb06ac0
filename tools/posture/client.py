"""A client for postured's line protocol (docs/protocol.md), standard library only.

One request is one line; every request gets exactly one reply line, in order:
``{"ok":true,"result":{...}}`` or ``{"ok":false,"error":{"code":...,"message":...}}``,
carrying ``"tag"`` when the request began with ``#TAG``. After ``subscribe`` the daemon
also sends event lines ``{"event":KIND,...}`` between replies. The client reads every
line once and files it under replies or events, so a caller waiting for a reply never
sees an event and a caller waiting for events never loses a reply.

Typical use::

    with Client() as c:                      # default socket, as docs/protocol.md says
        fig = c.call("load", "human", "as", "jack")["figure"]
        c.request("set joint jack knee_l 30deg")
        c.subscribe("posture")
        for ev in c.events(timeout=1.0):
            print(ev)
"""
import collections
import json
import os
import socket
import time

#: seconds a request waits for its reply unless told otherwise
DEFAULT_TIMEOUT = 30.0
#: the daemon's limit on a request line (bytes, newline excluded)
MAX_LINE = 65536
#: the daemon's limit on words a line
MAX_WORDS = 64
#: a reply line longer than this is taken as a broken stream (a frame event may be large)
MAX_REPLY = 256 * 1024 * 1024

# characters that force a word into double quotes
_QUOTE_CHARS = frozenset(' \t"\\')


class PostureError(Exception):
    """The daemon answered a request with an error reply.

    Attributes: ``code`` (one of docs/protocol.md's error codes, e.g. ``"not-found"``),
    ``message`` (the daemon's human-readable text), ``tag`` (the request's tag or None)
    and ``reply`` (the whole decoded reply object).
    """

    def __init__(self, code, message, tag=None, reply=None):
        super().__init__(f"{code}: {message}")
        self.code = code
        self.message = message
        self.tag = tag
        self.reply = reply


class ProtocolError(Exception):
    """The daemon sent something the protocol does not allow (bad JSON, wrong tag...)."""


class ConnectionClosed(ConnectionError):
    """The daemon closed the connection; ``partial`` holds bytes of an unfinished line."""

    def __init__(self, message, partial=b""):
        super().__init__(message)
        self.partial = partial


def default_socket_path(environ=None):
    """Returns the daemon's default socket path as docs/protocol.md gives it.

    ``$XDG_RUNTIME_DIR/posture/postured.sock`` when XDG_RUNTIME_DIR is set and not
    empty, else ``/tmp/posture-$UID/postured.sock``.
    """
    env = os.environ if environ is None else environ
    runtime = env.get("XDG_RUNTIME_DIR")
    if runtime:
        return os.path.join(runtime, "posture", "postured.sock")
    return f"/tmp/posture-{os.getuid()}/postured.sock"


def quote_word(word):
    """Returns ``word`` as one protocol word, in double quotes when it needs them.

    Numbers are written with 17 significant digits, so they reach the daemon exactly.
    """
    if isinstance(word, float):
        return repr(word)  # shortest repr that reads back bit-identically
    word = str(word)
    if word and not _QUOTE_CHARS.intersection(word):
        return word
    return '"' + word.replace("\\", "\\\\").replace('"', '\\"') + '"'


def format_command(*words, **keys):
    """Joins words (and ``key=value`` pairs from keyword arguments) into a request line.

    A list or tuple value becomes a comma-separated list: ``goal=(0.1, 1, 0)`` gives
    ``goal=0.1,1,0``. ``format_command("set", "joint", "jack", "knee_l", "30deg")``.
    """
    parts = [quote_word(w) for w in words]
    for key, value in keys.items():
        if isinstance(value, (list, tuple)):
            value = ",".join(quote_word(v) for v in value)
        else:
            value = quote_word(value)
        parts.append(f"{key}={value}")
    return " ".join(parts)


def is_silent(line):
    """True when the daemon sends no reply to ``line``: blank, or a ``%`` comment."""
    body = line.strip(" \t\r\n")
    return not body or body.startswith("%")


def split_tag(line):
    """Splits ``"#TAG rest"`` into ``("TAG", "rest")``; a line without a tag gives (None, line)."""
    if line.startswith("#"):
        head, _, rest = line.partition(" ")
        return head[1:], rest
    return None, line


def _reject_constant(name):
    raise ValueError(f"{name} is not JSON")


class Client:
    """One connection to postured, over its Unix socket or (when started so) TCP.

    ``socket_path``: the Unix socket; None means :func:`default_socket_path`.
    ``tcp``: a port number, ``"HOST:PORT"`` or ``(host, port)``; the host defaults to
    127.0.0.1. Over TCP, ``token`` is sent first as ``auth TOKEN``.
    ``timeout``: seconds any single wait for the daemon may take (None: forever).

    Replies and events are kept apart: :meth:`read_reply` files events it meets for
    :meth:`next_event`, and :meth:`next_event` files replies it meets for
    :meth:`read_reply`. Requests may be pipelined with :meth:`send_line` and their
    replies collected, in order, with :meth:`read_reply`.
    """

    def __init__(self, socket_path=None, tcp=None, token=None, timeout=DEFAULT_TIMEOUT,
                 connect=True):
        if tcp is not None and socket_path is not None:
            raise ValueError("give socket_path or tcp, not both")
        if tcp is not None and token is None:
            raise ValueError("TCP needs a token")
        self.socket_path = socket_path
        self.tcp = _parse_tcp(tcp) if tcp is not None else None
        self.token = token
        self.timeout = timeout
        self.sock = None
        self._buf = bytearray()
        self._replies = collections.deque()
        self._events = collections.deque()
        self._outstanding = 0  # requests sent whose replies have not been read
        if connect:
            self.connect()

    # ---- connection --------------------------------------------------------

    def connect(self):
        """Opens the connection (and authenticates over TCP); returns self."""
        if self.sock is not None:
            raise RuntimeError("already connected")
        if self.tcp is not None:
            sock = socket.create_connection(self.tcp, timeout=self.timeout)
        else:
            path = self.socket_path or default_socket_path()
            sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
            sock.settimeout(self.timeout)
            try:
                sock.connect(path)
            except OSError:
                sock.close()
                raise
        self.sock = sock
        if self.tcp is not None:
            self.request(format_command("auth", self.token))
        return self

    def close(self):
        """Closes the connection (idempotent). Unread replies and events are dropped."""
        if self.sock is not None:
            try:
                self.sock.close()
            finally:
                self.sock = None

    @property
    def closed(self):
        """True once :meth:`close` ran or before :meth:`connect`."""
        return self.sock is None

    def fileno(self):
        """The socket's file descriptor, for select/poll."""
        return self.sock.fileno()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    # ---- sending -------------------------------------------------------------

    def send_raw(self, data):
        """Sends bytes exactly as given: no newline added, no reply expected or counted."""
        if isinstance(data, str):
            data = data.encode()
        try:
            self._require_open().sendall(data)
        except (BrokenPipeError, ConnectionResetError) as e:
            raise ConnectionClosed(f"postured closed the connection ({e.strerror})") from None

    def send_line(self, line, tag=None):
        """Sends one request line (a newline is added) without waiting for its reply.

        ``tag`` puts ``#TAG `` in front. Returns True when a reply will come, False for
        a blank or comment line, which the daemon does not answer.
        """
        if "\n" in line:
            raise ValueError("a request is one line")
        if tag is not None:
            _check_tag(tag)
            line = f"#{tag} {line}"
        self.send_raw(line.encode() + b"\n")
        if tag is None and is_silent(line):
            return False
        self._outstanding += 1
        return True

    # ---- receiving -----------------------------------------------------------

    def read_message(self, timeout=None):
        """Reads the next line from the wire, reply or event, bypassing the queues.

        Raises ConnectionClosed at end of stream, TimeoutError when nothing comes within
        ``timeout`` (default: the client's), ProtocolError for a line that is not a JSON
        object holding ``ok`` or ``event``.
        """
        line = self._read_line(self.timeout if timeout is None else timeout)
        try:
            msg = json.loads(line, parse_constant=_reject_constant)
        except ValueError as e:
            raise ProtocolError(f"reply is not JSON ({e}): {line[:200]!r}") from None
        if not isinstance(msg, dict) or ("ok" in msg) == ("event" in msg):
            raise ProtocolError(f"neither a reply nor an event: {line[:200]!r}")
        return msg

    def read_reply(self, timeout=None):
        """Returns the next reply object (``{"ok":...}``), filing events met on the way."""
        if self._replies:
            msg = self._replies.popleft()
        else:
            while True:
                msg = self.read_message(timeout)
                if "event" in msg:
                    self._events.append(msg)
                    continue
                break
        if self._outstanding > 0:
            self._outstanding -= 1
        return msg

    def next_event(self, timeout=None):
        """Returns the next event object, or None if none comes within ``timeout`` seconds.

        ``timeout`` None waits as long as the client's timeout; 0 only looks at what has
        already arrived. Replies met on the way are kept for :meth:`read_reply`.
        """
        if self._events:
            return self._events.popleft()
        wait = self.timeout if timeout is None else timeout
        deadline = None if wait is None else time.monotonic() + wait
        while True:
            left = None if deadline is None else max(0.0, deadline - time.monotonic())
            try:
                # a zero timeout would make the socket non-blocking; poll briefly instead
                msg = self.read_message(timeout=1e-6 if left == 0 else left)
            except TimeoutError:
                return None
            if "event" in msg:
                return msg
            self._replies.append(msg)
            if left == 0:
                return None

    def events(self, timeout=None):
        """Iterates over events until none arrives within ``timeout`` seconds."""
        while True:
            ev = self.next_event(timeout)
            if ev is None:
                return
            yield ev

    def pending_events(self):
        """Returns (and forgets) the events already received but not yet consumed."""
        evs = list(self._events)
        self._events.clear()
        return evs

    # ---- requests ------------------------------------------------------------

    def request(self, line, tag=None, timeout=None):
        """Sends one request line and returns its result object; raises PostureError.

        The line is sent as written (quotes and ``key=value`` words included). A blank
        or comment line gets no reply, so it is refused here (ValueError).
        """
        reply = self.request_reply(line, tag=tag, timeout=timeout)
        return result_of(reply)

    def request_reply(self, line, tag=None, timeout=None):
        """Like :meth:`request` but returns the whole reply object, error or not."""
        if self._outstanding:
            raise RuntimeError(f"{self._outstanding} pipelined replies are still unread")
        if tag is None and is_silent(line):
            raise ValueError("blank and comment lines get no reply")
        self.send_line(line, tag=tag)
        reply = self.read_reply(timeout)
        want = tag if tag is not None else split_tag(line)[0]
        if reply.get("tag") != want:
            raise ProtocolError(f"reply tag {reply.get('tag')!r}, expected {want!r}")
        return reply

    def call(self, *words, tag=None, **keys):
        """Builds a request from words (see :func:`format_command`) and sends it."""
        return self.request(format_command(*words, **keys), tag=tag)

    def pipeline(self, lines, timeout=None):
        """Sends all lines at once, then returns their reply objects in order."""
        if any("\n" in line for line in lines):
            raise ValueError("a request is one line")
        expected = sum(1 for line in lines if not is_silent(line))
        payload = b"".join(line.encode() + b"\n" for line in lines)
        self.send_raw(payload)
        self._outstanding += expected
        return [self.read_reply(timeout) for _ in range(expected)]

    # ---- conveniences --------------------------------------------------------

    def subscribe(self, kind):
        """Starts events of ``kind`` (posture, telemetry, message, frame)."""
        return self.request(format_command("subscribe", kind))

    def unsubscribe(self, kind):
        """Stops events of ``kind``."""
        return self.request(format_command("unsubscribe", kind))

    def help(self):
        """The daemon's command list: [{"usage":..., "summary":...}, ...]."""
        return self.request("help")["commands"]

    def status(self):
        """The daemon's status object."""
        return self.request("status")

    # ---- internals -----------------------------------------------------------

    def _require_open(self):
        if self.sock is None:
            raise ConnectionClosed("not connected")
        return self.sock

    def _read_line(self, timeout):
        sock = self._require_open()
        while True:
            nl = self._buf.find(b"\n")
            if nl >= 0:
                line = bytes(self._buf[:nl])
                del self._buf[:nl + 1]
                return line
            if len(self._buf) > MAX_REPLY:
                raise ProtocolError("reply line too long")
            sock.settimeout(timeout)
            try:
                chunk = sock.recv(1 << 16)
            except socket.timeout:
                raise TimeoutError("no reply from postured in time") from None
            except ConnectionResetError:
                chunk = b""
            if not chunk:
                partial = bytes(self._buf)
                self._buf.clear()
                raise ConnectionClosed("postured closed the connection", partial)
            self._buf += chunk


def result_of(reply):
    """Returns a reply's result object, or raises PostureError for an error reply."""
    if reply.get("ok") is True:
        result = reply.get("result")
        if not isinstance(result, dict):
            raise ProtocolError(f"ok reply without a result object: {reply!r}")
        return result
    err = reply.get("error")
    if reply.get("ok") is not False or not isinstance(err, dict):
        raise ProtocolError(f"malformed reply: {reply!r}")
    raise PostureError(err.get("code"), err.get("message", ""), reply.get("tag"), reply)


def _check_tag(tag):
    tag = str(tag)
    if not tag or any(ch in tag for ch in " \t\r\n"):
        raise ValueError(f"bad tag {tag!r}")


def _parse_tcp(tcp):
    if isinstance(tcp, int):
        return ("127.0.0.1", tcp)
    if isinstance(tcp, str):
        host, sep, port = tcp.rpartition(":")
        return (host if sep and host else "127.0.0.1", int(port))
    host, port = tcp
    return (host, int(port))
