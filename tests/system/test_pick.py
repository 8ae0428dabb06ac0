"""The mouse line and picking against the real daemon: `pick VIEW X Y` gives the ray that
PyGLM's gluUnProject-style `glm.unProject` gives for the same camera (lookAt from the eye
to the target, a perspective of the view's fovy); a ray through the projected centre of a
segment of the built-in human hits that segment; a ray into the sky hits nothing; bad
arguments are refused and change nothing; a view's field of view survives restarts and
sessions, and a session written before it existed still loads with the default."""
import math
import random

from pyglm import glm
import pytest

from daemon import daemon, daemon_factory, snapshot  # noqa: F401 (fixtures)

ZNEAR, ZFAR = 0.05, 200.0  # the daemon's camera (view_camera_default); they do not tilt the ray


def reference_ray(eye, target, fovy_deg, width, height, px, py):
    """origin and unit direction through pixel (px, py), y down, from PyGLM in double."""
    view = glm.lookAt(glm.dvec3(*eye), glm.dvec3(*target), glm.dvec3(0, 1, 0))
    proj = glm.perspective(glm.radians(fovy_deg), width / height, ZNEAR, ZFAR)
    proj = glm.dmat4(proj) if not isinstance(proj, glm.dmat4) else proj
    port = glm.dvec4(0, 0, width, height)
    win_y = height - py  # GL windows count rows from the bottom
    near = glm.unProject(glm.dvec3(px, win_y, 0), view, proj, port)
    far = glm.unProject(glm.dvec3(px, win_y, 1), view, proj, port)
    d = glm.normalize(far - near)
    return list(near), [d.x, d.y, d.z]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def perspective_d(fovy_rad, aspect, n, f):
    """The GL perspective matrix in double, column-major as glm keeps it."""
    t = 1 / math.tan(fovy_rad / 2)
    m = glm.dmat4(0)
    m[0][0] = t / aspect
    m[1][1] = t
    m[2][2] = -(f + n) / (f - n)
    m[2][3] = -1
    m[3][2] = -2 * f * n / (f - n)
    return m


def test_reference_is_double_and_is_glms():
    """PyGLM's perspective() is float only, so the reference builds gluPerspective's
    published matrix in double; it must equal PyGLM's to float precision, and lookAt and
    unProject must run in double, or 1e-9 would mean nothing."""
    for fovy, aspect in ((40.0, 4 / 3), (7.5, 0.4), (119.0, 3.1)):
        ours = perspective_d(math.radians(fovy), aspect, ZNEAR, ZFAR)
        theirs = glm.perspective(glm.radians(fovy), aspect, ZNEAR, ZFAR)
        for col in range(4):
            for row in range(4):
                assert ours[col][row] == pytest.approx(theirs[col][row], rel=1e-6, abs=1e-9)
    view = glm.lookAt(glm.dvec3(1, 2, 3), glm.dvec3(0, 1, 0), glm.dvec3(0, 1, 0))
    assert isinstance(view, glm.dmat4)
    p = glm.unProject(glm.dvec3(1, 2, 0), view, perspective_d(1, 1, ZNEAR, ZFAR),
                      glm.dvec4(0, 0, 4, 4))
    assert isinstance(p, glm.dvec3)


def test_mouse_line_matches_glm_unproject(daemon):
    rng = random.Random(1991)
    worst_d, worst_o = 0.0, 0.0
    with daemon.client() as c:
        n = 0
        for cam in range(50):
            # a camera anywhere, not looking straight up or down (lookAt's up would fail)
            while True:
                eye = [rng.uniform(-6, 6), rng.uniform(0.1, 4), rng.uniform(-6, 6)]
                target = [rng.uniform(-1, 1), rng.uniform(0, 2), rng.uniform(-1, 1)]
                sight = [t - e for t, e in zip(target, eye)]
                length = math.sqrt(dot(sight, sight))
                if length > 0.5 and abs(sight[1]) / length < 0.95:
                    break
            fovy = rng.uniform(5, 120)
            w, h = rng.randint(16, 1920), rng.randint(16, 1200)
            eye_s = ",".join(repr(v) for v in eye)
            target_s = ",".join(repr(v) for v in target)
            c.request(f"add view v{cam} width={w} height={h} eye={eye_s} target={target_s} "
                      f"fovy={fovy!r}")
            for _ in range(5):
                px, py = rng.uniform(0, w), rng.uniform(0, h)
                got = c.request(f"pick v{cam} {px!r} {py!r}")
                view = glm.lookAt(glm.dvec3(*eye), glm.dvec3(*target), glm.dvec3(0, 1, 0))
                proj = perspective_d(math.radians(fovy), w / h, ZNEAR, ZFAR)
                port = glm.dvec4(0, 0, w, h)
                p0 = glm.unProject(glm.dvec3(px, h - py, 0), view, proj, port)
                p1 = glm.unProject(glm.dvec3(px, h - py, 1), view, proj, port)
                d = glm.normalize(p1 - p0)
                want = [d.x, d.y, d.z]
                o, dd = got["origin"], got["direction"]
                assert o == pytest.approx(eye, abs=1e-12)
                assert math.sqrt(dot(dd, dd)) == pytest.approx(1, abs=1e-12)
                err = max(abs(a - b) for a, b in zip(dd, want))
                worst_d = max(worst_d, err)
                assert err < 1e-9, (eye, target, fovy, w, h, px, py, dd, want)
                # the near-plane point glm gives lies on the daemon's line
                rel = [a - b for a, b in zip(p0, o)]
                t = dot(rel, dd)
                off = math.sqrt(sum((r - t * x) ** 2 for r, x in zip(rel, dd)))
                worst_o = max(worst_o, off)
                assert off < 1e-9
                n += 1
            c.request(f"delete view v{cam}")
        assert n >= 200


def test_float_glm_agrees_roughly(daemon):
    """PyGLM's own (float) perspective, as a second opinion at float precision."""
    with daemon.client() as c:
        c.request("add view v width=640 height=480 eye=1,2,3 target=0,1,0 fovy=50")
        for px, py in ((0.5, 0.5), (320, 240), (639.5, 10), (100, 470)):
            o, d = reference_ray((1, 2, 3), (0, 1, 0), 50, 640, 480, px, py)
            got = c.request(f"pick v {px} {py}")
            assert got["direction"] == pytest.approx(d, abs=1e-6)


def project(eye, target, fovy, w, h, p):
    """pixel (x right, y down) of world point p, by PyGLM"""
    view = glm.lookAt(glm.dvec3(*eye), glm.dvec3(*target), glm.dvec3(0, 1, 0))
    proj = perspective_d(math.radians(fovy), w / h, ZNEAR, ZFAR)
    q = glm.project(glm.dvec3(*p), view, proj, glm.dvec4(0, 0, w, h))
    return q.x, h - q.y


HUMAN_SEGMENTS = {  # a segment, its proximal and distal sites: its centre is between them
    "thigh_l": ("thigh_l.origin", "thigh_l.knee_l"),
    "thigh_r": ("thigh_r.origin", "thigh_r.knee_r"),
    "shank_l": ("shank_l.knee", "shank_l.ankle_l"),
    "shank_r": ("shank_r.knee", "shank_r.ankle_r"),
    "upperarm_l": ("upperarm_l.origin", "upperarm_l.elbow_l"),
    "upperarm_r": ("upperarm_r.origin", "upperarm_r.elbow_r"),
    "head": ("head.origin", "head.vertex"),
}


def test_pick_hits_the_segment_under_the_pixel(daemon):
    eye, target, fovy, w, h = (0.3, 1.1, 3.0), (0.0, 1.0, 0.0), 45.0, 640, 480
    with daemon.client() as c:
        c.request("load human as jack")
        c.request("add view front width=640 height=480 eye=0.3,1.1,3 target=0,1,0 fovy=45")
        for seg, (a, b) in HUMAN_SEGMENTS.items():
            pa = c.request(f"get site jack {a}")["position"]
            pb = c.request(f"get site jack {b}")["position"]
            centre = [(x + y) / 2 for x, y in zip(pa, pb)]
            px, py = project(eye, target, fovy, w, h, centre)
            got = c.request(f"pick front {px!r} {py!r}")
            hit = got["hit"]
            assert hit is not None, seg
            assert hit["segment"] == seg
            assert hit["name"] == "jack"
            assert hit["site"].split(".")[0] == seg
            # the point lies on the ray, between the eye and the segment's centre
            p = [o + hit["distance"] * d for o, d in zip(got["origin"], got["direction"])]
            assert hit["point"] == pytest.approx(p, abs=1e-9)
            to_centre = math.dist(eye, centre)
            assert 0 < hit["distance"] < to_centre
            # the outward normal of a face the ray enters: unit, against the ray
            assert math.sqrt(dot(hit["normal"], hit["normal"])) == pytest.approx(1, abs=1e-9)
            assert dot(hit["normal"], got["direction"]) < 0
            assert len(hit["edge"]) == 2 and hit["vertex"] in hit["edge"] + [hit["vertex"]]


def test_sky_and_floor_level_misses(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        c.request("add view front width=320 height=240 eye=0,1.2,3 target=0,1,0")
        for px, py in ((0, 0), (320, 0), (160, 0.5), (5, 120)):
            got = c.request(f"pick front {px} {py}")
            assert got["hit"] is None, (px, py)
        # without figures every ray misses
        c.request("unload figure jack")
        assert c.request("pick front 160 120")["hit"] is None


def test_bad_arguments_change_nothing(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        c.request("add view front width=320 height=240 eye=0,1.2,3 target=0,1,0 fovy=35")
        before = snapshot(c), c.request("list views")
        for line, code in (("pick back 1 1", "not-found"),
                           ("pick front 321 1", "bad-argument"),
                           ("pick front 1 -1", "bad-argument"),
                           ("pick front inf 1", "bad-number"),
                           ("pick front 1 2cm", "bad-number"),
                           ("pick front 1", "arity"),
                           ("pick front 1 2 3", "arity"),
                           ("add view side fovy=0.5", "bad-number"),
                           ("add view side fovy=nan", "bad-number"),
                           ("set camera front fovy=200", "bad-number"),
                           ("set camera front eye=1,1,1 fovy=20", "arity")):
            reply = c.request_reply(line)
            assert not reply["ok"] and reply["error"]["code"] == code, (line, reply)
        assert (snapshot(c), c.request("list views")) == before


def test_fovy_survives_restart_and_sessions(daemon):
    with daemon.client() as c:
        c.request("add view a width=320 height=240 fovy=27.25")
        c.request("add view b width=320 height=240")
        c.request("set camera b fovy=61")
        c.request("save session s.ses")
    daemon.kill9()
    daemon.start()
    with daemon.client() as c:
        views = {v["name"]: v["fovy"] for v in c.request("list views")["views"]}
        assert views == {"a": 27.25, "b": 61}
        # a session written before views had a field of view: the default, 40 degrees
        text = (daemon.state_dir / "s.ses").read_text()
        assert " fovy=27.25" in text
        old = "\n".join(line.split(" fovy=")[0] for line in text.split("\n"))
        (daemon.state_dir / "old.ses").write_text(old)
        c.request("load session old.ses")
        views = {v["name"]: v["fovy"] for v in c.request("list views")["views"]}
        assert views == {"a": 40, "b": 40}
        c.request("load session s.ses")
        views = {v["name"]: v["fovy"] for v in c.request("list views")["views"]}
        assert views == {"a": 27.25, "b": 61}
