"""The manikin's eye view (`add view NAME eyes=FIG [which=left|right|both] [hfov=DEG]`).

- The camera is the eyes: for one eye at its eyeball's `gaze` site looking along the site's
  +z axis, for both eyes at the midpoint of the two sites looking along the mean of their
  lines of sight; checked to 1e-9 against `get site` after `move head` and `move eyes`, and
  frame by frame while the behaviours turn the head (`pick` at the picture's centre, which
  reads the camera the last frame placed, gives the same origin and direction).
- The horizontal field of view: the mouse lines through the middle of the picture's left and
  right edges are hfov apart (90 deg binocular for both eyes, 100 deg for one, or as set);
  the vertical one follows from the aspect.
- A session keeps the view (its three words written only for an eye view); a session
  written before, without them, reads as it did.
- Bad input is refused and changes no view.
- The picture is seen from inside the head and the head does not block it: the eyeball
  (12 mm) and the face lie nearer than the camera's near plane (5 cm), and the inside of the
  head is not drawn.
"""
import base64
import colorsys
import math

import numpy as np

from daemon import daemon, daemon_factory  # noqa: F401 (fixtures)
from test_assess_tint import decode_png
from test_behave_daemon import LIBRARY

W, H = 320, 240
BAND = 2 * 20  # the message and status lines at the bottom (their text changes)


def site(c, name):
    r = c.request(f"get site jack {name}")
    rot = np.array(r["rotation"]).reshape(3, 3)  # row-major: the columns are the site's axes
    return np.array(r["position"]), rot[:, 2]


def expected(c, which):
    """the camera's place and line of sight from the eye sites, as the docs define them"""
    lp, lz = site(c, "eyeball_l.gaze")
    rp, rz = site(c, "eyeball_r.gaze")
    if which == "left":
        return lp, lz
    if which == "right":
        return rp, rz
    d = lz + rz
    return (lp + rp) / 2, d / np.linalg.norm(d)


def view(c, name):
    return next(v for v in c.request("list views")["views"] if v["name"] == name)


def camera(c, name):
    v = view(c, name)
    eye, target = np.array(v["eye"]), np.array(v["target"])
    d = target - eye
    return eye, d / np.linalg.norm(d)


def assert_on_eyes(c, name, which):
    eye, sight = camera(c, name)
    want_eye, want_sight = expected(c, which)
    assert np.abs(eye - want_eye).max() < 1e-9, (name, eye, want_eye)
    assert np.abs(sight - want_sight).max() < 1e-9, (name, sight, want_sight)


def angle(a, b):
    return math.degrees(math.acos(max(-1.0, min(1.0, float(np.dot(a, b))))))


def test_the_camera_is_the_eyes_after_move_head_and_move_eyes(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        for which in ("both", "left", "right"):
            c.request(f"add view {which} eyes=jack which={which} width={W} height={H}")
        c.request("add view plain")
        assert "eyes" not in view(c, "plain")
        v = view(c, "both")
        assert (v["eyes"], v["which"], v["hfov"], v["icons"]) == ("jack", "both", 90.0, False)
        assert view(c, "left")["hfov"] == 100.0 and view(c, "right")["hfov"] == 100.0
        for which in ("both", "left", "right"):
            assert_on_eyes(c, which, which)
        # standing straight, eyes ahead: the figure faces +z
        assert np.abs(camera(c, "both")[1] - [0, 0, 1]).max() < 1e-9
        c.request("behave jack on")
        c.request("move head jack 1.5,0.8,1.5")
        c.request("move eyes jack 0.8,1.2,1.5")
        c.request("settle frames=300")
        for which in ("both", "left", "right"):
            assert_on_eyes(c, which, which)
        # the eyes fixate the point: the camera of one eye looks at it
        eye, sight = camera(c, "left")
        to = np.array([0.8, 1.2, 1.5]) - eye
        assert angle(sight, to / np.linalg.norm(to)) < 1.0
        # the picture's width is the horizontal field of view, its height follows the aspect
        for name, hfov in (("both", 90.0), ("left", 100.0)):
            left = np.array(c.request(f"pick {name} 0 {H / 2}")["direction"])
            right = np.array(c.request(f"pick {name} {W} {H / 2}")["direction"])
            top = np.array(c.request(f"pick {name} {W / 2} 0")["direction"])
            mid = np.array(c.request(f"pick {name} {W / 2} {H / 2}")["direction"])
            assert abs(angle(left, right) - hfov) < 1e-6, name
            fovy = 2 * math.degrees(math.atan(math.tan(math.radians(hfov / 2)) * H / W))
            assert abs(2 * angle(top, mid) - fovy) < 1e-6, name
            assert abs(view(c, name)["fovy"] - fovy) < 1e-9
        c.request("set camera left hfov=60")
        left = np.array(c.request(f"pick left 0 {H / 2}")["direction"])
        right = np.array(c.request(f"pick left {W} {H / 2}")["direction"])
        assert abs(angle(left, right) - 60) < 1e-6
        # a picture through the eyes renders at the view's size
        r = c.request("render view both")
        assert (r["width"], r["height"]) == (W, H)
        # at the kiosk a tile like any other: resized to its tile, the width stays hfov wide
        tiles = c.request("layout both plain")["tiles"]
        tile = next(t for t in tiles if t["view"] == "both")
        w, h = tile["width"], tile["height"]
        assert (w, h) != (W, H)
        left = np.array(c.request(f"pick both 0 {h / 2}")["direction"])
        right = np.array(c.request(f"pick both {w} {h / 2}")["direction"])
        assert abs(angle(left, right) - 90) < 1e-6
        assert_on_eyes(c, "both", "both")
        c.request("render screen")


def test_the_view_follows_frame_by_frame(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        c.request(f"add view eyes eyes=jack width={W} height={H}")
        c.request("behave jack on")
        c.request("move head jack -1.5,2.0,1.0")
        sights = []
        for _ in range(12):
            c.request("settle frames=1")
            # pick reads the camera as the last frame left it (no placing of its own); the
            # daemon's own frames go on between requests, so the reading counts when the
            # camera did not move while the sites were read
            for _attempt in range(20):
                p = c.request(f"pick eyes {W / 2} {H / 2}")
                want_eye, want_sight = expected(c, "both")
                if c.request(f"pick eyes {W / 2} {H / 2}") == p:
                    break
            else:
                raise AssertionError("the head never held still for three requests")
            assert np.abs(np.array(p["origin"]) - want_eye).max() < 1e-9
            assert np.abs(np.array(p["direction"]) - want_sight).max() < 1e-9
            sights.append(want_sight)
        # the head did turn while the frames ran, and the camera went with it
        assert angle(sights[0], sights[-1]) > 2.0


def test_a_session_keeps_the_eye_view(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        c.request(f"add view eyes eyes=jack which=right hfov=75.125 width={W} height={H}")
        c.request("add view plain width=320 height=240 eye=3,1.2,0 target=0,0.95,0")
        c.request("set joint jack spine_17 0.2 0.1 0.3")
        before = c.request("list views")["views"]
        c.request("save session s.ses")
        text = (daemon.state_dir / "s.ses").read_text()
        lines = {ln.split()[1]: ln for ln in text.splitlines() if ln.startswith("view ")}
        assert lines["eyes"].endswith(" eyes=jack which=right hfov=75.125"), lines
        assert "eyes=" not in lines["plain"], lines
        c.request("delete view eyes")
        c.request("set joint jack spine_17 0 0 0")
        c.request("load session s.ses")
        assert c.request("list views")["views"] == before
        assert_on_eyes(c, "eyes", "right")
    daemon.restart()
    with daemon.client() as c:
        assert c.request("list views")["views"] == before
        assert_on_eyes(c, "eyes", "right")


def test_a_session_from_before_reads_as_it_did(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        c.request("save session probe.ses")
        kept = [ln for ln in (daemon.state_dir / "probe.ses").read_text().splitlines()
                if not ln.startswith("view ")]
        old_view = "view old width=320 height=240 icons=1 eye=3,1.5,0.5 target=0,1,0 fovy=35"
        assert kept[-1] == "end"
        (daemon.state_dir / "old.ses").write_text("\n".join(kept[:-1] + [old_view, "end"]) + "\n")
        c.request("load session old.ses")
        v = c.request("list views")["views"]
        assert v == [{"name": "old", "width": 320, "height": 240, "eye": [3, 1.5, 0.5],
                      "target": [0, 1, 0], "fovy": 35, "icons": True, "tint": "off",
                      "loads": "on"}]
        c.request("save session again.ses")
        again = (daemon.state_dir / "again.ses").read_text()
        assert old_view + "\n" in again
        # a damaged eye view's line is refused, the session's state not half taken
        (daemon.state_dir / "bad.ses").write_text(
            again.replace(old_view, old_view + " eyes=jack which=middle hfov=90"))
        r = c.request_reply("load session bad.ses")
        assert not r["ok"], r
        assert c.request("list views")["views"] == v


def test_bad_input_is_refused_and_changes_nothing(daemon_factory):
    with daemon_factory(extra=LIBRARY).client() as c:
        c.request("load human as jack")
        c.request("load figure lib:table.fig as table")
        c.request(f"add view eyes eyes=jack width={W} height={H}")
        c.request("add view plain")
        before = c.request("list views")["views"]
        for line, code in (("add view e eyes=nobody", "not-found"),
                           ("add view e eyes=table", "bad-argument"),
                           ("add view e eyes=jack which=middle", "bad-argument"),
                           ("add view e eyes=jack hfov=0", "bad-number"),
                           ("add view e eyes=jack hfov=171", "bad-number"),
                           ("add view e eyes=jack hfov=wide", "bad-number"),
                           ("add view e eyes=jack eye=0,1,2", "bad-argument"),
                           ("add view e eyes=jack fovy=50", "bad-argument"),
                           ("add view e which=left", "bad-argument"),
                           ("add view e hfov=80", "bad-argument"),
                           ("add view eyes eyes=jack", "exists"),
                           ("set camera eyes eye=0,1,2 target=0,1,0", "bad-argument"),
                           ("set camera eyes fovy=30", "bad-argument"),
                           ("set camera eyes hfov=200", "bad-number"),
                           ("set camera plain hfov=50", "bad-argument")):
            reply = c.request_reply(line)
            assert not reply["ok"] and reply["error"]["code"] == code, (line, reply)
            assert c.request("list views")["views"] == before, line
        # the figure gone, the view stays where the eyes last were; back, it follows again
        c.request("unload figure jack")
        assert c.request("list views")["views"] == before
        c.request("render view eyes")
        c.request("load human as jack")
        c.request("set joint jack spine_17 0.3 0 0")
        assert_on_eyes(c, "eyes", "both")


def picture(c, name):
    return decode_png(base64.b64decode(c.request(f"render view {name}")["png"]))[:-BAND]


def test_the_picture_is_seen_from_inside_the_head(daemon):
    """Looking straight ahead at nothing, the eye view is the picture an ordinary camera
    at the same place shows with the figure gone: its own head hides nothing."""
    with daemon.client() as c:
        c.request("load human as jack")
        c.request(f"add view eyes eyes=jack width={W} height={H}")
        v = view(c, "eyes")
        place = (f"width={W} height={H} eye={','.join(map(repr, v['eye']))} "
                 f"target={','.join(map(repr, v['target']))} fovy={v['fovy']!r}")
        c.request(f"add view same {place}")
        c.request("set view eyes cones=off")
        through_eyes = picture(c, "eyes")
        c.request("unload figure jack")
        nobody = picture(c, "same")
    assert np.array_equal(through_eyes, nobody)


def cone_radius(deg, fovy):
    """pixels from the picture's centre to where a cone of full angle deg about the line of
    sight meets it: a pinhole of vertical field fovy, H pixels high"""
    return H / 2 * math.tan(math.radians(deg / 2)) / math.tan(math.radians(fovy / 2))


def marks(c):
    """the pixels the cones' marks change (off against on), their distances from the centre"""
    on = picture(c, "eyes")
    views = {v["name"]: v for v in c.request("list views")["views"]}
    cones = views["eyes"]["cones"]
    c.request("set view eyes cones=off")
    off = picture(c, "eyes")
    c.request(f"set view eyes cones={','.join(map(repr, cones)) or 'off'}")
    ys, xs = np.nonzero(np.any(on != off, axis=2))
    return on, np.hypot(xs + 0.5 - W / 2, ys + 0.5 - H / 2)


def test_the_picture_marks_the_cones(daemon):
    """Circles about the line of sight at the cones of the research file (§6.2: CATIA's
    central 3 deg spot; DELMIA's reading 20, symbols 40, colour 60 deg), where a pinhole
    camera of the view's field puts them; settable and kept in sessions."""
    with daemon.client() as c:
        c.request("load human as jack")
        c.request(f"add view eyes eyes=jack width={W} height={H}")
        c.request("add view plain")
        v = view(c, "eyes")
        assert v["cones"] == [3, 20, 40, 60]
        fovy = v["fovy"]
        on, dist = marks(c)
        radii = [cone_radius(d, fovy) for d in (3, 20, 40, 60)]
        assert len(dist) > 400
        # every pixel changed lies on one of the circles; every circle is drawn
        assert all(min(abs(d - r) for r in radii) < 2.5 for d in dist), sorted(set(dist.round()))
        for r in radii:
            assert np.sum(np.abs(dist - r) < 2.5) > 2 * r, r
        # the central spot is red, reading yellow, symbols green, colour blue: the pixel
        # where each circle crosses the row through the centre, right of it
        for r, (want, name) in zip(radii, ((0, "red"), (60, "yellow"), (120, "green"),
                                           (215, "blue"))):
            row = on[H // 2, int(W / 2 + r) - 1:int(W / 2 + r) + 2, :3].astype(float) / 255
            rgb = max(row, key=lambda p: max(p) - min(p))  # the most coloured of the three
            h, sat, _ = colorsys.rgb_to_hsv(*rgb)
            assert sat > 0.25 and min(abs(h * 360 - want), 360 - abs(h * 360 - want)) < 25, \
                (name, rgb)
        # settable: two cones, then none
        assert c.request("set view eyes cones=10,30")["cones"] == [10, 30]
        _, dist = marks(c)
        radii = [cone_radius(d, fovy) for d in (10, 30)]
        assert all(min(abs(d - r) for r in radii) < 2.5 for d in dist)
        for r in radii:
            assert np.sum(np.abs(dist - r) < 2.5) > 2 * r, r
        # bad cones are refused, nothing changes
        before = c.request("list views")["views"]
        for line in ("set view eyes cones=0.1", "set view eyes cones=1,2,3,4,5",
                     "set view eyes cones=abc", "set view eyes cones=", "set view eyes cones=10,",
                     "set view eyes cones=171", "set view plain cones=3"):
            reply = c.request_reply(line)
            assert not reply["ok"] and reply["error"]["code"] == "bad-argument", (line, reply)
            assert c.request("list views")["views"] == before, line
        # sessions: the default not written, others are
        c.request("add view eyes2 eyes=jack which=left")
        c.request("add view eyes3 eyes=jack which=right")
        c.request("set view eyes3 cones=off")
        c.request("save session s.ses")
        text = (daemon.state_dir / "s.ses").read_text()
        lines = {ln.split()[1]: ln for ln in text.splitlines() if ln.startswith("view ")}
        assert lines["eyes"].endswith(" cones=10,30"), lines
        assert lines["eyes3"].endswith(" cones=off"), lines
        assert "cones=" not in lines["eyes2"] and "cones=" not in lines["plain"], lines
        before = c.request("list views")["views"]
        c.request("set view eyes cones=5")
        c.request("load session s.ses")
        assert c.request("list views")["views"] == before
        assert view(c, "eyes3")["cones"] == [] and view(c, "eyes2")["cones"] == [3, 20, 40, 60]


def test_undo_takes_back_the_eye_views_changes(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        c.request(f"add view eyes eyes=jack width={W} height={H}")
        before = view(c, "eyes")
        c.request("set view eyes cones=7")
        c.request("set camera eyes hfov=45")
        assert (view(c, "eyes")["cones"], view(c, "eyes")["hfov"]) == ([7], 45)
        c.request("undo")
        assert (view(c, "eyes")["cones"], view(c, "eyes")["hfov"]) == ([7], 90)
        c.request("undo")
        assert view(c, "eyes") == before
        c.request("undo")
        assert all(v["name"] != "eyes" for v in c.request("list views")["views"])
