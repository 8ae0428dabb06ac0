#!/usr/bin/env python3
"""Makes the replay suite of tests/replays: each session below is performed on a live daemon
through `input` lines (the kiosk's mouse, keys and dials, as a front end sends them) while the
daemon records it (--record), then its expectations are measured once with
`posture-replay run --update` and kept. Run it again only after a reviewed change that is meant
to change the postures; the test then fails until the new recordings are committed.

    python3 tests/replays/make_replays.py [NAME...]

The sessions run at 1000 fps, so the solver's time limit cuts solves live: a replay passes only
by cutting each one where the live one was cut.
"""
import pathlib
import shutil
import subprocess
import sys
import time

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(ROOT / "tests" / "system"))
sys.path.insert(0, str(ROOT / "tools"))
from daemon import Daemon  # noqa: E402
from posture.replay import run_test  # noqa: E402

PAUSE = 0.04  # between motions: frames run, the solver follows


def human(c, behave=True):
    c.request("load human as human")
    c.request("add view front width=320 height=240 eye=0.4,1.1,3.2 target=0,0.9,0")
    if behave:
        c.request("behave human on")


def drag(c, path, button="left", view="front", ctrl=False):
    """A drag with one button; with Ctrl held, the button's axis is a rotation wheel."""
    if ctrl:
        c.request("input key KEY_LEFTCTRL down")
    c.request(f"input pointer {view} {path[0][0]} {path[0][1]}")
    c.request(f"input button {button} down")
    for x, y in path[1:]:
        c.request(f"input pointer {view} {x} {y}")
        time.sleep(PAUSE)
    c.request(f"input button {button} up")
    if ctrl:
        c.request("input key KEY_LEFTCTRL up")
    time.sleep(0.2)


def key(c, name):
    c.request(f"input key {name} down")
    c.request(f"input key {name} up")


def line(x0, y0, x1, y1, n=12):
    return [(round(x0 + (x1 - x0) * k / n), round(y0 + (y1 - y0) * k / n)) for k in range(n + 1)]


# ---- the sessions: Chapter 5's figures, then the kiosk's other work ----------------------

def fig_5_3_move_foot(c):
    """Figure 5.3: the left foot moved, the balance point following the feet."""
    human(c)
    c.request("manipulate foot human left view=front")
    drag(c, line(170, 220, 200, 220), "left")      # x: sideways
    drag(c, line(200, 220, 200, 205), "right")     # z: forward
    key(c, "KEY_ESC")


def fig_5_4_shift_com(c):
    """Figure 5.4: the centre of mass shifted over the feet."""
    human(c)
    c.request("manipulate com human view=front")
    drag(c, line(160, 140, 185, 140), "left")
    key(c, "KEY_ESC")


def fig_5_5_lower_com(c):
    """Figure 5.5: the centre of mass lowered: the knees bend."""
    human(c)
    c.request("manipulate com human view=front")
    drag(c, line(160, 140, 160, 175), "middle")
    key(c, "KEY_ESC")


def fig_5_6_step(c):
    """Figure 5.6: the centre of mass pushed past the feet: a step is taken."""
    human(c)
    c.request("manipulate com human view=front")
    drag(c, line(160, 140, 240, 140, 20), "left")
    time.sleep(1.5)  # the step's motion
    key(c, "KEY_ESC")


def fig_5_7_bend_torso(c):
    """Figure 5.7: the torso bent forward while the figure keeps its balance."""
    human(c)
    c.request("manipulate torso human view=front")
    drag(c, line(200, 100, 200, 140), "right", ctrl=True)  # a turn about z: a lateral bend
    key(c, "KEY_ESC")


def fig_5_8_rotate_pelvis(c):
    """Figure 5.8: the pelvis rotated, the torso kept vertical."""
    human(c)
    # seen from above, where the wheel about the vertical faces the camera
    c.request("add view above width=320 height=240 eye=0.3,3.2,1.4 target=0,0.9,0")
    c.request("manipulate pelvis human view=above")
    drag(c, line(200, 120, 200, 160), "middle", view="above", ctrl=True)  # a turn about y
    key(c, "KEY_ESC")


def fig_5_9_move_hand(c):
    """Figure 5.9: the right hand moved: the arm and torso follow."""
    human(c)
    c.request("manipulate hand human right view=front")
    drag(c, line(120, 130, 90, 90), "left")
    drag(c, line(90, 90, 90, 70), "right")
    key(c, "KEY_ESC")


def fig_5_10_move_head(c):
    """Figure 5.10: the head moved, the neck and spine following."""
    human(c)
    c.request("manipulate head human view=front")
    drag(c, line(160, 60, 175, 75), "left")
    key(c, "KEY_ESC")


def change_view(c):
    """Change view (Appendix C) entered with V from a mode: sweep, zoom, then back out."""
    human(c, behave=False)
    c.request("manipulate figure human view=front")
    key(c, "KEY_V")
    drag(c, line(160, 120, 220, 110), "left")
    drag(c, line(160, 120, 160, 150), "right")
    key(c, "KEY_V")
    drag(c, line(160, 200, 160, 170), "middle")  # back in the mode: the figure lifted
    key(c, "KEY_ESC")


def snapping(c):
    """Snapping (Appendix B.4): the figure's G snapped onto the chair's site under the pointer."""
    human(c, behave=False)
    c.request("load figure lib:chair.fig as chair")
    c.request("set location chair 0.8 0 0")
    c.request("manipulate figure human view=front")
    spot = next((x, y) for x in range(200, 320, 4) for y in range(130, 240, 6)
                if (lambda h: h and h["name"] == "chair" and h["site"])(
                    c.request(f"pick front {x} {y}")["hit"]))
    c.request("input pointer front %d %d" % spot)
    c.request("snap site_position")
    time.sleep(0.3)
    key(c, "KEY_ESC")


def joint(c):
    """Joint manipulation (§3.6): the right elbow and shoulder turned within their limits."""
    human(c, behave=False)
    c.request("manipulate joint human elbow_r view=front")
    drag(c, line(120, 130, 120, 100), "left")
    key(c, "KEY_ESC")
    c.request("manipulate joint human shoulder_r view=front")
    drag(c, line(120, 110, 150, 110), "middle")
    key(c, "KEY_ESC")


def dial_panel(c):
    """The dial panel: dials bound to the picked joint's DOFs, a sweep and the elevation."""
    human(c)
    # the bindings of tools/panel.bindings: Dial2 turns DOF 0, Roll sweeps, Dial1 lifts
    c.request("manipulate joint human knee_l view=front")
    key(c, "KEY_ESC")
    for k in range(12):
        c.request(f"input valuator Dials.Dial2 {k * 3}")
        time.sleep(PAUSE)
    time.sleep(0.7)  # the dials' step ends when they are still
    for k in range(10):
        c.request(f"input valuator Tilt.Roll {k * 2}")
        c.request(f"input valuator Dials.Dial1 {-k * 5}")
        time.sleep(PAUSE)
    time.sleep(0.7)


def kiosk_devices(c):
    """A keyboard and a mouse read directly (evdev, replayed under umockdev): commands typed at
    the edit line, the right hand dragged with the mouse, ESC on the keyboard."""
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline and c.request("get kiosk")["mode"] != "hand":
        time.sleep(0.05)
    while time.monotonic() < deadline and c.request("get kiosk")["mode"] != "none":
        time.sleep(0.05)
    time.sleep(0.3)


def kiosk_devices_daemon(extra, tmp):
    """The daemon of kiosk_devices: under umockdev, with evemu files written into tmp."""
    sys.path.insert(0, str(ROOT / "tests" / "system"))
    from test_input import kernel_codes
    from test_kiosk_recorded import typing, umockdev_daemon
    codes = kernel_codes()
    keys, t = [], 2.5
    for text in ("add view front width=320 height=240 eye=0.4,1.1,3.2 target=0,0.9,0",
                 "load human as human", "behave human on", "manipulate hand human right"):
        more, t = typing(text, t, codes)
        keys += more + [(t, 1, codes["KEY_ENTER"], 1), (t + 0.03, 1, codes["KEY_ENTER"], 0)]
        t += 0.3
    drag_at = t + 0.3
    keys += [(drag_at + 1.2, 1, codes["KEY_ESC"], 1), (drag_at + 1.23, 1, codes["KEY_ESC"], 0)]
    mouse = [(drag_at, 1, codes["BTN_LEFT"], 1)]
    mouse += [(drag_at + 0.02 * (i + 1), 2, 0, -4) for i in range(30)]  # REL_X: to the left
    mouse += [(drag_at + 0.7, 1, codes["BTN_LEFT"], 0)]
    return umockdev_daemon(tmp, keys, mouse, fps=1000, extra=extra)


SESSIONS = {
    "fig_5_3_move_foot": (fig_5_3_move_foot, ["site human foot_l.heel", "margin human above 0"]),
    "fig_5_4_shift_com": (fig_5_4_shift_com, ["margin human above 0"]),
    "fig_5_5_lower_com": (fig_5_5_lower_com, ["joint human knee_l", "margin human above 0"]),
    "fig_5_6_step": (fig_5_6_step, ["site human foot_r.heel", "margin human above 0"]),
    "fig_5_7_bend_torso": (fig_5_7_bend_torso, ["site human head.vertex", "margin human above 0"]),
    "fig_5_8_rotate_pelvis": (fig_5_8_rotate_pelvis, ["joint human hip_l"]),
    "fig_5_9_move_hand": (fig_5_9_move_hand, ["site human hand_r.palm", "margin human above 0"]),
    "fig_5_10_move_head": (fig_5_10_move_head, ["site human head.vertex"]),
    "change_view": (change_view, ["picture front front.png tol=1.5"]),
    "snapping": (snapping, ["site human pelvis.center", "picture front front.png tol=1.5"]),
    "joint": (joint, ["joint human elbow_r", "joint human shoulder_r"]),
    "dial_panel": (dial_panel, ["joint human knee_l", "picture front front.png tol=1.5"]),
    "kiosk_devices": (kiosk_devices, ["site human hand_r.palm", "picture front front.png tol=1.5"]),
}


def make(name):
    session, checks = SESSIONS[name]
    out = HERE / name
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir()
    rec = out / "recording"
    extra = ["--record", str(rec), "--library", str(ROOT / "src" / "figure" / "library"),
             "--panel", str(ROOT / "tests" / "input" / "can" / "panel.map"),
             "--bindings", str(ROOT / "tools" / "panel.bindings")]
    if name == "kiosk_devices":
        import tempfile
        d = kiosk_devices_daemon(extra, pathlib.Path(tempfile.mkdtemp(prefix="kd-")))
    else:
        d = Daemon(fps=1000, extra=extra)
    d.start()
    try:
        with d.client() as c:
            session(c)
            time.sleep(0.3)
    finally:
        d.stop()
        d.cleanup()
    placeholders = []
    for check in checks:
        kind, *words = check.split()
        tol = [w for w in words if w.startswith("tol=")]
        words = [w for w in words if not w.startswith("tol=")]
        if kind == "site":
            words += ["0", "0", "0"]
        elif kind == "joint":
            words += ["0"]
        placeholders.append(" ".join(["at end", kind, *words, *tol]))
    (out / "expect").write_text("posture-replay 1\n# %s\nat end posture 0000000000000000\n%s\n" % (
        session.__doc__.strip().splitlines()[0], "\n".join(placeholders)))
    r = run_test(out, update=True)
    print(("made %s: %d frames" % (name, r.frames)) if r.passed else
          ("FAILED %s: %s" % (name, r.failures)))
    return r.passed


if __name__ == "__main__":
    names = sys.argv[1:] or list(SESSIONS)
    ok = all([make(n) for n in names])
    subprocess.run(["git", "-C", str(ROOT), "status", "--short", str(HERE)])
    sys.exit(0 if ok else 1)
