"""The kiosk against random input (robustness): streams of keys, buttons, motion,
pointer positions and dial values, in any order, never crash the daemon, never leave a
mode stuck (ESC brings the kiosk back to idle), and leave an environment that the journal
gives back exactly after a kill -9: what the kiosk did is what a sequence of journaled
changes made. The seeds are fixed, so a failure replays."""
import random

import pytest

from daemon import ROOT, daemon_factory, snapshot  # noqa: F401 (fixture)

PANEL = ["--panel", str(ROOT / "tests" / "input" / "can" / "panel.map"),
         "--bindings", str(ROOT / "tools" / "panel.bindings")]

KEYS = (["KEY_%s" % c for c in "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"] +
        ["KEY_SPACE", "KEY_MINUS", "KEY_DOT", "KEY_EQUAL", "KEY_ENTER", "KEY_BACKSPACE",
         "KEY_TAB", "KEY_LEFT", "KEY_RIGHT", "KEY_UP", "KEY_DOWN", "KEY_HOME", "KEY_END",
         "KEY_DELETE", "KEY_ESC", "KEY_F2", "KEY_V", "KEY_C", "KEY_S", "KEY_LEFTSHIFT",
         "KEY_LEFTCTRL", "KEY_LEFTALT", "KEY_RIGHTCTRL", "KEY_Z", "KEY_Y"])
BUTTONS = ["left", "middle", "right", "BTN_TRIGGER_HAPPY1", "BTN_TRIGGER_HAPPY3"]
DIALS = ["Dials.Dial1", "Dials.Dial2", "Dials.Dial3", "Tilt.Roll", "Knobs.KnobC", "Dials.Wide"]
# lines a person at the kiosk may well have typed, Enter included, for the modes to start
STARTS = ["manipulate figure bob", "manipulate joint bob elbow_r", "drag bob hand_r.palm",
          "manipulate hand bob right", "manipulate site bob hand_l.palm", "behave bob on",
          "manipulate torso bob", "manipulate com bob", "undo", "redo", "manipulate joint"]


def random_line(rng):
    r = rng.random()
    if r < 0.30:
        return f"input key {rng.choice(KEYS)} {rng.choice(['down', 'up'])}"
    if r < 0.45:
        return f"input button {rng.choice(BUTTONS)} {rng.choice(['down', 'up'])}"
    if r < 0.65:
        return f"input motion {rng.randint(-60, 60)} {rng.randint(-60, 60)}"
    if r < 0.75:
        return f"input pointer front {rng.uniform(0, 320):.2f} {rng.uniform(0, 240):.2f}"
    if r < 0.85:
        return f"input valuator {rng.choice(DIALS)} {rng.uniform(-300, 300):.3f}"
    return None  # a line typed whole


def type_line(c, text):
    from kiosk_keys import key_lines
    for line in key_lines(text):
        c.request(line)
    c.request("input key KEY_ENTER down")
    c.request("input key KEY_ENTER up")


def back_to_idle(c):
    """every button and key up, then ESC until the kiosk is idle"""
    for b in BUTTONS:
        c.request(f"input button {b} up")
    for k in ("KEY_LEFTSHIFT", "KEY_LEFTCTRL", "KEY_RIGHTCTRL", "KEY_LEFTALT"):
        c.request(f"input key {k} up")
    for _ in range(4):
        c.request("input key KEY_ESC down")
        c.request("input key KEY_ESC up")
    return c.request("get kiosk")


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_random_streams_leave_a_kiosk_that_esc_brings_back_and_a_journal_that_keeps_it(
        daemon_factory, seed):
    rng = random.Random(seed)
    d = daemon_factory(extra=PANEL)
    with d.client() as c:
        c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
        c.request("load human as bob")
        for n in range(1500):
            line = random_line(rng)
            if line is None:
                back_to_idle(c)
                type_line(c, rng.choice(STARTS))
                continue
            reply = c.request_reply(line)
            # a random Ctrl+Z may have undone the view or the figure: their lines find nothing
            assert reply["ok"] or reply["error"]["code"] == "not-found", (n, line, reply)
        kiosk = back_to_idle(c)
        assert kiosk["mode"] == "none" and kiosk["step"] is False and kiosk["prompt"] is None
        assert kiosk["line"] == "" and kiosk["value"] is False
        # behaviours go on balancing in the live frames: stilled, so one report is one moment
        for f in c.request("list figures")["figures"]:
            c.request_reply(f"behave {f['name']} off")
        c.request("settle frames=5")
        before = snapshot(c)
        assert snapshot(c) == before  # still
    d.kill9()
    d.start()
    with d.client() as c:
        after = snapshot(c)
        assert after == before, differences(before, after)


def differences(a, b, path="", out=None):
    """where two reports differ, as paths (the first few)"""
    out = [] if out is None else out
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            differences(a.get(k), b.get(k), f"{path}.{k}", out)
    elif isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        for i, (x, y) in enumerate(zip(a, b)):
            differences(x, y, f"{path}[{i}]", out)
    elif a != b:
        out.append(f"{path}: {a!r:.80} != {b!r:.80}")
    return out[:8]
