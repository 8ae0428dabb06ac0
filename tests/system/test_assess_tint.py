"""A view's tint (`set view VIEW tint=rula|reba|owas|off`): the setting itself.

- `set view` takes a method or off, refuses anything else and changes nothing then;
  `list views` says each view's tint; the tint is a change of the environment (undo
  takes it back) and a session keeps it (a view without one is written as before, so
  sessions of untinted views read by older daemons too).
"""
from daemon import daemon, daemon_factory  # noqa: F401 (fixtures)

VIEW = "add view main width=320 height=240 eye=1.9,1.55,3.1 target=0,0.95,0"


def tints(c):
    return {v["name"]: v["tint"] for v in c.request("list views")["views"]}


def test_set_view_tint_takes_each_method_and_off(daemon):
    with daemon.client() as c:
        c.request(VIEW)
        assert tints(c) == {"main": "off"}
        for t in ("rula", "reba", "owas", "off"):
            assert c.request(f"set view main tint={t}") == {"view": "main", "tint": t}
            assert tints(c) == {"main": t}


def test_bad_tint_requests_are_refused_and_change_nothing(daemon):
    with daemon.client() as c:
        c.request(VIEW)
        c.request("set view main tint=reba")
        for line, code in (("set view main tint=niosh", "bad-argument"),
                           ("set view main tint=", "bad-argument"),
                           ("set view main colour=rula", "bad-argument"),
                           ("set view nowhere tint=rula", "not-found"),
                           ("set view main", "arity")):
            reply = c.request_reply(line)
            assert not reply["ok"] and reply["error"]["code"] == code, (line, reply)
            assert tints(c) == {"main": "reba"}, line


def test_tint_is_undone_and_redone(daemon):
    with daemon.client() as c:
        c.request(VIEW)
        c.request("set view main tint=owas")
        c.request("undo")
        assert tints(c) == {"main": "off"}
        c.request("redo")
        assert tints(c) == {"main": "owas"}


def test_a_session_keeps_the_tint_and_an_untinted_view_is_written_as_before(daemon):
    with daemon.client() as c:
        c.request(VIEW)
        c.request("add view side width=320 height=240 eye=3,1.2,0 target=0,0.95,0")
        c.request("set view side tint=rula")
        c.request("save session s.ses")
        text = (daemon.state_dir / "s.ses").read_text()
        lines = {ln.split()[1]: ln for ln in text.splitlines() if ln.startswith("view ")}
        assert "tint=" not in lines["main"] and lines["side"].endswith(" tint=rula"), lines
        c.request("set view side tint=off")
        c.request("load session s.ses")
        assert tints(c) == {"main": "off", "side": "rula"}
    daemon.restart()  # the journal's snapshot and records keep it too
    with daemon.client() as c:
        assert tints(c) == {"main": "off", "side": "rula"}


def test_a_session_with_a_bad_tint_is_refused_whole(daemon):
    with daemon.client() as c:
        c.request(VIEW)
        c.request("save session s.ses")
        path = daemon.state_dir / "s.ses"
        path.write_text(path.read_text().replace(" fovy=", " tint=purple fovy="))
        reply = c.request_reply("load session s.ses")
        assert not reply["ok"] and "tint" in reply["error"]["message"], reply
        assert tints(c) == {"main": "off"}
