"""§3.7.1 through the daemon: when the manipulated object's origin is hidden from the camera
by another figure, the view turns (eased, about G) until the line from the eye to G is clear;
C takes it back. Clear or not is computed here, independently of the daemon's visibility map:
the segment from the eye to G against the wall's box, by slabs."""
import time

import pytest

from daemon import ROOT, daemon_factory, write_picture  # noqa: F401 (fixture)

# lib:box.fig is 40 x 25 x 30 cm (x, y, z) standing on its base; set where it stands
WALL_AT = (0.0, 0.85, 1.5)
WALL_LO = [WALL_AT[0] - 0.2, WALL_AT[1], WALL_AT[2] - 0.15]
WALL_HI = [WALL_AT[0] + 0.2, WALL_AT[1] + 0.25, WALL_AT[2] + 0.15]


def hits_box(a, b, lo, hi):
    """1 when the segment a-b passes through the box lo..hi (slab test)"""
    t0, t1 = 0.0, 1.0
    for k in range(3):
        d = b[k] - a[k]
        if abs(d) < 1e-12:
            if a[k] < lo[k] or a[k] > hi[k]:
                return False
            continue
        u, v = (lo[k] - a[k]) / d, (hi[k] - a[k]) / d
        t0, t1 = max(t0, min(u, v)), min(t1, max(u, v))
        if t0 > t1:
            return False
    return True


def front(c):
    return next(v for v in c.request("list views")["views"] if v["name"] == "front")


def turned(c, g, before, limit=3):
    """the view once it has turned to aim at G from elsewhere (or as it is after limit s)"""
    t0 = time.monotonic()
    v = front(c)
    while time.monotonic() - t0 < limit:
        v = front(c)
        if v["target"] == pytest.approx(g, abs=1e-6) and v["eye"] != before["eye"]:
            break
        time.sleep(0.02)
    return v


def settled(c, limit=3):
    """the view once its camera has stopped moving (or as it is after limit s)"""
    t0 = time.monotonic()
    v = front(c)
    while time.monotonic() - t0 < limit:
        time.sleep(0.25)
        now = front(c)
        if now == v:
            break
        v = now
    return v


def test_a_wall_between_camera_and_g_is_avoided(daemon_factory):
    library = ["--library", str(ROOT / "src" / "figure" / "library")]
    with daemon_factory(extra=library).client() as c:
        c.request("load human as human")
        c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
        c.request("load figure lib:box.fig as wall")
        c.request("set location wall %g %g %g" % WALL_AT)
        before = front(c)
        c.request("manipulate figure human")
        g = c.request("get manip")["position"]
        assert hits_box(before["eye"], g, WALL_LO, WALL_HI)  # the wall hides G
        v = turned(c, g, before)
        assert v["target"] == pytest.approx(g, abs=1e-6)  # it ends aimed at G
        assert not hits_box(v["eye"], g, WALL_LO, WALL_HI)  # and sees it past the wall
        write_picture(c, "front", "obstruct_wall.png")
        dist = lambda e: sum((x - y) ** 2 for x, y in zip(e, g)) ** 0.5  # noqa: E731
        assert dist(v["eye"]) == pytest.approx(dist(before["eye"]), abs=1e-6)  # turned about G
        # a slight turn (§3.9), not a jump to the other side
        cosang = sum((a - x) * (b - x) for a, b, x in zip(v["eye"], before["eye"], g)) / dist(
            before["eye"]) ** 2
        assert cosang > 0.9
        # C takes it back
        c.request("input key KEY_C down")
        c.request("input key KEY_C up")
        back = front(c)
        assert back["eye"] == pytest.approx(before["eye"], abs=1e-9)
        assert back["target"] == pytest.approx(before["target"], abs=1e-9)


def test_a_new_drag_checks_again(daemon_factory):
    """a button going down in a mode looks again: a wall put in the way since is avoided"""
    library = ["--library", str(ROOT / "src" / "figure" / "library")]
    with daemon_factory(extra=library).client() as c:
        c.request("load human as human")
        c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
        c.request("load figure lib:box.fig as wall")
        c.request("set location wall 1.5 0.85 1.5")  # off to the side: nothing to avoid
        c.request("manipulate figure human")
        time.sleep(0.2)
        before = front(c)
        assert before["eye"] == pytest.approx([0, 1, 3], abs=1e-9)
        c.request("set location wall %g %g %g" % WALL_AT)  # now in the way
        g = c.request("get manip")["position"]
        assert hits_box(before["eye"], g, WALL_LO, WALL_HI)
        c.request("input pointer front 10 10")
        c.request("input button left down")
        c.request("input button left up")
        v = turned(c, g, before)
        assert not hits_box(v["eye"], g, WALL_LO, WALL_HI)


def test_the_turned_camera_is_journaled(daemon_factory):
    """the end of the turn is journaled as `set camera`, as the other adjustments are"""
    library = ["--library", str(ROOT / "src" / "figure" / "library")]
    d = daemon_factory(extra=library)
    with d.client() as c:
        c.request("load human as human")
        c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
        c.request("load figure lib:box.fig as wall")
        c.request("set location wall %g %g %g" % WALL_AT)
        c.request("manipulate figure human")
        g = c.request("get manip")["position"]
        t0 = time.monotonic()
        while time.monotonic() - t0 < 3 and front(c)["target"] != pytest.approx(g, abs=1e-6):
            time.sleep(0.02)
        time.sleep(0.2)  # the last in-between journaled
        turned = front(c)
        assert turned["eye"] != pytest.approx([0, 1, 3], abs=1e-3)
    d.kill9()
    d.start()
    with d.client() as c:
        assert front(c)["eye"] == pytest.approx(turned["eye"], abs=1e-9)
        assert front(c)["target"] == pytest.approx(turned["target"], abs=1e-9)


def test_a_clear_view_is_left_alone(daemon_factory):
    library = ["--library", str(ROOT / "src" / "figure" / "library")]
    with daemon_factory(extra=library).client() as c:
        c.request("load human as human")
        c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
        c.request("load figure lib:box.fig as wall")
        c.request("set location wall 1.5 0.85 1.5")  # off to the side
        before = front(c)
        c.request("manipulate figure human")
        c.request("input pointer front 160 120")
        c.request("input button left down")
        c.request("input button left up")
        time.sleep(0.3)
        assert front(c)["eye"] == pytest.approx(before["eye"], abs=1e-9)


def test_the_figure_s_own_body_hiding_a_dragged_hand_is_avoided(daemon_factory):
    """A hand dragged where the figure's own hips hide it from the camera: the parts around
    G (the hand and the forearm) are left out of the map, the rest of the body is not, so
    the view turns. Hidden or seen is judged by `pick` (triangles along the mouse line
    through the view's centre, where G is: the view aims at it), not by the map."""
    with daemon_factory().client() as c:
        c.request("load human as human")
        palm = c.request("get site human hand_r.palm")["position"]
        # behind the figure and to its left, level with the hand: the hips in between
        eye = [palm[0] + 2.6, palm[1] + 0.1, palm[2] - 1.3]
        c.request("add view front width=320 height=240 eye=%g,%g,%g target=%g,%g,%g"
                  % (*eye, *palm))
        before = front(c)
        first = c.request("pick front 160 120")["hit"]
        assert first["segment"] not in ("hand_r", "forearm_r"), first  # the body hides it
        c.request("drag human hand_r.palm start=shoulder_r view=front")
        g = c.request("get manip")["position"]
        v = settled(c)
        assert v["target"] == pytest.approx(g, abs=1e-6)
        assert v["eye"] != pytest.approx(before["eye"], abs=1e-3), "the view did not turn"
        seen = c.request("pick front 160 120")["hit"]
        write_picture(c, "front", "obstruct_own_body.png")
        assert seen["segment"] in ("hand_r", "forearm_r"), seen
        c.request("input key KEY_ESC down")
