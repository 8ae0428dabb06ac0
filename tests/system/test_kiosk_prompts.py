"""Prompts: a command typed without its arguments asks for them one by one on
the status line; the person picks with the pointer (what is under it is highlighted) or
types; ESC cancels and nothing changes. What a click picks is checked against `pick` on
the same pixel, and the joint above a segment against the figure's own description."""
import math

import pytest

from daemon import daemon, daemon_factory, write_picture  # noqa: F401 (fixtures)
from kiosk_keys import press, type_text


def setup(c):
    c.request("add view front width=480 height=320 eye=0,1,3 target=0,1,0")
    c.request("load human as bob")


def pixel_on(c, segment):
    """a pixel of view front where `pick` meets the segment"""
    for y in range(20, 320, 6):
        for x in range(100, 380, 4):
            hit = c.request(f"pick front {x} {y}")["hit"]
            if hit and hit["segment"] == segment:
                return x, y
    raise AssertionError(f"no pixel on {segment}")


def asking(c):
    p = c.request("get kiosk")["prompt"]
    return p and p["question"]


def test_a_command_without_its_arguments_asks_and_the_pointer_picks(daemon):
    with daemon.client() as c:
        setup(c)
        type_text(c, "manipulate joint", enter=True)
        assert c.request("get manip")["mode"] == "none"  # nothing ran yet
        assert asking(c) == "select a figure"
        x, y = pixel_on(c, "forearm_r")
        c.request(f"input pointer front {x} {y}")
        picked = c.request("get kiosk")["picked"]
        assert picked == {"figure": "bob", "segment": "forearm_r"}
        write_picture(c, "front", "kiosk_prompt_pick.png")
        c.request("input button left down")
        c.request("input button left up")
        assert asking(c) == "select a joint"
        assert c.request("get kiosk")["prompt"]["line"] == "manipulate joint bob"
        c.request("input button left down")  # the forearm again: the joint above it
        c.request("input button left up")
        assert asking(c) is None
        g = c.request("get manip")
        assert g["mode"] == "joint"
        # the joint above the forearm is the elbow: G sits on its pivot, the elbow's site
        elbow = c.request("get site bob forearm_r.origin")["position"]
        assert g["position"] == pytest.approx(elbow, abs=1e-9)


def test_answers_typed_and_a_value_asked(daemon):
    with daemon.client() as c:
        setup(c)
        type_text(c, "set joint", enter=True)
        assert asking(c) == "select a figure"
        type_text(c, "bob", enter=True)
        assert asking(c) == "select a joint"
        type_text(c, "knee_l", enter=True)
        assert asking(c) == "value?"
        type_text(c, "30deg", enter=True)
        assert asking(c) is None
        assert c.request("get joint bob knee_l")["values"][0] == pytest.approx(math.radians(30))


def test_esc_cancels_and_nothing_changes(daemon):
    with daemon.client() as c:
        setup(c)
        before = c.request("get posture bob")
        depth = c.request("status")["undo"]
        type_text(c, "set joint bob", enter=True)
        assert asking(c) == "select a joint"
        type_text(c, "kne")
        press(c, "KEY_ESC")
        assert asking(c) is None and c.request("get kiosk")["line"] == ""
        assert c.request("get posture bob") == before
        assert c.request("status")["undo"] == depth
        # a click on nothing picks nothing: asked again
        type_text(c, "manipulate figure", enter=True)
        c.request("input pointer front 5 5")
        c.request("input button left down")
        c.request("input button left up")
        assert asking(c) == "select a figure"
        press(c, "KEY_ESC")
        assert c.request("get manip")["mode"] == "none"


def test_subscribers_are_told_the_prompt_and_what_is_picked(daemon):
    with daemon.client() as c, daemon.client() as watcher:
        setup(c)
        watcher.subscribe("kiosk")
        type_text(c, "manipulate site", enter=True)
        x, y = pixel_on(c, "thigh_l")
        c.request(f"input pointer front {x} {y}")
        press(c, "KEY_ESC")
        c.request("get kiosk")
        seen = [(e["prompt"], e["picked"]) for e in watcher.events(timeout=0.5)
                if e["event"] == "kiosk"]
        asked = {"line": "manipulate site", "question": "select a figure"}
        assert (asked, None) in seen
        assert (asked, {"figure": "bob", "segment": "thigh_l"}) in seen
        assert seen[-1] == (None, None)
