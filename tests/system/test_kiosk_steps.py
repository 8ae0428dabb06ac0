"""The kiosk's steps: a drag from the first button down to the last one up is one
undoable, journaled step; a daemon killed mid-drag comes back to the last completed step;
while a step is under way another client's change to the figure it moves is refused `busy`;
`subscribe kiosk` tells the mode and the step as they change; a button held too long ends
its step. The expected states are the daemon's own reports before the step, compared bit
for bit: a step taken back must give exactly what was there."""
import time

import pytest

from daemon import daemon, daemon_factory  # noqa: F401 (fixtures)
from test_manip import setup


def root(c):
    r = c.request("show figure human")["root"]
    s = c.request(f"get site human {r}")
    return s["position"] + s["rotation"]


def press_move_release(c, path, release=True, button="left"):
    c.request(f"input pointer front {path[0][0]} {path[0][1]}")
    c.request(f"input button {button} down")
    for x, y in path[1:]:
        c.request(f"input pointer front {x} {y}")
    if release:
        c.request(f"input button {button} up")


def undo_depth(c):
    return c.request("status")["undo"]


def test_a_drag_is_one_undo_and_a_click_is_none(daemon):
    with daemon.client() as c:
        setup(c)
        c.request("manipulate figure human")
        start = root(c)
        depth = undo_depth(c)
        press_move_release(c, [(160, 120), (180, 120), (200, 121), (230, 124)])
        moved = root(c)
        assert moved != start
        assert undo_depth(c) == depth + 1
        press_move_release(c, [(100, 100)])  # a click that moves nothing is no step
        assert undo_depth(c) == depth + 1
        assert c.request("undo")["undone"] is True
        assert root(c) == start  # bit for bit
        assert c.request("redo")["redone"] is True
        assert root(c) == moved


def test_a_typed_value_held_in_a_drag_is_part_of_its_step_and_alone_its_own(daemon):
    with daemon.client() as c:
        setup(c)
        c.request("manipulate figure human")
        start = root(c)
        depth = undo_depth(c)
        c.request("input button left down")
        c.request("set manip 10cm")
        c.request("input button left up")
        assert undo_depth(c) == depth + 1
        assert root(c)[0] == pytest.approx(start[0] + 0.1, abs=1e-12)
        c.request("undo")
        assert root(c) == start


def test_killed_mid_drag_it_comes_back_to_the_last_completed_step(daemon):
    with daemon.client() as c:
        setup(c)
        c.request("manipulate figure human")
        start = root(c)
        press_move_release(c, [(160, 120), (200, 120)])
        done = root(c)
        assert done != start
        press_move_release(c, [(200, 120), (250, 110), (280, 100)], release=False)
        assert root(c) != done  # the second step is under way (and its postures journaled)
    daemon.kill9()
    daemon.start()
    with daemon.client() as c:
        assert root(c) == done
        assert c.request("get manip")["mode"] == "none"
        c.request("undo")  # the completed step is in the history
        assert root(c) == start


def test_a_drag_s_constraint_is_the_mode_s_own(daemon):
    """killed mid-drag of a hand: no drag constraint after the restart, and the posture of
    the last completed step"""
    with daemon.client() as c:
        setup(c)
        before = c.request("get posture human")["posture"]
        c.request("drag human hand_r.palm start=shoulder_r")
        press_move_release(c, [(160, 120), (120, 120)], release=False)
        c.request("settle frames=20")
        assert c.request("get posture human")["posture"] != before
        assert [x["name"] for x in c.request("list constraints")["constraints"]] == ["drag"]
    daemon.kill9()
    daemon.start()
    with daemon.client() as c:
        assert c.request("list constraints")["constraints"] == []
        assert c.request("get posture human")["posture"] == before


def test_another_client_s_change_to_the_dragged_figure_is_busy(daemon):
    with daemon.client() as kiosk, daemon.client() as other:
        setup(kiosk)
        kiosk.request("load human as eve")
        kiosk.request("manipulate figure human")
        press_move_release(kiosk, [(160, 120), (170, 120)], release=False)
        for line in ("set joint human elbow_r 10deg", "set location human 0 0 0",
                     "add constraint human effector=hand_r.palm goal=0,1,0", "undo"):
            err = other.request_reply(line)["error"]
            assert err["code"] == "busy", line
            assert "figure mode" in err["message"] and "human" in err["message"], err
        other.request("get joint human elbow_r")  # reads go on
        other.request("set joint eve elbow_r 10deg")  # and other figures
        kiosk.request("input button left up")
        other.request("set joint human elbow_r 10deg")  # the step is over


def test_subscribe_kiosk_tells_the_mode_and_the_step(daemon):
    with daemon.client() as kiosk, daemon.client() as watcher:
        setup(kiosk)
        assert watcher.subscribe("kiosk") == {}
        kiosk.request("manipulate figure human view=front")
        kiosk.request("input button left down")
        kiosk.request("input pointer front 170 120")
        kiosk.request("input button left up")
        kiosk.request("input key KEY_ESC down")
        kiosk.request("get manip")
        seen = []
        for ev in watcher.events(timeout=0.5):
            if ev["event"] == "kiosk":
                seen.append((ev["mode"], ev["target"], ev["view"], ev["step"]))
        assert seen == [("figure", "human", "front", False), ("figure", "human", "front", True),
                        ("figure", "human", "front", False), ("none", None, None, False)]


def test_a_button_held_too_long_ends_its_drag(daemon):
    with daemon.client() as c:
        setup(c)
        assert c.request("set input held=1")["held"] == 1
        assert not c.request_reply("set input held=0.1")["ok"]
        c.request("manipulate figure human")
        start = root(c)
        depth = undo_depth(c)
        press_move_release(c, [(160, 120), (200, 120)], release=False)
        moved = root(c)
        t0 = time.monotonic()
        while time.monotonic() - t0 < 3 and c.request("get manip")["state"] != "idle":
            time.sleep(0.1)
        assert c.request("get manip")["state"] == "idle"
        assert 0.9 < time.monotonic() - t0 < 2.5
        assert root(c) == moved and undo_depth(c) == depth + 1
        c.request("input pointer front 250 120")  # the pointer moves nothing now
        assert root(c) == moved
        c.request("undo")
        assert root(c) == start


def test_a_mode_goes_on_with_the_figure_an_undo_restored(daemon):
    """undo replaces the environment (new models and states): a joint mode on a figure
    still there works on the restored one, as if it had been manipulated from the start"""
    def crank(c, fig):
        c.request(f"manipulate joint {fig} elbow_r view=side")
        c.request("input pointer side 150 150")
        c.request("input button left down")
        for x, y in ((140, 170), (120, 185), (100, 190)):
            c.request(f"input pointer side {x} {y}")
        c.request("input button left up")
        value = c.request(f"get joint {fig} elbow_r")["values"][0]
        c.request("input key KEY_ESC down")
        c.request("input key KEY_ESC up")
        return value

    with daemon.client() as c:
        c.request("add view side width=320 height=240 eye=3,1.2,0 target=0,1.2,0")
        c.request("load human as a")
        c.request("set joint a elbow_r 30deg")
        c.request("manipulate joint a elbow_r view=side")
        c.request("undo")  # elbow back to 0, the figure made anew
        assert c.request("get manip")["mode"] == "joint"
        c.request("input pointer side 150 150")
        c.request("input button left down")
        for x, y in ((140, 170), (120, 185), (100, 190)):
            c.request(f"input pointer side {x} {y}")
        c.request("input button left up")
        after_undo = c.request("get joint a elbow_r")["values"][0]
        c.request("input key KEY_ESC down")
        c.request("input key KEY_ESC up")
        c.request("unload figure a")
        c.request("load human as b")
        assert after_undo == pytest.approx(crank(c, "b"), abs=1e-12)
        assert after_undo != 0
