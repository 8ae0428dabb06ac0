"""Sites moved on their segments: `set site` over the socket and the
`manipulate site` mode the kiosk starts. The expected frames are the segment's frame
times the site's location, computed here from frames the daemon reports with the site
put on the segment's own frame (identity location), so nothing is copied from the
code under test."""
import math

import pytest

from daemon import daemon, daemon_factory, write_picture  # noqa: F401 (fixtures)
from test_manip import drag_x, setup


def site(c, name):
    """a site's global frame as one flat list: position, then the rotation row by row"""
    s = c.request(f"get site human {name}")
    return s["position"] + s["rotation"]


def rows(flat):
    return [flat[3 * i:3 * i + 3] for i in range(3)]


def mat_vec(r, v):
    return [sum(r[i][j] * v[j] for j in range(3)) for i in range(3)]


def segment_frame(c, name):
    """the segment's global frame: the site put on the segment's origin, unrotated"""
    c.request(f"set site human {name} 0 0 0 rot=x,0")
    s = site(c, name)
    return s[:3], rows(s[3:])


def test_set_site_places_the_site_in_its_segment_s_frame(daemon):
    with daemon.client() as c:
        setup(c)
        others = site(c, "hand_r.fingertip")
        o, r = segment_frame(c, "hand_r.palm")
        reply = c.request("set site human hand_r.palm 3cm -0.02 0.01 rot=z,90deg")
        want = [a + b for a, b in zip(o, mat_vec(r, [0.03, -0.02, 0.01]))]
        assert reply["position"] == pytest.approx(want, abs=1e-12)
        s = site(c, "hand_r.palm")
        assert s[:3] == pytest.approx(want, abs=1e-12)
        # the rotation: the segment's, turned 90 degrees about its own z
        turned = [x for i in range(3) for x in (r[i][1], -r[i][0], r[i][2])]
        assert s[3:] == pytest.approx(turned, abs=1e-12)
        # the segment and the rest of the figure stay put
        assert site(c, "hand_r.fingertip") == pytest.approx(others, abs=1e-12)


def test_bad_set_site_lines_change_nothing(daemon):
    with daemon.client() as c:
        setup(c)
        before = site(c, "hand_r.palm")
        for line, code in [("set site human hand_r.nowhere 0 0 0", "not-found"),
                           ("set site nobody hand_r.palm 0 0 0", "not-found"),
                           ("set site human hand_r.palm 0 x 0", "bad-number"),
                           ("set site human hand_r.palm 0 0 2km", "bad-number"),
                           ("set site human hand_r.palm 0 0 0 rot=q,1", "bad-argument"),
                           ("set site human hand_r.palm 0 0 0 yaw=1", "bad-argument")]:
            assert c.request_reply(line)["error"]["code"] == code, line
        assert site(c, "hand_r.palm") == before


def test_moving_the_root_site_keeps_its_segment_still(daemon):
    with daemon.client() as c:
        setup(c)
        root = c.request("show figure human")["root"]
        head = site(c, "head.between_eyes")
        c.request(f"set site human {root} 0.05 0 0")
        assert site(c, "head.between_eyes") == pytest.approx(head, abs=1e-12)
        o, r = segment_frame(c, root)
        assert site(c, "head.between_eyes") == pytest.approx(head, abs=1e-12)
        c.request(f"set site human {root} 0.05 0 0")
        assert site(c, root)[:3] == pytest.approx(
            [a + b for a, b in zip(o, mat_vec(r, [0.05, 0, 0]))], abs=1e-12)


def test_a_dragged_site_follows_g_on_its_segment_and_survives_a_kill(daemon):
    with daemon.client() as c:
        setup(c)
        wrist = site(c, "hand_r.fingertip")
        start = site(c, "hand_r.palm")[:3]
        assert c.request("manipulate site human hand_r.palm view=front") == {
            "mode": "site", "view": "front"}
        g0 = c.request("get manip")
        assert g0["mode"] == "site" and g0["position"] == pytest.approx(start, abs=1e-12)
        g = drag_x(c, -0.04)
        assert g[0] - g0["position"][0] == pytest.approx(-0.04, abs=0.01)
        moved = site(c, "hand_r.palm")[:3]
        write_picture(c, "front", "manip_site.png")
        assert moved == pytest.approx(g, abs=1e-9)
        assert site(c, "hand_r.fingertip") == pytest.approx(wrist, abs=1e-12)
        c.request("input key KEY_ESC down")
        c.request("input key KEY_ESC up")
        assert c.request("get manip")["mode"] == "none"
    daemon.kill9()
    daemon.start()
    with daemon.client() as c:
        assert site(c, "hand_r.palm")[:3] == pytest.approx(moved, abs=1e-9)
        assert site(c, "hand_r.fingertip") == pytest.approx(wrist, abs=1e-9)


def test_a_moved_site_goes_with_a_saved_session_and_undo_takes_it_back(daemon):
    with daemon.client() as c:
        setup(c)
        start = site(c, "hand_r.palm")[:3]
        c.request("set site human hand_r.palm 0.01 0.02 0.03")
        moved = site(c, "hand_r.palm")[:3]
        assert math.dist(moved, start) > 0.01
        c.request("save session moved.session")
        c.request("undo")
        assert site(c, "hand_r.palm")[:3] == pytest.approx(start, abs=1e-12)
        c.request("load session moved.session")
        assert site(c, "hand_r.palm")[:3] == pytest.approx(moved, abs=1e-12)


def test_a_site_its_segment_hangs_from_is_refused_with_the_way_out(daemon):
    with daemon.client() as c:
        setup(c)
        hanging = "hand_r.origin"  # the wrist joint's site on the hand
        err = c.request_reply(f"manipulate site human {hanging}")["error"]
        assert err["code"] == "bad-argument" and f"set root human {hanging}" in err["message"]
        assert c.request("get manip")["mode"] == "none"
        c.request(f"set root human {hanging}")
        assert c.request(f"manipulate site human {hanging}")["mode"] == "site"
