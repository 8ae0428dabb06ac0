"""A figure file's path as a session holds it (session files, snapshots, undo checkpoints).

- A path the session cannot hold whole (more than 255 bytes) is refused by `load figure`:
  it used to be kept cut short, so the snapshot named another file and the next start
  refused the snapshot; the daemon would not come back.
- A path with a quote or a backslash in a file name survives the session (escaped as the
  request language escapes them): it used to be written bare, and the snapshot did not read.
- A session file names figure files inside the state directory, as `load figure` does: a
  path out of it (absolute, or through `..`) is refused; one used to reach any file, a FIFO
  or a terminal among them, and the daemon then waited on it for ever.
"""
import os
import shutil
import threading

import pytest

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


def let_go(fifo):
    """opens the FIFO for writing and closes it, if a reader waits on it"""
    try:
        os.close(os.open(fifo, os.O_WRONLY | os.O_NONBLOCK))
    except OSError:
        pass  # nobody reads it


@pytest.mark.parametrize("path", ["../outside.fig", "sub/../../outside.fig", "/ABS/outside.fig",
                                  "lib:../outside.fig", "lib:sub/box.fig", "lib:.hidden.fig"])
def test_a_session_names_no_figure_file_outside_the_state_directory(path, tmp_path):
    d = Daemon(extra=("--library", str(ROOT / "src/figure/library")))
    try:
        outside = d.dir / "outside.fig"
        os.mkfifo(outside)  # a reader of it would wait for a writer for ever
        path = path.replace("/ABS", str(d.dir))
        (d.state_dir / "sub").mkdir()
        (d.state_dir / "s.ses").write_text(
            "session 1\nnext_gen 2\n"
            f'figure box slot=0 gen=1 file "{path}"\n'
            "root box box.base 0,0,0,1,0,0,0,1,0,0,0,1\nq box -\nend\n")
        d.start()
        # if the daemon opened the FIFO, a writer lets it go on (and the test fails below)
        threading.Timer(10, let_go, (outside,)).start()
        with d.client(timeout=30) as c:
            reply = c.request_reply("load session s.ses")
            assert not reply["ok"], reply
            assert "inside the state directory" in reply["error"]["message"], reply
            assert c.request("list figures")["figures"] == []
    finally:
        d.cleanup()
