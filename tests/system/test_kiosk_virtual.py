"""The kiosk over minutes of virtual time: `postured --drive FILE` runs a
script of timed lines frame by frame under a virtual clock, as fast as the machine goes.

- A mouse button held without release for 60 s ends its drag (the step closes between 59 s
  and 61 s of virtual time), as the kiosk's rule says.
- Random streams of keys, buttons, motion, pointer positions and dial values, with lines typed
  at the edit line now and then, for 10 minutes of virtual time: the daemon never crashes,
  ESC brings the kiosk back to idle, and the environment it leaves is the one its journal (a
  sequence of commands and postures) gives back to a daemon started on its state directory.
- The same script driven twice gives the same posture hash.
"""
import json
import random
import re
import subprocess

import pytest

from daemon import POSTURED, ROOT, Daemon
from kiosk_keys import key_lines
from test_kiosk_random import BUTTONS, DIALS, KEYS, STARTS, random_line

PANEL = ["--panel", str(ROOT / "tests" / "input" / "can" / "panel.map"),
         "--bindings", str(ROOT / "tools" / "panel.bindings")]
DRIVE_LINE = re.compile(r"^drive: frames=(\d+) virtual_s=([\d.]+) posture=([0-9a-f]{16})$")


def drive(tmp_path, lines, after=(), extra=()):
    """Drives the script of (t_us, line); (frames, virtual seconds, posture, replies, state dir)."""
    script = tmp_path / "script"
    script.write_text("".join("%d 0 %s\n" % (t, line) for t, line in lines))
    state = tmp_path / "state"
    state.mkdir(exist_ok=True)
    argv = [str(POSTURED), "--drive", str(script), "--state-dir", str(state),
            "--socket", str(tmp_path / "sock"), *PANEL, *extra]
    if after:
        (tmp_path / "after").write_text("\n".join(after) + "\n")
        argv += ["--after", str(tmp_path / "after")]
    p = subprocess.run(argv, capture_output=True, text=True, timeout=900)
    assert p.returncode == 0, p.stderr[-2000:]
    out = p.stdout.splitlines()
    m = DRIVE_LINE.match(out[-1])
    assert m, out[-3:]
    replies = [json.loads(ln[7:]) for ln in out if ln.startswith("reply: ")]
    return int(m[1]), float(m[2]), m[3], replies, state


SETUP = ["add view front width=320 height=240 eye=0,1,3 target=0,1,0", "load human as bob"]


def test_a_button_held_for_a_minute_ends_its_drag(tmp_path):
    s = 1000000
    lines = [(0, SETUP[0]), (0, SETUP[1]), (0, "behave bob on"),
             (s // 10, "manipulate hand bob right view=front"),
             (s // 5, "input pointer front 160 120"), (s // 4, "input button left down"),
             (s // 2, "input pointer front 150 110"), (s, "get kiosk"), (59 * s, "get kiosk"),
             (61 * s, "get kiosk")]
    frames, seconds, _, replies, _ = drive(tmp_path, lines)
    kiosk = [r["result"] for r in replies if "result" in r and "step" in r["result"]]
    assert [k["step"] for k in kiosk] == [True, True, False]
    assert kiosk[-1]["mode"] == "hand"  # the drag ended, the mode goes on
    assert seconds >= 62 and frames == round(seconds * 60) + 1


def random_script(seed, minutes):
    rng = random.Random(seed)
    t, end, lines = 500000, int(minutes * 60e6), [(0, ln) for ln in SETUP]
    while t < end:
        line = random_line(rng)
        if line is None:  # a line typed whole, after the kiosk is brought back to idle
            for ln in back_to_idle_lines():
                lines.append((t, ln))
            for ln in key_lines(rng.choice(STARTS)) + ["input key KEY_ENTER down",
                                                       "input key KEY_ENTER up"]:
                t += 30000
                lines.append((t, ln))
        else:
            lines.append((t, line))
        t += int(rng.expovariate(1 / 40000)) + 1
    return lines, t


def back_to_idle_lines():
    out = ["input button %s up" % b for b in BUTTONS]
    out += ["input key %s up" % k for k in ("KEY_LEFTSHIFT", "KEY_LEFTCTRL", "KEY_RIGHTCTRL",
                                            "KEY_LEFTALT")]
    for _ in range(4):
        out += ["input key KEY_ESC down", "input key KEY_ESC up"]
    return out


@pytest.mark.parametrize("seed", [11, 12])
def test_ten_minutes_of_random_input_in_virtual_time(tmp_path, seed):
    lines, t = random_script(seed, 10)
    lines += [(t, ln) for ln in back_to_idle_lines()]
    # behaviours would go on balancing in a live daemon's frames: stilled, one moment compared
    lines += [(t + 100000, "behave bob off"), (t + 100000, "settle frames=5")]
    frames, seconds, posture, replies, state = drive(tmp_path, lines, after=["get kiosk"])
    assert seconds >= 600 and frames > 36000
    kiosk = replies[-1]["result"]
    assert kiosk["mode"] == "none" and kiosk["step"] is False and kiosk["prompt"] is None
    assert kiosk["line"] == "" and kiosk["value"] is False and kiosk["menu"] is None
    # the journal gives the same environment back to a daemon started on it
    d = Daemon(extra=("--state-dir", str(state)) + tuple(PANEL))  # the last --state-dir wins
    d.start()
    try:
        with d.client() as c:
            assert c.request("status")["posture"] == posture
    finally:
        d.stop()
        d.cleanup()


def test_the_same_script_drives_to_the_same_posture(tmp_path):
    lines, t = random_script(7, 0.5)
    a = drive(tmp_path / "a", lines) if (tmp_path / "a").mkdir() is None else None
    b = drive(tmp_path / "b", lines) if (tmp_path / "b").mkdir() is None else None
    assert a[:3] == b[:3]
