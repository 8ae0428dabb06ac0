"""A manikin's sight drawn in other views (`set view VIEW sight=FIG|all|off [sight_length=LEN]`).

- The picture changes exactly where the cones are: the pixels that differ between sight on
  and off all lie within the projection (a pinhole of the view's camera, computed here) of
  the cones (3, 20, 40, 60 degrees), from the cyclopean eye (`get site` of the two eye sites)
  along the mean line of sight, its sides sight_length long; and most of that projection
  changes. After `move head` the cone is drawn where the eyes look then.
- Off: the picture is the one without; sight= and sight_length= are kept in sessions and
  taken back by undo; bad values are refused and change nothing.
"""
import base64
import math

import numpy as np

from daemon import daemon, daemon_factory  # noqa: F401 (fixtures)
from test_assess_tint import decode_png
from test_behave_daemon import LIBRARY

W, H = 320, 240
BAND = 2 * 20  # the message and status lines at the bottom (their text changes)
SIDE = "width=320 height=240 eye=3,1.6,0.6 target=0,1.5,0.6"
CAM_EYE, CAM_TARGET, FOVY = np.array([3, 1.6, 0.6]), np.array([0, 1.5, 0.6]), 40.0


def picture(c, name):
    return decode_png(base64.b64decode(c.request(f"render view {name}")["png"]))[:-BAND]


def project(points):
    """pixels (x, y) of world points through the side view's camera: -z along the line of
    sight, x horizontal, vertical field FOVY (view.h's camera)"""
    f = CAM_TARGET - CAM_EYE
    f = f / np.linalg.norm(f)
    x = np.cross(f, [0, 1, 0])
    x = x / np.linalg.norm(x)
    y = np.cross(x, f)
    rel = np.asarray(points) - CAM_EYE
    depth = rel @ f
    t = math.tan(math.radians(FOVY / 2))
    px = W / 2 * (1 + (rel @ x) / depth / (t * W / H))
    py = H / 2 * (1 - (rel @ y) / depth / t)
    return np.stack([px, py], axis=1)


def sight(c, fig="jack"):
    """the cyclopean eye and mean line of sight from the eye sites (eyeview.h)"""
    ps, zs = [], []
    for s in ("eyeball_l.gaze", "eyeball_r.gaze"):
        r = c.request(f"get site {fig} {s}")
        ps.append(np.array(r["position"]))
        zs.append(np.array(r["rotation"]).reshape(3, 3)[:, 2])
    d = zs[0] + zs[1]
    return (ps[0] + ps[1]) / 2, d / np.linalg.norm(d)


def cone_mask(eye, d, full_deg, length, grow):
    """the pixels the cone (apex eye, axis d, sides length long) covers, grown by grow px"""
    u = np.cross(d, [0, 1, 0] if abs(d[1]) < 0.9 else [1, 0, 0])
    u /= np.linalg.norm(u)
    v = np.cross(d, u)
    h = math.radians(full_deg / 2)
    t = np.linspace(0, 2 * math.pi, 720, endpoint=False)
    rim = eye + length * (math.cos(h) * d + math.sin(h) * (np.outer(np.cos(t), u) +
                                                             np.outer(np.sin(t), v)))
    # the cone is the union of the segments from the apex to the rim: sample them densely
    s = np.linspace(0, 1, 200)[:, None, None]
    pts = (eye + s * (rim - eye)).reshape(-1, 3)
    px = project(pts)
    mask = np.zeros((H - BAND, W), bool)
    xi, yi = np.floor(px[:, 0]).astype(int), np.floor(px[:, 1]).astype(int)
    ok = (xi >= 0) & (xi < W) & (yi >= 0) & (yi < H - BAND)
    mask[yi[ok], xi[ok]] = True
    grown = mask.copy()
    for dy in range(-grow, grow + 1):
        for dx in range(-grow, grow + 1):
            grown |= np.roll(np.roll(mask, dy, 0), dx, 1)
    return mask, grown


def changed(c):
    """the pixels sight changes in the side view (on against off), and the picture on"""
    on = picture(c, "side")
    was = next(v for v in c.request("list views")["views"] if v["name"] == "side")
    c.request("set view side sight=off")
    off = picture(c, "side")
    c.request(f"set view side sight={was['sight']} sight_length={was['sight_length']!r}")
    return np.any(on != off, axis=2), on


def assert_cone_where_the_eyes_look(c, length, cones=(3, 20, 40, 60)):
    diff, _ = changed(c)
    eye, d = sight(c)
    # the cones' sides are alike long: the narrow ones reach farther along the line of sight
    inside = np.zeros((H - BAND, W), bool)
    grown = inside.copy()
    for deg in cones:
        m, g = cone_mask(eye, d, deg, length, grow=3)
        inside |= m
        grown |= g
    # every changed pixel is on the cone (the rim's lines are 2 px wide: grown by 3)
    assert diff.sum() > 200
    assert not np.any(diff & ~grown), np.argwhere(diff & ~grown)[:10]
    # and most of the cone is drawn (the head hides its apex)
    assert (diff & inside).sum() > 0.8 * inside.sum(), ((diff & inside).sum(), inside.sum())
    return inside


def test_the_cones_are_drawn_from_the_eyes_and_follow_the_head(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        c.request(f"add view side {SIDE}")
        # the projection here is the view's: a point along the mouse line of a pixel
        # projects back onto that pixel
        for px, py in ((40, 30), (160, 120), (300, 190)):
            m = c.request(f"pick side {px} {py}")
            p = np.array(m["origin"]) + 2.5 * np.array(m["direction"])
            assert np.abs(project([p])[0] - [px, py]).max() < 1e-6
        # a view that draws no sight says nothing of it
        assert "sight" not in c.request("set view side loads=on")
        r = c.request("set view side sight=jack")
        assert (r["sight"], r["sight_length"]) == ("jack", 1.0)
        first = assert_cone_where_the_eyes_look(c, 1.0)
        # the length is the cone's sides: a shorter cone covers less
        c.request("set view side sight_length=0.5")
        short = assert_cone_where_the_eyes_look(c, 0.5)
        assert short.sum() < 0.5 * first.sum()
        # the head turned: the cone is where the eyes look now
        c.request("set view side sight_length=1")
        c.request("behave jack on")
        c.request("move head jack 0.4,2.4,1.2")
        c.request("settle frames=300")
        c.request("behave jack off")
        eye, d = sight(c)
        assert d[1] > 0.3  # looking up now
        moved = assert_cone_where_the_eyes_look(c, 1.0)
        assert (moved & first).sum() < 0.5 * first.sum()
        # off: no sight in the view's list
        c.request("set view side sight=off")
        assert "sight" not in c.request("list views")["views"][0]


def test_off_draws_nothing_and_all_draws_every_manikin(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        c.request(f"add view side {SIDE}")
        plain = picture(c, "side")
        c.request("set view side sight=jack")
        assert not np.array_equal(picture(c, "side"), plain)
        c.request("set view side sight=off")
        assert np.array_equal(picture(c, "side"), plain)
        # a second manikin a metre behind: sight=jack draws one cone, all draws two
        c.request("load human as jill")
        x, y, z = c.request("get site jack pelvis.root")["position"]
        c.request(f"set location jill {x} {y} {z - 1.5}")
        base = picture(c, "side")
        c.request("set view side sight=jack")
        one = np.any(picture(c, "side") != base, axis=2).sum()
        c.request("set view side sight=all")
        both = np.any(picture(c, "side") != base, axis=2).sum()
        assert both > 1.5 * one, (one, both)


def test_sessions_and_undo_keep_the_sight(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        c.request(f"add view side {SIDE}")
        c.request("add view plain")
        c.request("set view side sight=jack sight_length=1.25")
        before = c.request("list views")["views"]
        assert before[0]["sight"] == "jack" and before[0]["sight_length"] == 1.25
        assert "sight" not in before[1]
        c.request("save session s.ses")
        text = (daemon.state_dir / "s.ses").read_text()
        lines = {ln.split()[1]: ln for ln in text.splitlines() if ln.startswith("view ")}
        assert lines["side"].endswith(" sight=jack sight_length=1.25"), lines
        assert "sight" not in lines["plain"], lines
        c.request("set view side sight=all sight_length=3")
        c.request("load session s.ses")
        assert c.request("list views")["views"] == before
        # undo: each change one step back
        c.request("set view side sight_length=2")
        c.request("set view side sight=off")
        c.request("undo")
        assert c.request("list views")["views"][0]["sight_length"] == 2
        c.request("undo")
        assert c.request("list views")["views"] == before
    daemon.restart()
    with daemon.client() as c:
        assert c.request("list views")["views"] == before
        # a damaged line is refused whole
        good = (daemon.state_dir / "s.ses").read_text()
        for bad in (" sight=jack sight_length=0.01", " sight=jack", " sight=a-b sight_length=1"):
            (daemon.state_dir / "bad.ses").write_text(
                good.replace(" sight=jack sight_length=1.25", bad))
            r = c.request_reply("load session bad.ses")
            assert not r["ok"], (bad, r)
            assert c.request("list views")["views"] == before


def test_bad_input_is_refused_and_changes_nothing(daemon_factory):
    with daemon_factory(extra=LIBRARY).client() as c:
        c.request("load human as jack")
        c.request("load figure lib:table.fig as table")
        c.request(f"add view side {SIDE}")
        c.request("set view side sight=jack sight_length=0.7")
        before = c.request("list views")["views"]
        hash0 = c.request("status")["posture"]
        for line, code in (("set view side sight=nobody", "not-found"),
                           ("set view side sight=table", "bad-argument"),
                           ("set view side sight_length=0.01", "bad-number"),
                           ("set view side sight_length=21", "bad-number"),
                           ("set view side sight_length=far", "bad-number"),
                           ("set view side sight=all sight_length=-1", "bad-number"),
                           ("set view side sight=off sight_length=1", "bad-argument"),
                           ("set view side sight=jack tint=blue", "bad-argument"),
                           ("set view side sight=jack cones=3", "bad-argument"),
                           ("set view nowhere sight=jack", "not-found")):
            reply = c.request_reply(line)
            assert not reply["ok"] and reply["error"]["code"] == code, (line, reply)
            assert c.request("list views")["views"] == before, line
        assert c.request("status")["posture"] == hash0
        c.request("set view side sight=off")
        r = c.request_reply("set view side sight_length=1")
        assert not r["ok"] and r["error"]["code"] == "bad-argument", r
