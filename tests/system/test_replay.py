"""Recorded-input replay: a live session recorded with --record (or `record start`)
replays with --replay to the same postures, bit for bit, under the recording's clock.

The reference is the live daemon itself: its `status` posture hash at the end of the session
and the hash the frame log holds after every frame. A replay that cut a solve anywhere else
than the live one did, or ran a line in another order, gives another hash (the tests below see
that happen by changing one solve's work in a recording). The sessions run at 1000 fps with a
60 us solve budget, so the solver's time limit cuts solves live on any machine (the test
checks it did), which is what a replay must reproduce without a clock.
"""
import os
import pathlib
import re
import shutil
import signal
import subprocess
import time

import pytest

from daemon import POSTURED, daemon_factory  # noqa: F401 (fixture)
from test_kiosk_steps import press_move_release
from test_manip import setup

REPLAY_LINE = re.compile(r"^replay: frames=(\d+) posture=([0-9a-f]{16}) divergences=(\d+)$")


def replay(rec, *extra, timeout=120):
    """Runs postured --replay REC: (exit status, the parsed last stdout line or None, stderr)."""
    p = subprocess.run([str(POSTURED), "--replay", str(rec), *extra], capture_output=True,
                       text=True, timeout=timeout)
    lines = p.stdout.strip().splitlines()
    m = REPLAY_LINE.match(lines[-1]) if lines else None
    return p.returncode, (m and (int(m[1]), m[2], int(m[3]))), p.stderr


def request_error(c, line):
    """The error object of a request that must fail."""
    reply = c.request_reply(line)
    assert reply["ok"] is False, reply
    return reply["error"]


def drag_session(c):
    """A kiosk session: a hand dragged with behaviours on, typed keys, a settle."""
    setup(c)
    c.request("behave human on")
    c.request("manipulate hand human right view=front")
    press_move_release(c, [(160, 120), (170, 118), (185, 114), (200, 108), (215, 100)])
    time.sleep(0.2)  # frames run between the lines: the solver follows the hand
    press_move_release(c, [(215, 100), (200, 120), (190, 130)])
    time.sleep(0.2)
    for key in ("KEY_ESC",):
        c.request(f"input key {key} down")
        c.request(f"input key {key} up")
    c.request("save posture human take.pst")  # a file written live, never by a replay
    c.request("settle")


@pytest.fixture
def recorded(daemon_factory, tmp_path):
    """A recording of drag_session made from the daemon's start; (folder, live posture hash)."""
    rec = tmp_path / "rec"
    # 60 us a frame: the time limit cuts solves on any machine (a replay must cut them alike)
    d = daemon_factory(fps=1000, extra=("--record", str(rec), "--solve-budget", "60"))
    with d.client() as c:
        drag_session(c)
        time.sleep(0.3)
        live = c.request("status")["posture"]
    d.stop()
    return rec, live


def frame_log(rec):
    return (rec / "frames").read_text().splitlines()


def test_a_recorded_drag_replays_to_the_live_postures_bit_for_bit(recorded):
    rec, live = recorded
    log = frame_log(rec)
    cuts = [line for line in log if line.startswith("ik ") and " cut=1 " in line]
    assert cuts, "the time limit never cut a solve: the recording does not test the cut"
    manifest = (rec / "manifest").read_text()
    frames = int(re.search(r"state complete frames=(\d+)", manifest)[1])
    status, out, err = replay(rec)
    assert status == 0, err
    assert out == (frames, live, 0), err


def test_twenty_replays_give_the_same_hashes(recorded):
    rec, live = recorded
    outs = {replay(rec)[1] for _ in range(20)}
    assert len(outs) == 1 and outs.pop()[1] == live


def test_solves_left_uncut_diverge_and_the_replay_says_where(recorded):
    rec, _ = recorded
    log = frame_log(rec)
    frame, cut_frames = 0, set()
    for i, line in enumerate(log):
        frame += line.startswith("frame ")
        if line.startswith("ik ") and " cut=1 " in line:
            # what a replay that ignored the recorded cuts would do: solve on to the end
            log[i] = re.sub(r"cut=1 iterations=\d+ round=\d+ group=-?\d+ start=\d+ "
                            r"start_iterations=\d+$",
                            "cut=0 iterations=0 round=0 group=-1 start=0 start_iterations=0", line)
            cut_frames.add(frame)
    assert cut_frames
    (rec / "frames").write_text("\n".join(log) + "\n")
    status, out, err = replay(rec)
    assert status == 1
    assert out is not None and out[2] >= 1
    said = re.search(r"diverged first at frame (\d+): figure 0 \(human\) differs: (.*)", err)
    assert said, err
    assert int(said[1]) in cut_frames
    assert said[2].split()  # the joints that differ, by name
    assert all(re.fullmatch(r"[a-z_0-9]+|\(root\)|\(behaviours\)", w) for w in said[2].split())


@pytest.mark.parametrize("damage, where", [
    (lambda log: log[:3] + ["frame x t=1"] + log[3:], r"frames:4: not a record of the frame log"),
    (lambda log: log[:len(log) // 2], r"frames:\d+: truncated"),
    (lambda log: [ln.replace("posture ", "posture 99999 ", 1) if ln.startswith("posture")
                  else ln for ln in log], r"frames:\d+: not a record"),
])
def test_a_damaged_frame_log_is_refused_with_file_and_line(recorded, damage, where):
    rec, _ = recorded
    (rec / "frames").write_text("\n".join(damage(frame_log(rec))) + "\n")
    status, out, err = replay(rec)
    assert status == 1 and out is None
    assert re.search(re.escape(str(rec)) + "/" + where, err), err


def test_damaged_lines_and_manifest_are_refused_with_file_and_line(recorded):
    rec, _ = recorded
    lines = (rec / "lines").read_text().splitlines()
    (rec / "lines").write_text("\n".join(lines[:2] + ["not a line"] + lines[2:]) + "\n")
    status, out, err = replay(rec)
    assert status == 1 and f"{rec}/lines:3:" in err
    (rec / "manifest").write_text("posture-recording 9\n")
    status, out, err = replay(rec)
    assert status == 1 and f"{rec}/manifest:1:" in err
    status, out, err = replay(rec / "missing")
    assert status != 0 and f"{rec}/missing/config" in err


def test_a_replay_writes_nothing_but_its_frames(recorded, tmp_path):
    rec, live = recorded
    before = {p: p.stat().st_mtime_ns for p in rec.rglob("*")}
    frames = tmp_path / "frames"
    status, out, err = replay(rec, "--frames", str(frames))
    assert status == 0 and out[1] == live, err
    assert {p: p.stat().st_mtime_ns for p in rec.rglob("*")} == before
    assert not (rec / "take.pst").exists()
    assert (frames / "front.png").exists()


def test_a_killed_recording_replays_up_to_its_last_complete_frame(daemon_factory, tmp_path):
    rec = tmp_path / "rec"
    d = daemon_factory(fps=1000, extra=("--record", str(rec), "--solve-budget", "60"))
    with d.client() as c:
        drag_session(c)
        time.sleep(0.3)
    d.kill9()
    assert "state recording" in (rec / "manifest").read_text()
    # a torn last record, as a kill mid-write leaves it
    with open(rec / "frames", "a") as f:
        f.write("ik 0 ik_work cut=1 itera")
    status, out, err = replay(rec)
    assert status == 0, err
    assert "was not stopped" in err
    complete = [ln for ln in frame_log(rec) if ln.startswith("posture ")]
    assert out[0] == int(complete[-1].split()[1])


def test_record_start_and_stop_over_the_socket(daemon_factory, tmp_path):
    d = daemon_factory(fps=1000)
    with d.client() as c:
        setup(c)
        c.request("behave human on")
        assert c.request("get record")["recording"] is False
        assert c.request("record start take1") == {"path": "take1"}
        err = request_error(c, "record start take2")
        assert err["code"] == "busy" and "already recording" in err["message"]
        c.request("manipulate hand human right view=front")
        press_move_release(c, [(160, 120), (180, 115), (200, 105)])
        time.sleep(0.2)
        got = c.request("get record")
        assert got["recording"] is True and got["frames"] > 0 and got["waits"] == 0
        c.request("input key KEY_ESC down")
        c.request("input key KEY_ESC up")
        time.sleep(0.2)
        live = c.request("status")["posture"]
        stopped = c.request("record stop")
        assert stopped["frames"] > 0
        assert request_error(c, "record stop")["code"] == "not-found"
        assert request_error(c, "record start /tmp/x")["code"] == "denied"
        assert request_error(c, "record start ../x")["code"] == "denied"
        # a mode under way holds state outside the session: refused until it ends
        c.request("manipulate hand human right view=front")
        err = request_error(c, "record start take3")
        assert err["code"] == "busy" and "mode" in err["message"]
        assert request_error(c, "record start take1")["code"] == "busy"  # not empty
    status, out, err = replay(d.state_dir / "take1")
    assert status == 0, err
    assert out[1] == live and out[2] == 0


def test_loads_replay_what_they_read_live(daemon_factory, tmp_path):
    """load posture and load session read state files: a recording keeps what each read
    (read.N beside the log), so the replay loads the same text though the replay's state
    directory is the recording and the files were saved over afterwards. A load whose file
    was missing fails alike in the replay."""
    rec = tmp_path / "rec"
    d = daemon_factory(fps=1000, extra=("--record", str(rec), "--solve-budget", "60"))
    with d.client() as c:
        c.request("load human as jack")
        c.request("set joint jack knee_l 40deg")
        c.request("save posture jack bent.pst")
        c.request("save session s.ses")
        c.request("set joint jack knee_l 0")
        c.request("set joint jack elbow_r 70deg")
        c.request("load posture jack bent.pst")
        assert request_error(c, "load posture jack missing.pst")["code"] == "not-found"
        c.request("load session s.ses")
        c.request("set joint jack elbow_l 20deg")
        c.request("save posture jack bent.pst")
        c.request("save session s.ses")
        time.sleep(0.2)
        live = c.request("status")["posture"]
    d.stop()
    assert sorted(p.name for p in rec.glob("read.*")) == ["read.1", "read.2"]
    assert (rec / "read.1").read_text() != (d.state_dir / "bent.pst").read_text()
    log = frame_log(rec)
    assert [line for line in log if line.startswith(("file ", "nofile "))] == [
        "file 1", "nofile 2", "file 2"]
    status, out, err = replay(rec)
    assert status == 0, err
    assert out[1] == live and out[2] == 0, err
