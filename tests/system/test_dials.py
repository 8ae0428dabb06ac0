"""The dial panel at work: the bindings file (tools/panel.bindings, for the
example panel map) and `bind` at run time turn a picked joint's DOF, the view, a behaving
human's elevation and torso, and G; panel buttons run commands; a turn of the dials is one
undo. Dials are relative: only the change of a dial's value moves (Jack's dial box). The
expected values are the bindings' gains times the changes fed, worked out here."""
import math
import time

import pytest

from daemon import ROOT, daemon_factory, write_picture  # noqa: F401 (fixture)

PANEL = ["--panel", str(ROOT / "tests" / "input" / "can" / "panel.map"),
         "--bindings", str(ROOT / "tools" / "panel.bindings")]


def view(c):
    return c.request("list views")["views"][0]


def test_the_dial_box_turns_the_picked_joint_and_a_turn_is_one_undo(daemon_factory):
    with daemon_factory(extra=PANEL).client() as c:
        c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
        c.request("load human as human")
        text = c.request("list bindings")["text"]
        assert "dial Dials.Dial2 dof 0 gain=1deg" in " ".join(text.split())
        # no joint picked yet: a turn moves nothing, and says why
        c.request("input valuator Dials.Dial2 10")
        c.request("input valuator Dials.Dial2 20")
        assert c.request("get joint human elbow_r")["values"] == [0]
        c.request("manipulate joint human elbow_r")
        c.request("input key KEY_ESC down")  # picked, and it stays picked after the mode
        c.request("input key KEY_ESC up")
        depth = c.request("status")["undo"]
        c.request("input valuator Dials.Dial2 25")  # +5 -> 5 degrees (gain 1deg)
        c.request("input valuator Dials.Dial2 55")  # +30 -> 35 degrees in all
        assert c.request("get joint human elbow_r")["values"][0] == pytest.approx(
            math.radians(35), abs=1e-12)
        write_picture(c, "front", "dials_elbow.png")
        c.request("input valuator Dials.Dial2 1000")  # far past the limit: clamped
        upper = c.request("get joint human elbow_r")["upper"][0]
        assert c.request("get joint human elbow_r")["values"][0] == pytest.approx(upper, abs=1e-12)
        time.sleep(0.8)  # still for half a second: the turn is one step
        c.request("get joint human elbow_r")
        assert c.request("status")["undo"] == depth + 1
        c.request("undo")
        assert c.request("get joint human elbow_r")["values"] == [0]


def test_a_client_s_undo_waits_while_the_dials_turn(daemon_factory):
    """The turn is a step outside a mode: an undo in the middle of it took back the step
    before it (the view) and the turn was lost; a change to the figure it turns was taken
    back with the turn. Both are refused busy now, and other figures go on."""
    with daemon_factory(extra=PANEL).client() as c:
        c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
        c.request("load human as human")
        c.request("load human as eve")
        c.request("manipulate joint human elbow_r")
        c.request("input key KEY_ESC down")
        c.request("input key KEY_ESC up")
        depth = c.request("status")["undo"]
        c.request("input valuator Dials.Dial2 10")
        c.request("input valuator Dials.Dial2 15")  # +5 degrees, the step under way
        err = c.request_reply("undo")["error"]
        assert err["code"] == "busy" and "dials" in err["message"], err
        assert c.request_reply("redo")["error"]["code"] == "busy"
        err = c.request_reply("set joint human knee_l 30deg")["error"]
        assert err["code"] == "busy" and "human" in err["message"], err
        c.request("set joint eve knee_l 30deg")  # another figure goes on
        assert [v["name"] for v in c.request("list views")["views"]] == ["front"]
        time.sleep(0.8)  # still: the turn is one step
        c.request("get joint human elbow_r")
        assert c.request("status")["undo"] == depth + 2  # eve's change, then the turn
        c.request("undo")
        assert c.request("get joint human elbow_r")["values"] == [0]
        assert [v["name"] for v in c.request("list views")["views"]] == ["front"]


def test_the_view_turns_and_zooms_on_its_dials(daemon_factory):
    with daemon_factory(extra=PANEL).client() as c:
        c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
        c.request("input valuator Tilt.Roll 0")
        c.request("input valuator Tilt.Roll 30")  # sweep_h 30 degrees about the vertical
        e = view(c)["eye"]
        assert e == pytest.approx([3 * math.sin(math.radians(30)), 1, 3 * math.cos(math.radians(30))],
                                  abs=1e-9)
        assert view(c)["target"] == pytest.approx([0, 1, 0], abs=1e-9)
        c.request("input valuator Knobs.KnobC 0")
        c.request("input valuator Knobs.KnobC 0.5")  # zoom 0.5 m back
        assert math.dist(view(c)["eye"], [0, 1, 0]) == pytest.approx(3.5, abs=1e-9)
        c.request("load human as human")
        write_picture(c, "front", "dials_view.png")


def test_elevation_and_torso_dials_drive_the_behaviours(daemon_factory):
    with daemon_factory(extra=PANEL).client() as c:
        c.request("load human as human")
        c.request("behave human on")
        c.request("settle frames=30")
        com0 = c.request("get behavior human")["balance"]["point"]
        spine0 = c.request("get posture human")["posture"]
        c.request("input valuator Dials.Dial3 0")
        c.request("input valuator Dials.Dial3 100")  # torso_forward: 100 * 0.1 deg = 10 deg
        posture = c.request("get posture human")["posture"]
        flex = sum(posture[f"spine_{k}"][0] for k in range(18))
        flex0 = sum(spine0[f"spine_{k}"][0] for k in range(18))
        assert flex - flex0 == pytest.approx(math.radians(10), abs=1e-9)
        c.request("add view front width=320 height=240 eye=2.5,1.2,2 target=0,1,0")
        write_picture(c, "front", "dials_torso.png")
        assert com0 is not None


def test_a_panel_button_runs_its_command_and_bind_changes_them(daemon_factory):
    with daemon_factory(extra=PANEL).client() as c:
        c.request("load human as human")
        c.request("set joint human elbow_r 20deg")
        c.request("input button BTN_TRIGGER_HAPPY1 down")  # "undo"
        c.request("input button BTN_TRIGGER_HAPPY1 up")
        assert c.request("get joint human elbow_r")["values"] == [0]
        c.request('bind button BTN_TRIGGER_HAPPY1 "set joint human elbow_r 15deg"')
        c.request("input button BTN_TRIGGER_HAPPY1 down")
        assert c.request("get joint human elbow_r")["values"][0] == pytest.approx(math.radians(15))
        c.request("bind dial Dials.Dial1 joint human knee_l 0 gain=2deg")
        c.request("input valuator Dials.Dial1 1")
        c.request("input valuator Dials.Dial1 6")  # +5 at 2 degrees
        assert c.request("get joint human knee_l")["values"][0] == pytest.approx(math.radians(10))
        assert c.request("unbind dial Dials.Dial1") == {}
        c.request("input valuator Dials.Dial1 20")
        assert c.request("get joint human knee_l")["values"][0] == pytest.approx(math.radians(10))
        for bad in ("bind dial Nope.Dial dof 0", "bind dial Dials.Dial1 camera spin",
                    "unbind dial Dials.Dial1", "bind button BTN_NOPE undo"):
            assert c.request_reply(bad)["error"]["code"] == "bad-argument", bad
