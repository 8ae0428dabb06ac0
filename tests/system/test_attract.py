"""The attract mode: with --attract DIR, a recording plays in a loop once nobody has
touched the kiosk for --attract-after seconds; questions over the socket (get, status) leave
it playing; the first real input (an `input` line, a command, a device) ends it, and the
state is exactly what it was before, bit for bit (the `status` posture hash, the figures, the
undo history), and nothing of the demo was journaled (a kill -9 after it comes back to the
state before it)."""
import math
import time

from daemon import ROOT, daemon_factory  # noqa: F401 (fixture)

DEMO = ROOT / "tests" / "replays" / "fig_5_9_move_hand" / "recording"


def wait_for(c, attract, timeout=15.0):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if c.request("get kiosk")["attract"] == attract:
            return
        time.sleep(0.05)
    raise AssertionError("the attract mode is not %s" % ("on" if attract else "off"))


def state(c):
    return (c.request("status")["posture"], c.request("status")["undo"],
            [f["name"] for f in c.request("list figures")["figures"]])


def test_a_demo_plays_when_idle_and_real_input_brings_the_state_back(daemon_factory):
    d = daemon_factory(extra=("--attract", str(DEMO), "--attract-after", "1"))
    with d.client() as c:
        c.request("load human as jack")
        c.request("set joint jack knee_l 40deg")
        before = state(c)
        assert c.request("get kiosk")["attract"] is False
        wait_for(c, True)
        # questions leave it playing; the demo's own figure is on stage
        time.sleep(0.5)
        assert c.request("get kiosk")["attract"] is True
        assert [f["name"] for f in c.request("list figures")["figures"]] == ["human"]
        assert c.request("status")["posture"] != before[0]
        # the first real input ends it: the state is as it was
        c.request("input motion 1 0")
        wait_for(c, False)
        assert state(c) == before
        # a command too, once it plays again; and the command runs on the real state
        wait_for(c, True)
        c.request("set joint jack knee_l 20deg")
        assert c.request("get kiosk")["attract"] is False
        assert c.request("get joint jack knee_l")["values"][0] == math.radians(20)
        after = state(c)
        wait_for(c, True)
    # killed mid-demo: the journal holds the real state, not the demo's
    d.kill9()
    d.start()
    with d.client() as c:
        c.request("input motion 0 0")  # a demo that may have begun again gives way
        wait_for(c, False)
        assert state(c)[0] == after[0] and state(c)[2] == ["jack"]


def test_an_attract_recording_that_cannot_be_read_stops_the_start(tmp_path):
    import subprocess
    from daemon import POSTURED
    bad = tmp_path / "demo"
    bad.mkdir()
    (bad / "manifest").write_text("posture-recording 7\n")
    p = subprocess.run([str(POSTURED), "--socket", str(tmp_path / "s"), "--state-dir",
                        str(tmp_path / "st"), "--input", "none", "--attract", str(bad)],
                       capture_output=True, text=True, timeout=60)
    assert p.returncode == 1
    assert f"attract: {bad}/manifest:1: not a posture recording" in p.stderr
