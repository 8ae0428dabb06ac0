"""A view's tint (`set view VIEW tint=rula|reba|owas|off`).

- `set view` takes a method or off, refuses anything else and changes nothing then;
  `list views` says each view's tint; the tint is a change of the environment (undo
  takes it back) and a session keeps it (a view without one is written as before, so
  sessions of untinted views read by older daemons too).
- The pictures: with the right arm raised to 110 deg of flexion and the rest of the body
  neutral, a RULA tint draws the right upper arm yellow (upper arm 4 alone: Table A 4,
  Table C 3, action level 2), the rest of the scored side and the trunk, head and legs
  green (each alone at score 1 or 2 stays at level 1), and the unscored left arm grey;
  which pixel shows which segment is asked of `pick` (ray casting on the figure's meshes,
  not the renderer). REBA's upper arm 4 alone (Table B 4, Table C 2: level 1) is yellow
  too. The key in the corner shows the four colours in order. Switched off, the picture
  is the untinted one again, pixel for pixel.
"""
import colorsys
import struct
import zlib

import numpy as np

from daemon import daemon, daemon_factory  # noqa: F401 (fixtures)

VIEW = "add view main width=320 height=240 eye=1.9,1.55,3.1 target=0,0.95,0"


def tints(c):
    return {v["name"]: v["tint"] for v in c.request("list views")["views"]}


def test_set_view_tint_takes_each_method_and_off(daemon):
    with daemon.client() as c:
        c.request(VIEW)
        assert tints(c) == {"main": "off"}
        for t in ("rula", "reba", "owas", "off"):
            assert c.request(f"set view main tint={t}") == {"view": "main", "tint": t, "loads": "on"}
            assert tints(c) == {"main": t}


def test_bad_tint_requests_are_refused_and_change_nothing(daemon):
    with daemon.client() as c:
        c.request(VIEW)
        c.request("set view main tint=reba")
        for line, code in (("set view main tint=niosh", "bad-argument"),
                           ("set view main tint=", "bad-argument"),
                           ("set view main colour=rula", "bad-argument"),
                           ("set view nowhere tint=rula", "not-found"),
                           ("set view main", "arity")):
            reply = c.request_reply(line)
            assert not reply["ok"] and reply["error"]["code"] == code, (line, reply)
            assert tints(c) == {"main": "reba"}, line


def test_tint_is_undone_and_redone(daemon):
    with daemon.client() as c:
        c.request(VIEW)
        c.request("set view main tint=owas")
        c.request("undo")
        assert tints(c) == {"main": "off"}
        c.request("redo")
        assert tints(c) == {"main": "owas"}


def test_a_session_keeps_the_tint_and_an_untinted_view_is_written_as_before(daemon):
    with daemon.client() as c:
        c.request(VIEW)
        c.request("add view side width=320 height=240 eye=3,1.2,0 target=0,0.95,0")
        c.request("set view side tint=rula")
        c.request("save session s.ses")
        text = (daemon.state_dir / "s.ses").read_text()
        lines = {ln.split()[1]: ln for ln in text.splitlines() if ln.startswith("view ")}
        assert "tint=" not in lines["main"] and lines["side"].endswith(" tint=rula"), lines
        c.request("set view side tint=off")
        c.request("load session s.ses")
        assert tints(c) == {"main": "off", "side": "rula"}
    daemon.restart()  # the journal's snapshot and records keep it too
    with daemon.client() as c:
        assert tints(c) == {"main": "off", "side": "rula"}


def test_a_session_with_a_bad_tint_is_refused_whole(daemon):
    with daemon.client() as c:
        c.request(VIEW)
        c.request("save session s.ses")
        path = daemon.state_dir / "s.ses"
        path.write_text(path.read_text().replace(" fovy=", " tint=purple fovy="))
        reply = c.request_reply("load session s.ses")
        assert not reply["ok"] and "tint" in reply["error"]["message"], reply
        assert tints(c) == {"main": "off"}


# ---- the pictures --------------------------------------------------------------

W, H = 360, 440
FRONT = f"add view front width={W} height={H} eye=0.35,1.15,3.0 target=0,1.0,0 fovy=40"
BAND = 2 * 20  # the message and status lines at the bottom (their text changes)
KEY = 26       # the key's band at the top


def decode_png(data):
    """An 8-bit RGBA non-interlaced PNG (what the daemon writes) as an h x w x 4 array."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, ihdr = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    w, h, depth, colour, _, _, interlace = ihdr
    assert (depth, colour, interlace) == (8, 6, 0), ihdr
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(h, 1 + 4 * w)
    out = np.zeros((h, w, 4), dtype=np.uint8)
    for y in range(h):
        f, line = raw[y, 0], raw[y, 1:].reshape(w, 4).astype(np.int64)
        up = out[y - 1].astype(np.int64) if y else np.zeros((w, 4), dtype=np.int64)
        if f == 0:
            out[y] = line
        elif f == 1:  # sub: each pixel adds the one to its left
            out[y] = np.cumsum(line, axis=0) & 0xFF
        elif f == 2:
            out[y] = (line + up) & 0xFF
        else:
            raise AssertionError(f"filter {f}: the daemon writes sub rows")
    return out


def picture(c):
    import base64
    got = c.request("render view front")
    return decode_png(base64.b64decode(got["png"]))


def segment_colours(c, img, step=6):
    """{segment: median RGB of the pixels pick says show it} over a grid of the scene's pixels."""
    seen = {}
    for y in range(KEY + step, H - BAND, step):
        for x in range(step // 2, W, step):
            hit = c.request(f"pick front {x + 0.5} {y + 0.5}")["hit"]
            if hit and hit["name"] == "jack":
                seen.setdefault(hit["segment"], []).append(img[y, x, :3])
    return {k: np.median(np.array(v), axis=0) for k, v in seen.items() if len(v) >= 3}


def hue_class(rgb):
    """grey, or the nearest of the four tint hues (yellow 52, green 131, orange 29, red 1 deg)
    and the shirt's blue (216 deg)"""
    h, s, v = colorsys.rgb_to_hsv(*(float(x) / 255 for x in rgb))
    if s < 0.25:
        return "grey"
    deg = h * 360
    hues = {"red": 1, "orange": 29, "yellow": 52, "green": 131, "blue": 216}
    return min(hues, key=lambda k: min(abs(deg - hues[k]), 360 - abs(deg - hues[k])))


def raised_arm(c):
    c.request("load human as jack")
    c.request(FRONT)
    c.request("set joint jack shoulder_r 110deg 0 0")


ARM_R = ("clavicle_r", "upperarm_r")
ARM_L = ("clavicle_l", "upperarm_l", "forearm_l", "hand_l")
GREEN = ("forearm_r", "hand_r", "pelvis", "T6", "head", "thigh_l", "thigh_r", "shank_l",
         "shank_r")


def test_rula_tint_shows_the_raised_arm_yellow_the_rest_green_the_other_arm_grey(daemon):
    with daemon.client() as c:
        raised_arm(c)
        rula = c.request("assess rula jack")
        assert rula["side"] == "right" and rula["parts"]["upper_arm"]["score"] == 4, rula
        c.request("set view front tint=rula")
        colours = segment_colours(c, picture(c))
    classes = {k: hue_class(v) for k, v in colours.items()}
    for seg in ("upperarm_r",):
        assert classes.get(seg) == "yellow", (seg, colours.get(seg), classes)
    for seg in GREEN:
        assert classes.get(seg) == "green", (seg, colours.get(seg), classes)
    for seg in ("upperarm_l", "forearm_l"):
        assert classes.get(seg) == "grey", (seg, colours.get(seg), classes)


def test_reba_tint_shows_the_raised_arm_yellow_too(daemon):
    with daemon.client() as c:
        raised_arm(c)
        assert c.request("assess reba jack")["parts"]["upper_arm"]["score"] == 4
        c.request("set view front tint=reba")
        colours = segment_colours(c, picture(c), step=8)
    classes = {k: hue_class(v) for k, v in colours.items()}
    assert classes.get("upperarm_r") == "yellow", classes
    assert classes.get("pelvis") == "green" and classes.get("forearm_r") == "green", classes


def test_the_key_shows_the_four_colours_in_order(daemon):
    with daemon.client() as c:
        raised_arm(c)
        c.request("set view front tint=owas")
        img = picture(c)
    row = img[14, :, :3].astype(int)  # the key's middle row
    want = {"green": (41, 168, 61), "yellow": (237, 204, 26), "orange": (242, 120, 18),
            "red": (214, 28, 26)}
    first = {}
    for name, rgb in want.items():
        xs = [x for x in range(row.shape[0]) if np.abs(row[x] - rgb).max() <= 2]
        assert len(xs) >= 8, (name, rgb)  # a swatch 12 px wide
        first[name] = xs[0]
    assert first["green"] < first["yellow"] < first["orange"] < first["red"], first


def test_tint_off_gives_back_the_untinted_picture_pixel_for_pixel(daemon):
    with daemon.client() as c:
        raised_arm(c)
        before = picture(c)
        untinted = {k: hue_class(v) for k, v in segment_colours(c, before, step=8).items()}
        c.request("set view front tint=rula")
        tinted = picture(c)
        c.request("set view front tint=off")
        after = picture(c)
    # the untinted picture is the figure's own: its shirt blue on both arms
    assert untinted.get("upperarm_r") == "blue" and untinted.get("upperarm_l") == "blue", untinted
    scene = slice(KEY, H - BAND)  # below the key; the status line's frame count changes
    assert (tinted[scene] != before[scene]).any(), "the tint changed nothing"
    whole = slice(0, H - BAND)
    assert np.array_equal(after[whole], before[whole])
