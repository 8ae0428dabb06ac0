"""Manipulation with constraints (§4.6.3): moving a figure with the operator while
other constraints hold. A human's hand holding a place on a box follows the box the mouse
moves (hold local location, Table D.4); a box the hand grabbed follows the hand the mouse
moves. The expected motion is G's, which the mouse line gives (test_manip.py checks G)."""
import math

import pytest

from daemon import ROOT, daemon_factory, write_picture  # noqa: F401 (fixture)
from test_manip import drag_x

LIBRARY = ["--library", str(ROOT / "src" / "figure" / "library")]


def palm(c):
    return c.request("get site human hand_r.palm")["position"]


def near_the_right_hand(c):
    """the box (40 x 25 x 30 cm, on its base) put with its top face just under the palm"""
    c.request("load human as human")
    c.request("behave human on")
    c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
    c.request("settle frames=30")
    p = palm(c)
    c.request("load figure lib:box.fig as box")
    c.request("set location box %.17g %.17g %.17g" % (p[0] - 0.15, p[1] - 0.26, p[2]))
    c.request("settle frames=5")


def test_a_hand_holding_a_box_follows_the_box_the_mouse_moves(daemon_factory):
    with daemon_factory(extra=LIBRARY).client() as c:
        near_the_right_hand(c)
        c.request("hold hand human right box")
        before = palm(c)
        c.request("manipulate figure box view=front")
        g0 = c.request("get manip")["position"]
        g = drag_x(c, -0.05)  # outwards, within the arm's reach
        moved = [a - b for a, b in zip(g, g0)]
        assert moved[0] == pytest.approx(-0.05, abs=0.01)
        c.request("settle frames=120")
        write_picture(c, "front", "manip_hold_follows_box.png")
        after = palm(c)
        want = [a + m for a, m in zip(before, moved)]
        assert math.dist(after, want) < 0.005, (after, want)
        assert c.request("get behavior human")["balance"]["margin"] > 0
        c.request("input key KEY_ESC down")


def test_a_grabbed_box_follows_the_hand_the_mouse_moves(daemon_factory):
    with daemon_factory(extra=LIBRARY).client() as c:
        near_the_right_hand(c)
        c.request("grab human right box")
        box0 = c.request("get site box %s" % c.request("show figure box")["root"])["position"]
        c.request("manipulate hand human right view=front")
        g0 = c.request("get manip")["position"]
        g = drag_x(c, -0.06)
        c.request("settle frames=120")
        write_picture(c, "front", "manip_grab_follows_hand.png")
        hand = [a - b for a, b in zip(palm(c), g0)]
        assert hand[0] == pytest.approx(g[0] - g0[0], abs=0.01)
        box = c.request("get site box %s" % c.request("show figure box")["root"])["position"]
        # the box went with the hand, rigidly
        assert [b - a for a, b in zip(box0, box)] == pytest.approx(hand, abs=0.005)
        c.request("input key KEY_ESC down")
