"""Change view (Appendix C) through the daemon: V enters it from anywhere, the mouse sweeps,
ESC keeps the view (journaled as the command that sets it), C gives the old one back, and
the manipulation it interrupted goes on after. The expected cameras are Appendix C's
geometry computed here."""
import math

import pytest

from daemon import daemon, daemon_factory, snapshot, write_picture  # noqa: F401 (fixtures)


def view(c, name):
    return next(v for v in c.request("list views")["views"] if v["name"] == name)


def key(c, name):
    c.request(f"input key {name} down")
    c.request(f"input key {name} up")


def test_a_left_sweep_turns_the_camera_about_the_vertical_through_the_reference_point(daemon):
    with daemon.client() as c:
        c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
        c.request("input pointer front 160 120")
        key(c, "KEY_F2")  # at the edit line V is a letter
        c.request("input button left down")
        c.request("input motion 40 0")  # 40 px at 0.5 degrees a pixel: 20 degrees
        c.request("input button left up")
        v = view(c, "front")
        a = math.radians(20)
        # the camera moves right round R: from +z towards +x, R and the distance kept
        assert v["eye"] == pytest.approx([3 * math.sin(a), 1, 3 * math.cos(a)], abs=1e-9)
        assert v["target"] == pytest.approx([0, 1, 0], abs=1e-9)
        key(c, "KEY_ESC")
        c.request("load human as human")
        write_picture(c, "front", "viewctl_sweep.png")
        kept = view(c, "front")
        assert kept["eye"] == pytest.approx(v["eye"], abs=1e-9)
    daemon.kill9()
    daemon.start()
    with daemon.client() as c:  # the view it left was journaled
        assert view(c, "front")["eye"] == pytest.approx(kept["eye"], abs=1e-9)


def test_c_gives_the_view_before_back(daemon):
    with daemon.client() as c:
        c.request("add view front width=320 height=240 eye=0.5,1.5,3 target=0,1,0")
        before = view(c, "front")
        c.request("input pointer front 160 120")
        key(c, "KEY_F2")  # at the edit line V is a letter
        c.request("input button middle down")
        c.request("input motion 0 -30")
        c.request("input button middle up")
        assert view(c, "front")["eye"] != pytest.approx(before["eye"], abs=1e-6)
        key(c, "KEY_C")
        after = view(c, "front")
        assert after["eye"] == pytest.approx(before["eye"], abs=1e-9)
        assert after["target"] == pytest.approx(before["target"], abs=1e-9)


def test_v_mid_manipulation_moves_the_view_and_the_manipulation_goes_on(daemon):
    with daemon.client() as c:
        c.request("load human as human")
        c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
        c.request("manipulate figure human")
        g0 = c.request("get manip")["position"]
        key(c, "KEY_V")
        c.request("input button left down")
        c.request("input motion 20 0")
        c.request("input button left up")
        # the camera moved, G did not
        assert view(c, "front")["eye"][0] > 0.5
        assert c.request("get manip")["position"] == pytest.approx(g0, abs=1e-12)
        key(c, "KEY_ESC")  # ends change view only
        m = c.request("get manip")
        assert m["mode"] == "figure"
        key(c, "KEY_ESC")  # and now the manipulation
        assert c.request("get manip")["mode"] == "none"


def test_s_snaps_the_reference_point_to_what_is_picked(daemon):
    import time
    with daemon.client() as c:
        c.request("load human as human")
        c.request("add view front width=320 height=240 eye=0,1,3 target=0,1.6,0")
        hit = c.request("pick front 160 150")["hit"]
        assert hit is not None
        c.request("input pointer front 160 150")
        key(c, "KEY_F2")  # at the edit line V is a letter
        key(c, "KEY_S")
        c.request("input button left down")
        c.request("input button left up")
        deadline = time.monotonic() + 3
        while time.monotonic() < deadline:  # at most 1 s of eased in-betweens
            t = view(c, "front")["target"]
            if t == pytest.approx(hit["point"], abs=1e-6):
                break
            time.sleep(0.05)
        assert view(c, "front")["target"] == pytest.approx(hit["point"], abs=1e-6)
        write_picture(c, "front", "viewctl_snap.png")
