"""The wire protocol against the real daemon: golden transcripts, the command table,
framing, events, the Python client, posturectl and TCP.

Golden transcripts live in proto/transcripts/*.txt (format at the top of basics.txt):
"> request" lines are sent as written, each "< JSON" line is matched as a subset of the
next reply (numbers within 1e-9). Every transcript runs against a fresh daemon whose
state directory holds a few prepared files, and every mismatch of a transcript is
reported at once.
"""
import json
import math
import os
import pathlib
import re
import shutil
import socket
import subprocess
import sys
import time

import pytest

from daemon import (POSTURED, ROOT, Client, ConnectionClosed, Daemon, PostureError,  # noqa: F401
                    daemon, daemon_factory, wait_closed)
from posture import format_command, quote_word

TRANSCRIPTS = sorted((ROOT / "proto" / "transcripts").glob("*.txt"))
COMMANDS_DEF = ROOT / "proto" / "commands.def"
PROTOCOL_MD = ROOT / "docs" / "protocol.md"
POSTURECTL = ROOT / "tools" / "posturectl"
TOLERANCE = 1e-9


# ---- commands.def -------------------------------------------------------------------

def _split_top_level(text):
    """Splits a C argument list at commas outside string literals."""
    args, cur, i = [], "", 0
    while i < len(text):
        ch = text[i]
        if ch == '"':
            m = re.compile(r'"(?:[^"\\]|\\.)*"').match(text, i)
            cur += m.group(0)
            i = m.end()
            continue
        if ch == ",":
            args.append(cur.strip())
            cur = ""
        else:
            cur += ch
        i += 1
    args.append(cur.strip())
    return args


def _c_string(arg):
    """The value of adjacent C string literals ("a" "b" -> "ab")."""
    parts = re.findall(r'"((?:[^"\\]|\\.)*)"', arg)
    return "".join(p.replace('\\"', '"').replace("\\\\", "\\") for p in parts)


def read_commands():
    """The rows of proto/commands.def as dicts (verb, object, min, max, flags, usage...)."""
    text = re.sub(r"/\*.*?\*/", "", COMMANDS_DEF.read_text(), flags=re.S)
    rows = []
    for m in re.finditer(r"^CMD\((.*?)\)\s*$(?=\s*(?:^CMD\(|\Z))", text, flags=re.S | re.M):
        a = _split_top_level(m.group(1))
        assert len(a) == 9, f"a CMD row with {len(a)} columns: {m.group(0)[:80]}"
        rows.append({"verb": _c_string(a[0]), "object": _c_string(a[1]), "min": int(a[2]),
                     "max": int(a[3]), "flags": a[4], "handler": a[5], "usage": _c_string(a[6]),
                     "reply": _c_string(a[7]), "summary": _c_string(a[8])})
    return rows


COMMANDS = read_commands()


def test_commands_def_is_read_whole():
    """The parser above sees every row (a sanity check of the test itself)."""
    assert len(COMMANDS) == COMMANDS_DEF.read_text().count("\nCMD(")
    assert {"verb": "set", "object": "joint"}.items() <= next(
        c for c in COMMANDS if c["handler"] == "cmd_set_joint").items()


# ---- transcripts ----------------------------------------------------------------------

class Transcript:
    """A parsed transcript: a list of steps (kind, text, line number)."""

    def __init__(self, path):
        self.path = path
        self.steps = []
        for number, raw in enumerate(path.read_text().splitlines(), 1):
            if raw.startswith(">"):
                self.steps.append(("send", raw[2:] if raw.startswith("> ") else raw[1:], number))
            elif raw.startswith("<"):
                try:
                    expected = json.loads(raw[1:])
                except ValueError as e:
                    raise ValueError(f"{path.name}:{number}: bad JSON: {e}") from None
                self.steps.append(("expect", expected, number))
            elif raw.startswith("!"):
                self.steps.append(("directive", raw[1:].strip(), number))
            elif raw.strip() and not raw.startswith("#"):
                raise ValueError(f"{path.name}:{number}: a line must start with >, <, ! or #")

    def requests(self):
        """(request text, expected reply or None) pairs."""
        out = []
        for i, (kind, text, _) in enumerate(self.steps):
            if kind == "send":
                nxt = self.steps[i + 1] if i + 1 < len(self.steps) else None
                out.append((text, nxt[1] if nxt and nxt[0] == "expect" else None))
        return out


def match(expected, actual, env, where="$"):
    """Returns a list of mismatch descriptions (empty when actual matches expected)."""
    if isinstance(expected, str):
        if expected == "*":
            return []
        if re.fullmatch(r"\$[A-Za-z_][A-Za-z0-9_]*", expected):
            name = expected[1:]
            if name not in env:
                env[name] = actual
                return []
            return [] if env[name] == actual else [f"{where}: {actual!r} != ${name} = {env[name]!r}"]
        return [] if expected == actual else [f"{where}: {actual!r} != {expected!r}"]
    if isinstance(expected, dict) and expected and all(k.startswith("$") for k in expected):
        return _match_operator(expected, actual, where)
    if isinstance(expected, bool) or expected is None:
        return [] if actual is expected else [f"{where}: {actual!r} is not {expected!r}"]
    if isinstance(expected, (int, float)):
        if isinstance(actual, bool) or not isinstance(actual, (int, float)):
            return [f"{where}: {actual!r} is not a number"]
        ok = abs(actual - expected) <= TOLERANCE * max(1.0, abs(expected))
        return [] if ok else [f"{where}: {actual!r} != {expected!r}"]
    if isinstance(expected, dict):
        if not isinstance(actual, dict):
            return [f"{where}: {actual!r} is not an object"]
        out = []
        for key, value in expected.items():
            if key not in actual:
                out.append(f"{where}: no key {key!r} (has {sorted(actual)})")
            else:
                out += match(value, actual[key], env, f"{where}.{key}")
        return out
    if isinstance(expected, list):
        if not isinstance(actual, list):
            return [f"{where}: {actual!r} is not a list"]
        if len(actual) != len(expected):
            return [f"{where}: {len(actual)} items, expected {len(expected)}: {actual!r:.300}"]
        out = []
        for i, (e, a) in enumerate(zip(expected, actual)):
            out += match(e, a, env, f"{where}[{i}]")
        return out
    raise TypeError(f"cannot match {expected!r}")


def _match_operator(expected, actual, where):
    out = []
    for op, arg in expected.items():
        if op == "$len":
            if not isinstance(actual, (list, dict, str)) or len(actual) != arg:
                out.append(f"{where}: length of {actual!r:.200} is not {arg}")
            continue
        if isinstance(actual, bool) or not isinstance(actual, (int, float)):
            out.append(f"{where}: {actual!r} is not a number")
        elif op == "$lt" and not actual < arg:
            out.append(f"{where}: {actual!r} is not < {arg}")
        elif op == "$gt" and not actual > arg:
            out.append(f"{where}: {actual!r} is not > {arg}")
        elif op == "$approx" and not abs(actual - arg[0]) <= arg[1]:
            out.append(f"{where}: {actual!r} is not within {arg[1]} of {arg[0]}")
        elif op not in ("$lt", "$gt", "$approx"):
            raise ValueError(f"unknown operator {op}")
    return out


def substitute(line, env):
    """Replaces $NAME words of a request with captured values."""
    def repl(m):
        if m.group(1) not in env:
            raise KeyError(f"${m.group(1)} is not captured yet")
        return str(env[m.group(1)])
    return re.sub(r"\$([A-Za-z_][A-Za-z0-9_]*)", repl, line)


def prepare_state_dir(state_dir):
    """The files transcripts may refer to (see basics.txt)."""
    shutil.copytree(ROOT / "src" / "figure" / "library", state_dir / "figures")
    (state_dir / "junk.txt").write_text("this is neither a figure, a posture nor a session\n")
    (state_dir / "newer.pst").write_text("posture 99\nfigure human_male\nend\n")
    shutil.copy(ROOT / "data" / "ansur2" / "ANSUR_II_FEMALE_Public.csv", state_dir / "ansur_women.csv")


def run_transcript(d, transcript):
    """Replays a transcript; returns every mismatch as 'file:line: text'."""
    env, failures = {}, []
    client = d.client(timeout=20)
    last_request = None
    try:
        for kind, text, number in transcript.steps:
            here = f"{transcript.path.name}:{number}"
            if kind == "send":
                if last_request and last_request[1]:
                    failures.append(f"{last_request[0]}: no '<' line for a request that gets a reply")
                try:
                    line = substitute(text, env)
                except KeyError as e:
                    failures.append(f"{here}: {e.args[0]}; request skipped")
                    last_request = None
                    continue
                client.send_raw(line.encode() + b"\n")
                silent = not line.strip(" \t") or line.strip(" \t").startswith("%")
                last_request = (here, not silent, line)
            elif kind == "expect":
                if last_request is None:
                    failures.append(f"{here}: a reply is expected but no request went")
                    continue
                try:
                    reply = client.read_reply(timeout=20)
                except (ConnectionClosed, TimeoutError) as e:
                    failures.append(f"{here}: no reply to {last_request[2]!r}: {e}")
                    return failures
                for problem in match(text, reply, env):
                    failures.append(f"{here}: {last_request[2]!r}\n      {problem}\n      reply "
                                    f"{json.dumps(reply)[:400]}")
                last_request = None
            elif text == "closed":
                if not wait_closed(client, 5):
                    failures.append(f"{here}: the connection is still open")
                last_request = None
            elif text == "reconnect":
                client.close()
                client = d.client(timeout=20)
            else:
                failures.append(f"{here}: unknown directive {text!r}")
    finally:
        client.close()
    return failures


@pytest.mark.parametrize("path", TRANSCRIPTS, ids=[p.stem for p in TRANSCRIPTS])
def test_transcript(daemon_factory, path):
    """Every reply of the transcript matches its expectation."""
    panel = ROOT / "tests" / "input" / "panel.map"
    d = daemon_factory(start=False, extra=("--panel", str(panel)))
    prepare_state_dir(d.state_dir)
    d.start()
    failures = run_transcript(d, Transcript(path))
    assert not failures, f"{len(failures)} mismatches:\n" + "\n".join(failures)


def _command_of(request):
    words = request.split()
    if words and words[0].startswith("#"):
        words = words[1:]
    for c in COMMANDS:
        if words[:1] == [c["verb"]] and (not c["object"] or words[1:2] == [c["object"]]):
            return (c["verb"], c["object"])
    return None


def test_transcripts_cover_every_command():
    """Each command of commands.def appears in a transcript answered ok and answered
    with an error."""
    seen = {(c["verb"], c["object"]): set() for c in COMMANDS}
    for path in TRANSCRIPTS:
        for request, expected in Transcript(path).requests():
            cmd = _command_of(request)
            if cmd and isinstance(expected, dict) and "ok" in expected:
                seen[cmd].add(expected["ok"])
    missing = [f"{v} {o}".strip() + f" (ok={sorted(s)})" for (v, o), s in seen.items()
               if s != {True, False}]
    assert not missing, "commands without a happy path and an error in proto/transcripts: " \
        + ", ".join(missing)


def test_subset_matcher():
    """The matcher the transcripts rely on fails where it should."""
    env = {}
    assert match({"a": 1}, {"a": 1.0000000001, "b": 2}, env) == []
    assert match({"a": 1}, {"a": 1.00001}, env)
    assert match([1, 2], [1, 2, 3], env)
    assert match({"a": "$X"}, {"a": "f0.1"}, env) == [] and env["X"] == "f0.1"
    assert match("$X", "f0.2", env)
    assert match({"$lt": 1}, 2, env) and not match({"$lt": 3}, 2, env)
    assert match({"k": "*"}, {}, env)
    assert match(True, 1, env)


# ---- the command table ----------------------------------------------------------------

def test_help_lists_commands_def(daemon):
    """`help` lists exactly the rows of commands.def, in order, with their usage and
    summary; `help VERB OBJECT` gives one row."""
    with daemon.client() as c:
        listed = c.help()
        assert [(x["usage"], x["summary"]) for x in listed] == \
            [(r["usage"], r["summary"]) for r in COMMANDS]
        for row in COMMANDS:
            words = [row["verb"]] + ([row["object"]] if row["object"] else [])
            one = c.call("help", *words)["commands"]
            if row["object"]:
                assert [x["usage"] for x in one] == [row["usage"]]
            else:
                assert row["usage"] in [x["usage"] for x in one]


def test_protocol_md_table_is_generated():
    """docs/protocol.md holds the table `postured --protocol-table` prints."""
    if not POSTURED.exists():
        pytest.fail(f"{POSTURED} is not built")
    out = subprocess.run([str(POSTURED), "--protocol-table"], capture_output=True, text=True,
                         timeout=10)
    assert out.returncode == 0, out.stderr
    table = out.stdout.strip()
    assert table.count("\n") + 1 >= len(COMMANDS), table
    assert table in PROTOCOL_MD.read_text(), "docs/protocol.md's command table is out of date"


def test_arity_follows_commands_def(daemon):
    """One word too many is `arity` for every command (min/max come from commands.def)."""
    with daemon.client() as c:
        for row in COMMANDS:
            words = [row["verb"]] + ([row["object"]] if row["object"] else [])
            words += ["x"] * (row["max"] + 1)
            reply = c.request_reply(format_command(*words))
            assert reply["ok"] is False and reply["error"]["code"] == "arity", (words, reply)
            if row["min"] > 0:
                words = words[:len(words) - row["max"] - 1] + ["x"] * (row["min"] - 1)
                reply = c.request_reply(format_command(*words))
                assert reply["error"]["code"] == "arity", (words, reply)


# ---- framing --------------------------------------------------------------------------

def test_pipelined_requests_answered_in_order(daemon):
    """200 requests in one write: 200 replies, in order, each with its own tag."""
    with daemon.client() as c:
        c.request("load human as jack")
        lines = []
        for i in range(200):
            lines.append(f"#{i} " + ("status" if i % 3 == 0 else "get joint jack knee_l"
                                     if i % 3 == 1 else "frobnicate"))
        replies = c.pipeline(lines)
        assert [r.get("tag") for r in replies] == [str(i) for i in range(200)]
        assert [r["ok"] for r in replies] == [i % 3 != 2 for i in range(200)]


def test_crlf_and_split_writes(daemon):
    """A \\r before the newline is ignored, and a line may arrive in pieces."""
    with daemon.client() as c:
        c.send_raw(b"#a status\r\n")
        assert c.read_reply()["tag"] == "a"
        for piece in (b"#b ge", b"t pos", b"ture nob", b"ody\r", b"\n"):
            c.send_raw(piece)
            time.sleep(0.01)
        reply = c.read_reply()
        assert reply["tag"] == "b" and reply["error"]["code"] == "not-found"


def test_replies_are_single_json_lines(daemon):
    """Replies are strict JSON (no NaN), one object a line, with ok and result/error."""
    with daemon.client() as c:
        c.request("load human as jack")
        for line in ("status", "show figure jack", "get posture jack", "list figures",
                     "help", "get site jack head.top", "frobnicate \"é\""):
            c.send_line(line)
            msg = c.read_reply()
            assert msg["ok"] in (True, False)
            assert ("result" in msg) == msg["ok"] and ("error" in msg) != msg["ok"]


def test_numbers_are_printed_exactly(daemon):
    """A value set with 17 digits comes back bit for bit."""
    with daemon.client() as c:
        c.request("load human as jack")
        value = 0.12345678901234567
        c.call("set", "joint", "jack", "knee_l", value)
        assert c.request("get joint jack knee_l")["values"] == [value]


# ---- events ---------------------------------------------------------------------------

def test_posture_events_reach_subscribers_only(daemon):
    """While the solver moves a figure, a subscriber gets posture events naming it, a
    client that did not subscribe gets none, and after `unsubscribe` they stop."""
    with daemon.client() as sub, daemon.client() as other, daemon.client() as quiet:
        other.request("load human as jack")
        assert sub.subscribe("posture") == {}
        other.request("add constraint jack effector=hand_r.palm goal=-0.3,1.3,0.3 as reach")
        # the subscriber's own requests keep working while events queue up
        assert sub.request("#x status")["figures"] == 1
        ev = sub.next_event(timeout=5)
        assert ev is not None and ev["event"] == "posture" and ev["figure"] == "jack", ev
        assert quiet.next_event(timeout=0.3) is None
        sub.unsubscribe("posture")
        for _ in sub.events(timeout=0.3):
            pass  # drain what was already under way
        other.request("set goal reach -0.2 1.2 0.4")
        assert sub.next_event(timeout=0.5) is None


def test_events_interleave_with_pipelined_replies(daemon):
    """Events between pipelined replies are filed apart; replies keep their order."""
    with daemon.client() as sub, daemon.client() as other:
        other.request("load human as jack")
        sub.subscribe("posture")
        sub.subscribe("telemetry")
        other.request("add constraint jack effector=hand_r.palm goal=-0.3,1.3,0.3 as reach")
        replies = []
        for batch in range(10):
            lines = [f"#{batch}.{i} get joint jack elbow_r" for i in range(20)]
            lines.append(f"#{batch}.move move goal reach 0 {(-1) ** batch * 0.05} 0")
            replies += sub.pipeline(lines)
            time.sleep(0.02)
        assert [r["tag"] for r in replies] == [
            f"{b}.{i}" for b in range(10) for i in list(range(20)) + ["move"]]
        assert all(r["ok"] for r in replies)
        sub.unsubscribe("posture")
        sub.unsubscribe("telemetry")
        events = sub.pending_events() + list(sub.events(timeout=0.5))
        kinds = {e["event"] for e in events}
        assert kinds == {"posture", "telemetry"}, kinds


# ---- the Python client ----------------------------------------------------------------

def test_quote_word_round_trips(daemon):
    """Quoted words reach the daemon as one word: a name with a space is an error about
    that name, escapes survive."""
    assert quote_word("plain") == "plain"
    assert quote_word('a "b" c\\') == '"a \\"b\\" c\\\\"'
    assert quote_word(0.1) == "0.1"
    with daemon.client() as c:
        with pytest.raises(PostureError) as e:
            c.call("get", "posture", 'no "such" figure')
        assert e.value.code == "not-found"
        assert 'no "such" figure' in e.value.message


def test_client_default_socket(daemon_factory, monkeypatch, tmp_path):
    """Client() with no path finds the daemon at $XDG_RUNTIME_DIR/posture/postured.sock,
    else /tmp/posture-$UID/postured.sock."""
    from posture import default_socket_path
    assert default_socket_path({"XDG_RUNTIME_DIR": "/run/user/7"}) == \
        "/run/user/7/posture/postured.sock"
    assert default_socket_path({}) == f"/tmp/posture-{os.getuid()}/postured.sock"
    d = daemon_factory(start=False)
    runtime = d.dir / "run"
    (runtime / "posture").mkdir(parents=True)
    d.socket = runtime / "posture" / "postured.sock"
    d.argv[d.argv.index("--socket") + 1] = str(d.socket)
    d.start()
    monkeypatch.setenv("XDG_RUNTIME_DIR", str(runtime))
    with Client() as c:
        assert "version" in c.status()


def test_client_errors_and_tags(daemon):
    """Errors raise PostureError with code and tag; request() refuses lines without
    replies; a closed connection raises ConnectionClosed."""
    with daemon.client() as c:
        with pytest.raises(PostureError) as e:
            c.request("frobnicate", tag="t9")
        assert (e.value.code, e.value.tag) == ("unknown-command", "t9")
        with pytest.raises(ValueError):
            c.request("% a comment")
        assert c.request("status", tag="ok1")["figures"] == 0
        c.request("quit")
        with pytest.raises(ConnectionClosed):
            c.request("status")


# ---- posturectl -----------------------------------------------------------------------

def posturectl(daemon, *args, stdin=None):
    """Runs posturectl against the daemon; returns the CompletedProcess."""
    return subprocess.run([sys.executable, str(POSTURECTL), "--socket", str(daemon.socket), *args],
                          input=stdin, capture_output=True, text=True, timeout=60)


def test_posturectl_one_shot(daemon):
    """One command prints its JSON result; an error goes to stderr with status 1."""
    out = posturectl(daemon, "load", "human", "as", "jack")
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout)["name"] == "jack"
    out = posturectl(daemon, "get joint jack knee_l")
    assert out.returncode == 0 and json.loads(out.stdout)["values"] == [0]
    out = posturectl(daemon, "get", "joint", "jack", "kneecap")
    assert out.returncode == 1 and out.stdout == ""
    assert "not-found" in out.stderr


def test_posturectl_scripts(daemon, tmp_path):
    """Scripts stop at the first error unless --keep-going; comments are skipped."""
    script = tmp_path / "s.txt"
    script.write_text("% make a figure\nload human as jack\n\nset joint jack knee_l 10deg\n"
                      "get joint jack nope\nset joint jack knee_l 20deg\n")
    out = posturectl(daemon, "-f", str(script))
    assert out.returncode == 1
    assert len(out.stdout.splitlines()) == 2 and "s.txt:5" in out.stderr
    with daemon.client() as c:
        assert c.request("get joint jack knee_l")["values"] == [math.radians(10)]
        c.request("unload figure jack")
    out = posturectl(daemon, "--keep-going", "-", stdin=script.read_text())
    assert out.returncode == 1 and len(out.stdout.splitlines()) == 3
    with daemon.client() as c:
        assert c.request("get joint jack knee_l")["values"] == [math.radians(20)]
    out = posturectl(daemon, "-", stdin="status\nlist figures\n")
    assert out.returncode == 0
    assert [sorted(json.loads(x)) for x in out.stdout.splitlines()][1] == ["figures"]


def test_posturectl_cannot_connect(tmp_path):
    """No daemon: a message on stderr, a failing exit status."""
    out = subprocess.run([sys.executable, str(POSTURECTL), "--socket", str(tmp_path / "none"),
                          "status"], capture_output=True, text=True, timeout=30)
    assert out.returncode != 0 and "cannot connect" in out.stderr


# ---- TCP ------------------------------------------------------------------------------

def test_tcp_with_token(daemon_factory):
    """Over TCP, `auth TOKEN` first; then the same protocol."""
    d = daemon_factory(tcp=True)
    with d.tcp_client() as c:
        assert "version" in c.status()
        c.request("load human as jack")
    with d.client() as c:
        assert [f["name"] for f in c.request("list figures")["figures"]] == ["jack"]


def test_tcp_bad_token_is_denied(daemon_factory):
    """A wrong token is answered `denied` and the connection closed; so is a first line
    that is not auth."""
    d = daemon_factory(tcp=True)
    with pytest.raises(PostureError) as e:
        d.tcp_client(token="wrong")
    assert e.value.code == "denied"
    s = socket.create_connection(("127.0.0.1", d.tcp_port), timeout=5)
    s.sendall(b"status\n")
    data = b""
    while True:
        chunk = s.recv(4096)
        if not chunk:
            break
        data += chunk
    s.close()
    assert b'"version"' not in data
    with d.client() as c:
        assert c.status()["figures"] == 0


def listening_tcp_ports(pid):
    """(hex address, port) of every TCP socket a process listens on (from /proc: its
    socket inodes in state LISTEN); 127.0.0.1 is "0100007F"."""
    inodes = set()
    for fd in pathlib.Path(f"/proc/{pid}/fd").iterdir():
        try:
            target = os.readlink(fd)
        except OSError:
            continue
        if target.startswith("socket:["):
            inodes.add(target[8:-1])
    ports = set()
    for table in ("/proc/net/tcp", "/proc/net/tcp6"):
        try:
            rows = pathlib.Path(table).read_text().splitlines()[1:]
        except OSError:
            continue
        for row in rows:
            f = row.split()
            if f[3] == "0A" and f[9] in inodes:  # 0A: LISTEN
                addr, port = f[1].rsplit(":", 1)
                ports.add((addr, int(port, 16)))
    return ports


def test_tcp_is_off_by_default(daemon_factory):
    """Without --tcp the daemon listens on no TCP port; with it, on exactly that one,
    on 127.0.0.1 only."""
    plain = daemon_factory()
    assert listening_tcp_ports(plain.pid) == set()
    with_tcp = daemon_factory(tcp=True)
    assert listening_tcp_ports(with_tcp.pid) == {("0100007F", with_tcp.tcp_port)}
