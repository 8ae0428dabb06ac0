"""The loads on the body drawn as arrows (`set view VIEW loads=on|off`, on by default).

- The pictures: with the right arm out to the side, a 15 kg weight at the right palm is a
  magenta arrow straight down from the palm, 2 mm a newton long (15 x 9.80665 N: 29 cm);
  a 200 N pull at the left palm a magenta arrow out along the pull (40 cm). Where each
  arrow must be is worked out here from the view's camera (a pinhole aimed at the target,
  the view's vertical field of view) and the palms' positions; pixels along it are
  magenta, and `pick` (rays on the figures' meshes, not the renderer) finds no body
  there. Each arrow's label (its size) is drawn past its tip. Off, those pixels are the
  background's, and the picture is the one without loads, pixel for pixel.
- `set view` takes loads=on|off and refuses anything else, changing nothing; `list views`
  tells; undo takes it back; a session keeps it (a view with its loads shown is written as
  before).
"""
import base64
import colorsys
import math

import numpy as np

from daemon import daemon, daemon_factory, write_picture  # noqa: F401 (fixtures)
from test_assess_tint import decode_png

W, H = 480, 400
EYE, TARGET, FOVY = (0.0, 1.2, 4.0), (0.0, 1.0, 0.0), 40.0
VIEW = (f"add view main width={W} height={H} eye={','.join(map(str, EYE))} "
        f"target={','.join(map(str, TARGET))} fovy={FOVY}")
M_PER_N = 0.002
BAND = 2 * 20  # the message and status lines at the bottom (their text changes)
G = 9.80665


def project(p):
    """pixel (x, y) of world point p: a pinhole at EYE looking at TARGET, x horizontal"""
    z = np.subtract(EYE, TARGET)
    z /= np.linalg.norm(z)
    x = np.array([z[2], 0.0, -z[0]])
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    d = np.subtract(p, EYE)
    pc = (d @ x, d @ y, d @ z)
    f = 1 / math.tan(math.radians(FOVY) / 2)
    nx, ny = f * H / W * pc[0] / -pc[2], f * pc[1] / -pc[2]
    return (nx + 1) / 2 * W, (1 - ny) / 2 * H


def picture(c, name=None):
    if name:
        return decode_png(write_picture(c, "main", name))
    return decode_png(base64.b64decode(c.request("render view main")["png"]))


def magenta(rgb):
    h, s, v = colorsys.rgb_to_hsv(*(float(x) / 255 for x in rgb))
    return s > 0.4 and v > 0.25 and 290 <= h * 360 <= 325  # the loads' (200, 40, 180): 307


def count_magenta(img):
    """the magenta pixels above the message and status lines"""
    rgb = img[:-BAND, :, :3].reshape(-1, 3)
    return sum(magenta(p) for p in rgb)


def arrow_pixels(c, start, direction, length):
    """pixels at 45 %, 60 % and 75 % of an arrow's shaft, clear of the hand (its head is
    the last 6 cm)"""
    out = []
    for t in (0.45, 0.6, 0.75):
        p = [start[i] + t * length * direction[i] for i in range(3)]
        x, y = project(p)
        out.append((int(x), int(y)))
    return out


def arm_out(c):
    c.request("load human as jack")
    c.request(VIEW)
    c.request("set joint jack shoulder_r 0 90deg 0")
    c.request("set joint jack shoulder_l 0 90deg 0")
    right = c.request("get site jack hand_r.palm")["position"]
    left = c.request("get site jack hand_l.palm")["position"]
    assert right[1] > 1.2 and left[1] > 1.2, (right, left)  # both arms out sideways
    return right, left


def test_a_weight_and_a_pull_are_arrows_where_they_act(daemon):
    with daemon.client() as c:
        right, left = arm_out(c)
        bare = picture(c)
        c.request("add load jack hand_r.palm mass=15 as box")
        c.request("add load jack hand_l.palm force=200,0,0 as pull")
        img = picture(c, "load-arrows.png")
        checks = [(right, (0, -1, 0), 15 * G * M_PER_N), (left, (1, 0, 0), 200 * M_PER_N)]
        for start, d, length in checks:
            for x, y in arrow_pixels(c, start, d, length):
                assert magenta(img[y, x, :3]), (start, d, x, y, img[y, x, :3])
                assert not magenta(bare[y, x, :3])
                assert c.request(f"pick main {x + 0.5} {y + 0.5}")["hit"] is None
            # the label beyond the tip: magenta text where the background was
            tip = [start[i] + (length + 0.04) * d[i] for i in range(3)]
            x, y = project(tip)
            box = img[int(y) - 14:int(y) + 10, int(x) - 30:int(x) + 30, :3].reshape(-1, 3)
            assert sum(magenta(p) for p in box) >= 10, (start, x, y)
        # off: no magenta anywhere, and where the arrows were the bare picture's pixels
        # (elsewhere the balance icon moved: the weight moved the centre of mass)
        c.request("set view main loads=off")
        off = picture(c)
        assert count_magenta(bare) == 0 and count_magenta(off) == 0
        assert count_magenta(img) > 100
        for start, d, length in checks:
            for x, y in arrow_pixels(c, start, d, length):
                assert np.array_equal(off[y, x], bare[y, x])


def views(c):
    return {v["name"]: v["loads"] for v in c.request("list views")["views"]}


def test_set_view_loads_is_checked_undone_and_kept_in_sessions(daemon):
    with daemon.client() as c:
        c.request(VIEW)
        c.request("add view side width=320 height=240 eye=3,1.2,0 target=0,0.95,0")
        assert views(c) == {"main": "on", "side": "on"}
        assert c.request("set view side loads=off") == {"view": "side", "tint": "off",
                                                         "loads": "off"}
        for line, code in (("set view side loads=maybe", "bad-argument"),
                           ("set view side loads=", "bad-argument"),
                           ("set view side arrows=on", "bad-argument"),
                           ("set view nowhere loads=on", "not-found")):
            reply = c.request_reply(line)
            assert not reply["ok"] and reply["error"]["code"] == code, (line, reply)
            assert views(c) == {"main": "on", "side": "off"}, line
        c.request("undo")
        assert views(c) == {"main": "on", "side": "on"}
        c.request("redo")
        c.request("save session s.ses")
        text = (daemon.state_dir / "s.ses").read_text()
        lines = {ln.split()[1]: ln for ln in text.splitlines() if ln.startswith("view ")}
        assert "loads=" not in lines["main"] and lines["side"].endswith(" loads=off"), lines
        c.request("set view side loads=on tint=rula")
        assert c.request("list views")["views"][1]["tint"] == "rula"
        c.request("load session s.ses")
        assert views(c) == {"main": "on", "side": "off"}
    daemon.restart()
    with daemon.client() as c:
        assert views(c) == {"main": "on", "side": "off"}
