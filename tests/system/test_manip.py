"""The manipulation operator through the daemon: `manipulate figure` starts the
mode, `input` lines drive it as a mouse does, ESC ends it, `get manip` says where G is.
The expected positions are Appendix B's geometry computed here in Python from the mouse
lines the daemon's `pick` gives (the mouse line itself is checked against PyGLM in
test_pick.py)."""
import math
import time

import pytest

from daemon import daemon, daemon_factory, snapshot, write_picture  # noqa: F401 (fixtures)


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def nearest_on_axis(p0, u, o, d):
    """the parameter s of the point p0 + s u of the axis nearest the line o + t d"""
    w = sub(p0, o)
    a, b, c = dot(u, u), dot(u, d), dot(d, d)
    dd, e = dot(u, w), dot(d, w)
    den = a * c - b * b
    return (b * e - c * dd) / den


def ray(c, view, x, y):
    r = c.request(f"pick {view} {x} {y}")
    return r["origin"], r["direction"]


def setup(c, eye="0,1,3", target="0,1,0"):
    c.request("load human as human")
    c.request(f"add view front width=320 height=240 eye={eye} target={target}")


def test_a_drag_along_x_follows_the_nearest_point_and_moves_the_figure(daemon):
    with daemon.client() as c:
        setup(c)
        assert c.request("get manip")["mode"] == "none"
        assert c.request("manipulate figure human view=front") == {"mode": "figure",
                                                                   "view": "front"}
        g0 = c.request("get manip")
        assert g0["mode"] == "figure" and g0["view"] == "front" and g0["state"] == "idle"
        p0 = g0["position"]
        # press at one pixel, drag to another: G follows the change of the nearest point
        c.request("input pointer front 100 150")
        c.request("input button left down")
        pressed = c.request("get manip")
        assert pressed["position"] == pytest.approx(p0, abs=1e-12)  # a press never moves G
        assert pressed["axis"] == "x" and pressed["state"] == "linear"
        c.request("input pointer front 220 90")
        moved = c.request("get manip")
        o1, d1 = ray(c, "front", 100, 150)
        o2, d2 = ray(c, "front", 220, 90)
        x = [1, 0, 0]
        want = nearest_on_axis(p0, x, o2, d2) - nearest_on_axis(p0, x, o1, d1)
        assert moved["position"][0] == pytest.approx(p0[0] + want, abs=1e-9)
        assert moved["position"][1:] == pytest.approx(p0[1:], abs=1e-12)
        assert abs(want) > 0.1
        write_picture(c, "front", "manip_figure_linear.png")
        # the figure's root went with G
        root = c.request("show figure human")["root"]
        site = c.request(f"get site human {root}")
        assert site["position"] == pytest.approx(moved["position"], abs=1e-9)
        c.request("input button left up")
        c.request("input key KEY_ESC down")
        c.request("input key KEY_ESC up")
        assert c.request("get manip")["mode"] == "none"
        # the figure stays where the drag left it
        site = c.request(f"get site human {root}")
        assert site["position"] == pytest.approx(moved["position"], abs=1e-9)


def test_two_buttons_move_in_their_plane_and_three_do_nothing(daemon):
    with daemon.client() as c:
        setup(c)
        c.request("manipulate figure human")
        p0 = c.request("get manip")["position"]
        c.request("input pointer front 160 120")
        c.request("input button left down")
        c.request("input button middle down")  # x and y: the xy plane, normal z
        g = c.request("get manip")
        assert g["state"] == "planar" and g["axis"] == "xy"
        c.request("input pointer front 200 100")
        o1, d1 = ray(c, "front", 160, 120)
        o2, d2 = ray(c, "front", 200, 100)

        def hit(o, d):  # the mouse line through the plane z = p0.z
            t = (p0[2] - o[2]) / d[2]
            return [o[i] + t * d[i] for i in range(3)]
        want = sub(hit(o2, d2), hit(o1, d1))
        got = sub(c.request("get manip")["position"], p0)
        assert got == pytest.approx(want, abs=1e-9)
        c.request("input button right down")  # three buttons: nothing
        g3 = c.request("get manip")
        c.request("input pointer front 10 10")
        assert c.request("get manip")["position"] == g3["position"]
        assert c.request("get manip")["state"] == "none"


def test_control_rotates_about_the_axis_keeping_the_origin(daemon):
    with daemon.client() as c:
        setup(c, eye="0,4,0.5", target="0,0,0")  # from above: the wheel about y faces us
        c.request("manipulate figure human")
        g0 = c.request("get manip")
        c.request("input key KEY_LEFTCTRL down")
        c.request("input pointer front 220 120")
        c.request("input button middle down")
        assert c.request("get manip")["state"] == "rotate"
        c.request("input pointer front 160 40")
        g = c.request("get manip")
        assert g["position"] == pytest.approx(g0["position"], abs=1e-12)
        # the turn is about y: y's row and column unchanged, the rotation orthonormal
        r = g["rotation"]
        r0 = g0["rotation"]
        for i in range(3):
            assert dot(r[i], r[i]) == pytest.approx(1, abs=1e-12)
        cos_turn = dot([r[0][0], r[1][0], r[2][0]], [r0[0][0], r0[1][0], r0[2][0]])
        assert cos_turn < math.cos(math.radians(10))  # it turned visibly


def test_the_20_degree_rule_refuses_an_axis_along_the_line_of_sight(daemon):
    with daemon.client() as c:
        setup(c, eye="0.05,6,0.05", target="0,0,0")  # straight down: y is the line of sight
        c.request("manipulate figure human")
        p0 = c.request("get manip")["position"]
        c.request("input button middle down")
        g = c.request("get manip")
        assert g["state"] == "refused"
        assert g["message"] == "can't translate along that axis from this view"
        c.request("input pointer front 10 10")
        assert c.request("get manip")["position"] == pytest.approx(p0, abs=1e-12)


def test_bad_lines_are_refused_and_change_nothing(daemon):
    with daemon.client() as c:
        c.request("load human as human")
        assert c.request_reply("manipulate figure human")["error"]["code"] == "not-found"  # no view yet
        c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
        assert c.request_reply("manipulate figure nobody")["error"]["code"] == "not-found"
        assert c.request_reply("manipulate figure human view=back")["error"]["code"] == "not-found"
        assert c.request_reply("manipulate figure human speed=3")["error"]["code"] == "bad-argument"
        assert c.request("get manip")["mode"] == "none"


def png_pixels(data):
    """(width, height, rows of (r, g, b)) of an 8-bit RGB or RGBA, non-interlaced PNG"""
    import struct
    import zlib
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and color in (2, 6) and interlace == 0
            bpp = 3 if color == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * bpp:x * bpp + 3]) for x in range(w)])
        prev = line
    return w, h, rows


def test_the_icons_show_as_soon_as_the_chord_changes(daemon):
    """§3.6: G's frame, the arrow of the chosen axis and the pointer are drawn in the mode's
    view as soon as a button goes down, before any motion; ESC takes them away. The
    pictures go to the test output."""
    import base64
    import os
    out = os.path.join(os.environ.get("POSTURE_BUILD", "build/rel"), "test-output")
    os.makedirs(out, exist_ok=True)
    with daemon.client() as c:
        c.request("load human as human")
        c.request("add view front width=320 height=240 eye=0.8,1.2,2.5 target=0,0.7,0")
        c.request("manipulate figure human")
        c.request("input button left down")
        with_icons = base64.b64decode(c.request("render view front")["png"])
        c.request("input button left up")
        c.request("input key KEY_ESC down")
        plain = base64.b64decode(c.request("render view front")["png"])
    for name, data in (("manip_icons.png", with_icons), ("manip_plain.png", plain)):
        with open(os.path.join(out, name), "wb") as f:
            f.write(data)
    w, h, a = png_pixels(with_icons)
    _, _, b = png_pixels(plain)
    changed = [a[y][x] for y in range(h) for x in range(w) if a[y][x] != b[y][x]]
    assert len(changed) > 200, len(changed)

    def strong(px, i):  # one channel well above the other two
        return px[i] > 150 and all(px[i] > px[j] + 60 for j in range(3) if j != i)
    assert any(strong(p, 0) for p in changed), "no red x axis"
    assert any(strong(p, 1) for p in changed), "no green y axis"
    assert any(strong(p, 2) for p in changed), "no blue z axis"


def site_pos(c, name):
    return c.request(f"get site human {name}")["position"]


def test_dragging_a_hand_the_solver_follows_g_and_esc_ends_it(daemon):
    """§4.6.1: G is the goal of a constraint on the site; the solver brings the hand to G
    frame by frame; §4.6.2: when the button comes up G takes the hand's orientation; ESC
    deletes the constraint and the posture stays."""
    with daemon.client() as c:
        setup(c)
        start = site_pos(c, "hand_r.palm")
        reply = c.request("drag human hand_r.palm start=shoulder_r view=front")
        assert reply["mode"] == "drag" and reply["view"] == "front"
        g = c.request("get manip")
        assert g["mode"] == "drag" and g["position"] == pytest.approx(start, abs=1e-12)
        assert [x["name"] for x in c.request("list constraints human")["constraints"]] == ["drag"]
        # drag along x, 5 cm outwards from the hand's side (the view looks along -z)
        o, d = ray(c, "front", 160, 120)
        c.request("input pointer front 160 120")
        c.request("input button left down")
        s0 = nearest_on_axis(start, [1, 0, 0], o, d)
        target_x = start[0] - 0.05  # the right hand is on -x; outwards, within reach
        # the pixel whose mouse line is nearest the axis at target_x: search the row
        best = min(range(0, 321), key=lambda px: abs(
            nearest_on_axis(start, [1, 0, 0], *ray(c, "front", px, 120)) - s0 - (target_x - start[0])))
        c.request(f"input pointer front {best} 120")
        g = c.request("get manip")
        assert g["position"][0] == pytest.approx(target_x, abs=0.01)
        c.request("settle frames=60")
        write_picture(c, "front", "manip_drag_hand.png")
        hand = site_pos(c, "hand_r.palm")
        assert math.dist(hand, g["position"]) < 0.002, (hand, g["position"])
        c.request("input button left up")
        after_up = c.request("get manip")
        assert after_up["position"] == pytest.approx(g["position"], abs=1e-12)
        c.request("input key KEY_ESC down")
        assert c.request("get manip")["mode"] == "none"
        assert c.request("list constraints human")["constraints"] == []
        c.request("settle frames=10")
        assert site_pos(c, "hand_r.palm") == pytest.approx(hand, abs=1e-3)


def test_a_drag_survives_a_restart_as_its_journal_says(daemon):
    """The drag command is journaled, and so is the end of the drag (the constraint's
    deletion): a restart after ESC has no drag constraint and the dragged posture."""
    with daemon.client() as c:
        setup(c)
        c.request("drag human hand_r.palm start=shoulder_r")
        c.request("input pointer front 160 120")
        c.request("input button left down")
        c.request("input pointer front 120 120")
        c.request("settle frames=30")
        c.request("input button left up")
        c.request("input key KEY_ESC down")
        hand = site_pos(c, "hand_r.palm")
        assert c.request("list constraints human")["constraints"] == []
    daemon.kill9()
    daemon.start()
    with daemon.client() as c:
        assert c.request("list constraints human")["constraints"] == []
        assert site_pos(c, "hand_r.palm") == pytest.approx(hand, abs=1e-6)
        assert c.request("get manip")["mode"] == "none"


def spoke_angle(axis, s0, s1):
    """the signed angle turning s0 into s1 about axis (right hand), both projected"""
    def proj(s):
        k = dot(s, axis)
        return [s[i] - k * axis[i] for i in range(3)]
    a, b = proj(s0), proj(s1)
    cross = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    return math.atan2(dot(cross, axis), dot(a, b))


def crank_elbow(c, pixels):
    """manipulate joint elbow_r from the side, left button, the pointer through pixels;
    returns (pivot, the elbow's value before and after)"""
    c.request("manipulate joint human elbow_r view=side")
    pivot = c.request("get manip")["position"]
    before = c.request("get joint human elbow_r")["values"][0]
    c.request(f"input pointer side {pixels[0][0]} {pixels[0][1]}")
    c.request("input button left down")
    assert c.request("get joint human elbow_r")["values"][0] == before  # a press moves nothing
    assert c.request("get manip")["axis"] == "dof0"
    for x, y in pixels[1:]:
        c.request(f"input pointer side {x} {y}")
    after = c.request("get joint human elbow_r")["values"][0]
    write_picture(c, "side", "manip_joint_elbow.png")
    c.request("input button left up")
    c.request("input key KEY_ESC down")
    return pivot, before, after


def test_a_joint_turns_by_the_spoke_angle_and_stops_at_its_limits(daemon):
    """§3.8: the left button turns the elbow's one DOF (R(-x)) by the angle between the
    first and the current spoke in the wheel's plane (through the pivot, normal -x at rest,
    so seen from +x the wheel faces the camera); cranked on, it stops at its limit."""
    with daemon.client() as c:
        c.request("load human as human")
        c.request("add view side width=320 height=240 eye=3,1.1,0 target=0,1.1,0")
        path = [(150, 150), (140, 160), (130, 165)]
        pivot, before, after = crank_elbow(c, path)
        o0, d0 = ray(c, "side", *path[0])
        o1, d1 = ray(c, "side", *path[-1])

        def on_plane(o, d):  # the wheel's plane: x = pivot.x
            t = (pivot[0] - o[0]) / d[0]
            return [o[i] + t * d[i] - pivot[i] for i in range(3)]
        want = spoke_angle([-1, 0, 0], on_plane(o0, d0), on_plane(o1, d1))
        assert abs(want) > 0.05
        lo, hi = 0.0, 2.6179938779914944
        assert after == pytest.approx(min(max(before + want, lo), hi), abs=1e-9)
        # cranked far the other way: the limit, exactly
        circle = [(int(160 + 60 * math.cos(t / 10)), int(120 + 60 * math.sin(t / 10)))
                  for t in range(0, 120, 2)]
        _, _, a1 = crank_elbow(c, circle)
        _, _, a2 = crank_elbow(c, circle[::-1])
        assert sorted([a1, a2]) == [lo, hi]


def test_a_joint_pointing_up_the_rooting_moves_as_defined(daemon):
    """Rooted at the hand, the elbow points up the rooting: the same crank still changes its
    value the same way (the axis and the angle are both negated)."""
    path = [(150, 150), (140, 160), (130, 165)]
    with daemon.client() as c:
        c.request("load human as human")
        c.request("add view side width=320 height=240 eye=3,1.1,0 target=0,1.1,0")
        _, b1, a1 = crank_elbow(c, path)
        c.request("set joint human elbow_r 0")
        c.request("set root human hand_r.palm")
        _, b2, a2 = crank_elbow(c, path)
    assert b1 == b2 == 0
    assert a1 == pytest.approx(a2, abs=1e-9) and a1 > 0.05


def test_choosing_a_refused_axis_again_turns_the_view_until_it_is_clear(daemon):
    """§3.7: the same axis chosen again after the warning turns the camera about the
    object's origin, eased over about a second, until the line of sight is 20 degrees clear;
    then the held button moves G. The new view is journaled."""
    import time
    with daemon.client() as c:
        setup(c, eye="0.05,6,0.05", target="0,0,0")  # looking down y
        c.request("manipulate figure human")
        g = c.request("get manip")["position"]
        c.request("input button middle down")
        assert c.request("get manip")["state"] == "refused"
        c.request("input button middle up")
        before = next(v for v in c.request("list views")["views"] if v["name"] == "front")
        t0 = time.monotonic()
        c.request("input button middle down")  # again: the adjustment
        def front():
            return next(v for v in c.request("list views")["views"] if v["name"] == "front")
        # the adjustment ends focused on G's origin; the operator is free as soon as it is clear
        while time.monotonic() - t0 < 3 and front()["target"] != pytest.approx(g, abs=1e-6):
            time.sleep(0.02)
        took = time.monotonic() - t0
        assert c.request("get manip")["state"] == "linear" and 0.8 < took < 2.5, took
        v = next(v for v in c.request("list views")["views"] if v["name"] == "front")
        sight = [g[i] - v["eye"][i] for i in range(3)]
        n = math.sqrt(dot(sight, sight))
        angle = math.degrees(math.acos(abs(sight[1]) / n))
        assert 20 <= angle < 23, angle  # clear, by the least turn (and a degree's margin)
        assert v["target"] == pytest.approx(g, abs=1e-6)  # focused on G's origin
        d0 = math.dist(before["eye"], g)
        assert math.dist(v["eye"], g) == pytest.approx(d0, abs=1e-6)
    daemon.kill9()
    daemon.start()
    with daemon.client() as c:
        kept = next(x for x in c.request("list views")["views"] if x["name"] == "front")
        assert kept["eye"] == pytest.approx(v["eye"], abs=1e-9)


def test_a_mode_starting_off_screen_turns_the_view_to_g(daemon):
    """§3.7: a command whose object's origin is not visible turns the view to it first."""
    import time
    with daemon.client() as c:
        setup(c, eye="0,1,3", target="6,1,0")  # looking well to the right of the figure
        c.request("manipulate figure human")
        g = c.request("get manip")["position"]
        t0 = time.monotonic()
        while time.monotonic() - t0 < 3:
            v = next(v for v in c.request("list views")["views"] if v["name"] == "front")
            if v["target"] == pytest.approx(g, abs=1e-6):
                break
            time.sleep(0.02)
        assert v["target"] == pytest.approx(g, abs=1e-6) and v["eye"] == pytest.approx([0, 1, 3])
        assert 0.8 < time.monotonic() - t0 < 2.5


def wait_view(c, name, pred, limit=3):
    import time
    t0 = time.monotonic()
    while time.monotonic() - t0 < limit:
        v = next(v for v in c.request("list views")["views"] if v["name"] == name)
        if pred(v):
            return v
        time.sleep(0.02)
    return v


def angle_to_plane(eye, g, normal):
    """degrees between the line of sight from eye to g and the plane with this unit normal"""
    sight = sub(g, eye)
    return math.degrees(math.asin(abs(dot(sight, normal)) / math.sqrt(dot(sight, sight))))


def test_choosing_a_refused_plane_again_turns_the_view_as_an_axis_does(daemon):
    """§3.7's second try for a two-button plane: the buttons go down one after the other, so
    the chord passes through a one-button axis that is not refused (x here); that passing
    state is not a choice, and the second planar try turns the camera as a second axis or
    wheel does. From (3, 1.6, 4) the line of sight to G is about 7.7 degrees from the
    horizontal xz plane, which is refused."""
    with daemon.client() as c:
        setup(c, eye="3,1.6,4", target="0,1,0")
        c.request("manipulate figure human")
        g = c.request("get manip")["position"]
        before = next(v for v in c.request("list views")["views"] if v["name"] == "front")
        assert angle_to_plane(before["eye"], g, [0, 1, 0]) < 20

        def planar_try():
            c.request("input pointer front 160 120")
            c.request("input button left down")
            assert c.request("get manip")["state"] == "linear"  # x on the way: not refused
            c.request("input button right down")

        # the first try: the warning, and neither the camera nor G moves under the drag
        planar_try()
        m = c.request("get manip")
        assert m["state"] == "refused" and m["axis"] == "xz"
        assert m["message"] == "can't translate in that plane from this view"
        for x in range(165, 230, 8):
            c.request(f"input pointer front {x} 140")
        time.sleep(0.3)  # several frames: an adjustment, were one begun, would show
        assert c.request("get manip")["position"] == pytest.approx(g, abs=1e-12)
        v = next(v for v in c.request("list views")["views"] if v["name"] == "front")
        assert v["eye"] == before["eye"] and v["target"] == before["target"]
        c.request("input button left up")
        c.request("input button right up")

        # the second try: the same plane again turns the camera about G until it is clear
        planar_try()
        v = wait_view(c, "front", lambda v: v["target"] == pytest.approx(g, abs=1e-6))
        assert v["target"] == pytest.approx(g, abs=1e-6)  # focused on G's origin
        assert math.dist(v["eye"], g) == pytest.approx(math.dist(before["eye"], g), abs=1e-6)
        angle = angle_to_plane(v["eye"], g, [0, 1, 0])
        assert 20 <= angle < 23, angle  # clear by the least turn (and a degree's margin)
        m = c.request("get manip")
        assert m["state"] == "planar" and m["axis"] == "xz"

        # and the held chord now drags G in the plane y = g.y, under the pointer
        c.request("input pointer front 160 120")  # anchors in the new view
        c.request("input pointer front 200 150")
        o1, d1 = ray(c, "front", 160, 120)
        o2, d2 = ray(c, "front", 200, 150)

        def hit(o, d):  # the mouse line through the plane y = g.y
            t = (g[1] - o[1]) / d[1]
            return [o[i] + t * d[i] for i in range(3)]
        want = [g[i] + hit(o2, d2)[i] - hit(o1, d1)[i] for i in range(3)]
        got = c.request("get manip")["position"]
        assert got == pytest.approx(want, abs=1e-9)
        assert math.dist(got, g) > 0.1
        root = c.request("show figure human")["root"]
        assert c.request(f"get site human {root}")["position"] == pytest.approx(got, abs=1e-9)
        c.request("input button left up")
        c.request("input button right up")


def test_c_takes_an_automatic_view_change_back(daemon):
    """Beyond the dissertation: every automatic view change can be taken back with one key
    (C, as in change view), so a view a person set up is never lost."""
    with daemon.client() as c:
        setup(c, eye="0,1,3", target="6,1,0")  # G off screen: the view turns to it
        before = next(v for v in c.request("list views")["views"] if v["name"] == "front")
        c.request("manipulate figure human")
        g = c.request("get manip")["position"]
        wait_view(c, "front", lambda v: v["target"] == pytest.approx(g, abs=1e-6))
        c.request("input key KEY_C down")
        c.request("input key KEY_C up")
        back = next(v for v in c.request("list views")["views"] if v["name"] == "front")
        assert back["eye"] == pytest.approx(before["eye"], abs=1e-9)
        assert back["target"] == pytest.approx(before["target"], abs=1e-9)
        assert c.request("get manip")["mode"] == "figure"  # the mode goes on


def test_a_dragged_figure_near_the_edge_takes_the_view_with_it(daemon):
    """Beyond the dissertation: while dragging, G never leaves the view: near the edge of
    the picture the view follows it, eased."""
    with daemon.client() as c:
        setup(c)
        c.request("manipulate figure human")
        c.request("input pointer front 160 120")
        c.request("input button left down")
        c.request("input pointer front 318 120")  # to the right edge: G follows along x
        g = c.request("get manip")["position"]
        assert g[0] > 0.5
        v = wait_view(c, "front", lambda v: v["target"] == pytest.approx(g, abs=1e-6))
        assert v["target"] == pytest.approx(g, abs=1e-6)
        assert v["eye"] == pytest.approx([0, 1, 3], abs=1e-9)  # it turned, it did not move


def drag_x(c, dx, view="front"):
    """press left at the view's centre and move the pointer so G goes dx along x"""
    g0 = c.request("get manip")["position"]
    o, d = ray(c, view, 160, 120)
    s0 = nearest_on_axis(g0, [1, 0, 0], o, d)
    best = min(range(0, 321), key=lambda px: abs(
        nearest_on_axis(g0, [1, 0, 0], *ray(c, view, px, 120)) - s0 - dx))
    c.request(f"input pointer {view} 160 120")
    c.request("input button left down")
    c.request(f"input pointer {view} {best} 120")
    c.request("input button left up")
    return c.request("get manip")["position"]


@pytest.mark.parametrize("primitive,site", [("hand human right", "hand_r.palm"),
                                            ("foot human left", "foot_l.balance")])
def test_a_primitive_s_goal_follows_g_and_the_behaviours_respond(daemon, primitive, site):
    """Table 5.2 as interactive modes: G starts on the primitive's site and is its goal; the
    behaviours bring the site there frame by frame, the figure staying balanced."""
    with daemon.client() as c:
        setup(c)
        c.request("behave human on")
        c.request("settle frames=30")
        start = site_pos(c, site)
        reply = c.request(f"manipulate {primitive}")
        assert reply["mode"] == primitive.split()[0]
        g0 = c.request("get manip")["position"]
        dx = -0.06 if "right" in primitive else 0.08
        g = drag_x(c, dx)
        assert g[0] - g0[0] == pytest.approx(dx, abs=0.01)
        c.request("settle frames=120")
        write_picture(c, "front", f"manip_primitive_{primitive.split()[0]}.png")
        now = site_pos(c, site)  # a site of the moved limb goes as far as G
        assert (now[0] - start[0]) == pytest.approx(g[0] - g0[0], abs=0.01), (now, start, g, g0)
        assert c.request("get behavior human")["balance"]["margin"] > 0


def test_moving_the_centre_of_mass_shifts_the_balance_point(daemon):
    with daemon.client() as c:
        setup(c)
        c.request("behave human on")
        c.request("settle frames=30")
        p0 = c.request("get behavior human")["balance"]["point"]
        assert c.request("manipulate com human")["mode"] == "com"
        g0 = c.request("get manip")["position"]
        g = drag_x(c, 0.04)
        c.request("settle frames=120")
        p1 = c.request("get behavior human")["balance"]["point"]
        assert p1[0] - p0[0] == pytest.approx(g[0] - g0[0], abs=0.01)


def test_snapping_onto_what_is_under_the_pointer(daemon_factory):
    """B.4 through the daemon: in a mode, G snaps onto the feature under the pointer (on any
    other figure), checked against `pick` and `get site` on the same pixel."""
    from daemon import ROOT
    library = ["--library", str(ROOT / "src" / "figure" / "library")]
    with daemon_factory(extra=library).client() as c:
        setup(c)
        c.request("load figure lib:chair.fig as chair")
        c.request("set location chair 0.8 0 0")
        c.request("manipulate figure human")
        # the pixel of the chair's middle, from its root site's projection: search the row
        hit = None
        for x in range(200, 320, 4):
            for y in range(130, 240, 6):
                h = c.request(f"pick front {x} {y}")["hit"]
                if h and h["name"] == "chair" and h["site"]:
                    hit, px, py = h, x, y
                    break
            if hit:
                break
        assert hit, "the chair is not in view"
        c.request(f"input pointer front {px} {py}")
        g0 = c.request("get manip")["position"]
        reply = c.request("snap site_position")
        site = c.request(f"get site chair {hit['site']}")["position"]
        assert reply["position"] == pytest.approx(site, abs=1e-9)
        assert c.request("get manip")["position"] == pytest.approx(site, abs=1e-9)
        # the figure went with G
        root = c.request("show figure human")["root"]
        assert c.request(f"get site human {root}")["position"] == pytest.approx(site, abs=1e-9)
        # face plane: G dropped onto the plane of the face under the pointer, along its normal
        c.request("input pointer front %d %d" % (px, py))
        before = c.request("get manip")["position"]
        snapped = c.request("snap face_plane")["position"]
        write_picture(c, "front", "manip_snap_face_plane.png")
        n = hit["normal"]
        assert dot(sub(snapped, hit["point"]), n) == pytest.approx(0, abs=1e-9)
        moved = sub(snapped, before)
        along = dot(moved, n)
        assert [m - along * k for m, k in zip(moved, n)] == pytest.approx([0, 0, 0], abs=1e-9)
        assert g0 != pytest.approx(snapped)
        # bad lines
        assert c.request_reply("snap vertex")["error"]["code"] == "bad-argument"
        c.request("input pointer front 5 5")  # the sky
        assert c.request_reply("snap face_center")["error"]["code"] == "not-found"
        c.request("input key KEY_ESC down")
        assert c.request_reply("snap site")["error"]["code"] == "bad-argument"


def test_a_typed_value_sets_the_displacement_exactly(daemon):
    """Blender's typed values: during a drag along x, "10cm" puts G exactly 10 cm from where
    the chord began, whatever the mouse did; a turn takes an angle; the figure follows."""
    with daemon.client() as c:
        setup(c)
        c.request("manipulate figure human")
        g0 = c.request("get manip")["position"]
        c.request("input pointer front 100 120")
        c.request("input button left down")
        c.request("input pointer front 140 120")  # some motion first
        assert c.request("set manip 10cm")["position"] == pytest.approx(
            [g0[0] + 0.10, g0[1], g0[2]], abs=1e-12)
        assert c.request("set manip -0.25")["position"] == pytest.approx(
            [g0[0] - 0.25, g0[1], g0[2]], abs=1e-12)  # again from the chord's start
        root = c.request("show figure human")["root"]
        assert c.request(f"get site human {root}")["position"][0] == pytest.approx(g0[0] - 0.25)
        c.request("input button left up")
        assert c.request_reply("set manip 1cm")["error"]["code"] == "bad-argument"  # no axis
        c.request("input key KEY_LEFTCTRL down")
        c.request("input button right down")  # a turn about z, the wheel facing us
        r0 = c.request("get manip")["rotation"]
        c.request("set manip 90deg")
        r = c.request("get manip")["rotation"]
        # R_z(90) R0, rows: (-row 1, row 0, row 2)
        want = [[-r0[1][j] for j in range(3)], r0[0], r0[2]]
        assert sum(r, []) == pytest.approx(sum(want, []), abs=1e-12)
        assert c.request_reply("set manip 10cm")["error"]["code"] == "bad-number"


def test_increments_move_g_in_whole_centimetres(daemon):
    """With increments on, a drag along x moves G by whole steps of 1 cm from where it
    began (the nearest step to the free motion); off again, the motion is free."""
    with daemon.client() as c:
        setup(c)
        c.request("manipulate figure human")
        assert c.request("set manip increments=on")["increments"] is True
        g0 = c.request("get manip")["position"]
        c.request("input pointer front 160 120")
        c.request("input button left down")
        for x in (171, 183, 197):
            c.request(f"input pointer front {x} 120")
            dx = c.request("get manip")["position"][0] - g0[0]
            assert dx == pytest.approx(round(dx * 100) / 100, abs=1e-12) and dx > 0
        c.request("input button left up")
        assert c.request("set manip increments=off")["increments"] is False
        assert c.request_reply("set manip increments=maybe")["error"]["code"] == "bad-argument"


def test_increment_sizes_are_settable_and_kept_from_mode_to_mode(daemon):
    """step= and turn= set the increments' sizes; set once (even with no mode), they hold
    in every mode after: a drag goes in whole 2.5 cm steps, a turn in whole 15 degrees."""
    with daemon.client() as c:
        setup(c, eye="0,4,0.5", target="0,0,0")
        reply = c.request("set manip increments=on step=2.5cm turn=15deg")
        assert reply == {"increments": True, "step": pytest.approx(0.025, abs=1e-15),
                         "turn": pytest.approx(math.radians(15), abs=1e-15)}
        c.request("manipulate figure human")
        g0 = c.request("get manip")
        c.request("input pointer front 160 120")
        c.request("input button left down")
        seen = set()
        for x in (175, 190, 215, 240):
            c.request(f"input pointer front {x} 120")
            dx = c.request("get manip")["position"][0] - g0["position"][0]
            assert dx / 0.025 == pytest.approx(round(dx / 0.025), abs=1e-9)
            seen.add(round(dx / 0.025))
        assert len(seen) > 1
        c.request("input button left up")
        c.request("input key KEY_ESC down")
        c.request("input key KEY_ESC up")
        # a new mode: the wheel about y turns in whole 15 degree steps
        c.request("manipulate figure human")
        g0 = c.request("get manip")
        c.request("input key KEY_LEFTCTRL down")
        c.request("input pointer front 220 120")
        c.request("input button middle down")
        turns = set()
        for x, y in ((200, 60), (160, 40), (110, 70)):
            c.request(f"input pointer front {x} {y}")
            r, r0 = c.request("get manip")["rotation"], g0["rotation"]
            x_now, x_then = [r[i][0] for i in range(3)], [r0[i][0] for i in range(3)]
            turn = math.degrees(math.acos(max(-1, min(1, dot(x_now, x_then)))))
            assert turn / 15 == pytest.approx(round(turn / 15), abs=1e-6), turn
            turns.add(round(turn / 15))
        assert len(turns) > 1
        c.request("input button middle up")
        for bad in ("step=0", "step=20m", "turn=200deg", "turn=x", "speed=2"):
            assert not c.request_reply(f"set manip {bad}")["ok"], bad
        assert c.request("set manip increments=off")["step"] == pytest.approx(0.025, abs=1e-15)


@pytest.mark.parametrize("what,site", [("head", "head.between_eyes"), ("eyes", "eyeball_l.gaze")])
def test_the_head_and_the_eyes_fixate_g(daemon, what, site):
    """move head / move eyes as modes: G starts a metre along the aim axis (+z) and is the
    point fixated; dragged aside, the head (or eye) turns until its +z points at G."""
    with daemon.client() as c:
        setup(c, eye="0,1.6,3", target="0,1.6,0")
        c.request("behave human on")
        c.request("settle frames=30")
        assert c.request(f"manipulate {what} human")["mode"] == what
        g = drag_x(c, 0.3)
        c.request("settle frames=120")
        write_picture(c, "front", f"manip_{what}.png")
        s = c.request(f"get site human {site}")
        r = s["rotation"]  # row-major 3x3: the +z axis is the third column
        z = [r[2], r[5], r[8]]
        to_g = sub(g, s["position"])
        n = math.sqrt(dot(to_g, to_g))
        angle = math.degrees(math.acos(max(-1, min(1, dot(z, to_g) / n))))
        assert angle < 2, angle


def test_turning_the_pelvis_with_the_wheel(daemon):
    """rotate pelvis as a mode: CONTROL and the middle button turn G about the vertical; the
    pelvis turns as far relative to the feet (here by a typed 25 degrees)."""
    with daemon.client() as c:
        setup(c, eye="0,4,0.5", target="0,0,0")  # from above: the wheel about y faces us
        c.request("behave human on")
        c.request("settle frames=30")

        def heading():
            r = c.request("get site human pelvis.root")["rotation"]
            return math.degrees(math.atan2(r[6], r[0]))  # the x axis (column 0) about y
        h0 = heading()
        assert c.request("manipulate pelvis human")["mode"] == "pelvis"
        c.request("input key KEY_LEFTCTRL down")
        c.request("input button middle down")
        assert c.request("get manip")["state"] == "rotate"
        c.request("set manip 25deg")
        c.request("settle frames=120")
        write_picture(c, "front", "manip_pelvis.png")
        turned = h0 - heading()  # +25 about y turns x towards -z: atan2(r6, r0) falls
        assert turned == pytest.approx(25, abs=3)


def test_a_typed_value_sets_a_joint_exactly_in_its_own_sense(daemon):
    with daemon.client() as c:
        c.request("load human as human")
        c.request("add view side width=320 height=240 eye=3,1.1,0 target=0,1.1,0")
        for root in ("pelvis.root", "hand_r.palm"):  # the elbow down, then up the rooting
            c.request(f"set root human {root}")
            c.request("set joint human elbow_r 0")
            c.request("manipulate joint human elbow_r view=side")
            assert c.request_reply("set manip 10deg")["error"]["code"] == "bad-argument"
            c.request("input button left down")
            value = c.request("set manip 30deg")["value"]
            got = c.request("get joint human elbow_r")["values"][0]
            assert value == pytest.approx(math.radians(30), abs=1e-12)
            assert got == pytest.approx(math.radians(30), abs=1e-12)
            c.request("set manip 200deg")  # clamped at the upper limit, 150 degrees
            assert c.request("get joint human elbow_r")["values"][0] == pytest.approx(
                math.radians(150), abs=1e-12)
            assert c.request_reply("set manip 3cm")["error"]["code"] == "bad-number"
            c.request("input button left up")
            c.request("input key KEY_ESC down")
