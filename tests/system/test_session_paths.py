"""A figure file's path as a session holds it (session files, snapshots, undo checkpoints).

- A path the session cannot hold whole (more than 255 bytes) is refused by `load figure`:
  it used to be kept cut short, so the snapshot named another file and the next start
  refused the snapshot; the daemon would not come back.
- A path with a quote or a backslash in a file name survives the session (escaped as the
  request language escapes them): it used to be written bare, and the snapshot did not read.
"""
import shutil

from daemon import Daemon, ROOT, daemon, daemon_factory  # noqa: F401 (fixtures)

BOX = ROOT / "src/figure/library/box.fig"


def test_a_figure_path_too_long_for_a_session_is_refused_and_the_daemon_comes_back(daemon):
    deep = daemon.state_dir / ("d" * 100) / ("e" * 100) / ("f" * 60)
    deep.mkdir(parents=True)
    shutil.copy(BOX, deep / "box.fig")
    rel = str((deep / "box.fig").relative_to(daemon.state_dir))
    assert len(rel) > 255
    with daemon.client() as c:
        c.request("load human as jack")
        reply = c.request_reply(f"load figure {rel} as box")
        before = c.request("list figures")["figures"]
    daemon.stop()  # a snapshot
    daemon.start()  # it used to hold the path cut short, and this start refused it
    with daemon.client() as c:
        assert c.request("list figures")["figures"] == before
    assert not reply["ok"] and "255" in reply["error"]["message"], reply


def test_a_quote_and_a_backslash_in_a_figure_path_survive_the_snapshot(daemon):
    name = 'a "quoted" \\ box.fig'
    shutil.copy(BOX, daemon.state_dir / name)
    with daemon.client() as c:
        quoted = name.replace("\\", "\\\\").replace('"', '\\"')
        c.request(f'load figure "{quoted}" as box')
        c.request("set location box 1 0 0")
        c.request("save session s.ses")
        c.request("load session s.ses")
        before = c.request("list figures")["figures"]
        assert [f["source"] for f in before] == [name]
    daemon.stop()  # the snapshot holds the path
    daemon.start()
    with daemon.client() as c:
        assert c.request("list figures")["figures"] == before
