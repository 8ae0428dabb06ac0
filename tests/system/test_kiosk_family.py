"""A family of manikins at the kiosk (`show family`): side by side in a row along a view's
horizontal, or overlaid with the others drawn as translucent ghosts the mouse cannot pick;
posed alike (`pose family`); the status line names the selected manikin and where its size
comes from.

The references are geometry and the pixels themselves: a row's places are the spacing
apart along the camera's level x axis, computed here from the view's eye and target; the
default spacing is the members' widest reaches as trimesh measures them on each member's
glTF export, plus the margin; a ghost's pixel is the blend, at its alpha, of the same
figure drawn opaque and the background drawn without it (three pictures of one camera),
and a pixel only a ghost covers picks nothing. Sessions, undo, a kill -9 and a recording's
replay keep the arrangement and the ghosts."""
import base64
import math
import re

import numpy as np
import pytest

from daemon import daemon, daemon_factory, write_picture  # noqa: F401 (fixtures)
from kiosk_keys import press, type_text
from test_manip import png_pixels
from test_replay import replay

GHOST_ALPHA = 0.25  # family.h: FAMILY_GHOST_ALPHA
MARGIN = 0.2        # family.h: FAMILY_ROW_MARGIN
SOLE_SITES = ["foot_l.heel", "foot_r.heel", "foot_l.balance", "foot_r.balance", "toes_l.tip",
              "toes_r.tip"]


def place(c, fig):
    """the midpoint of a human's feet's balance sites (world)"""
    a = np.array(c.request(f"get site {fig} foot_l.balance")["position"])
    b = np.array(c.request(f"get site {fig} foot_r.balance")["position"])
    return (a + b) / 2


def level_x(eye, target):
    """a camera's x axis aimed from eye at target with no twist: forward x up, made level"""
    f = np.array(target, float) - np.array(eye, float)
    x = np.cross(f, [0, 1, 0])
    return x / np.linalg.norm(x)


def members(c, prefix):
    """the family's members in its order (women first, then by member number)"""
    figs = [f for f in c.request("list figures")["figures"] if f.get("family") == prefix]
    figs.sort(key=lambda f: (f["sex"] != "female", f["member"]))
    return [f["name"] for f in figs]


def pixels(c, view):
    return png_pixels(base64.b64decode(c.request(f"render view {view}")["png"]))[2]


def picked(c, view, x, y):
    hit = c.request(f"pick {view} {x} {y}")["hit"]
    return hit and hit["name"]


def test_a_row_stands_the_members_spacing_apart_along_the_views_horizontal(daemon):
    eye, target = [3.0, 1.5, 4.0], [0.0, 0.9, 0.0]
    h = level_x(eye, target)
    with daemon.client() as c:
        c.request(f"add view main width=640 height=360 eye={','.join(map(str, eye))} "
                  f"target={','.join(map(str, target))}")
        c.request("load family f sex=female n=4")
        names = members(c, "f")
        assert names == ["f_0", "f_1", "f_2", "f_3", "f_4"]
        # one member turned and lifted, another moved away: the row turns them back to
        # face as the selected one does and stands them on the floor
        c.request("set location f_1 2 1.2 -1 yaw=30deg")
        c.request("set location f_3 -1 0.5 2")
        before = {n: c.request(f"get posture {n}") for n in names}
        sel_before = place(c, "f_2")
        r = c.request("show family f row spacing=0.9 select=f_2")
        assert r["arrangement"] == "row" and r["selected"] == "f_2" and r["spacing"] == 0.9
        assert r["direction"] == pytest.approx(list(h), abs=1e-12)
        at = {n: place(c, n) for n in names}
        assert at["f_2"] == pytest.approx(sel_before, abs=1e-12)  # the selected stays put
        turn = np.array(c.request("get site f_2 pelvis.root")["rotation"])
        for i, n in enumerate(names):
            want = at["f_2"] + (i - 2) * 0.9 * h
            assert at[n][[0, 2]] == pytest.approx(want[[0, 2]], abs=1e-9), n
            sole = min(c.request(f"get site {n} {s}")["position"][1] for s in SOLE_SITES)
            assert sole == pytest.approx(0, abs=1e-9), n
            rot = np.array(c.request(f"get site {n} pelvis.root")["rotation"])
            assert rot == pytest.approx(turn, abs=1e-9), n
            assert c.request(f"get posture {n}")["posture"] == before[n]["posture"]
        assert [f["ghost"] for f in r["figures"]] == [False] * 5
        write_picture(c, "main", "kiosk_family_row.png")
        # one undo step takes the whole row back, bit for bit
        c.request("undo")
        assert {n: c.request(f"get posture {n}") for n in names} == before
        assert c.request("get kiosk")["figure"] is None


def test_the_default_spacing_is_the_widest_reaches_plus_the_margin(daemon):
    trimesh = pytest.importorskip("trimesh")
    eye, target = [-2.0, 1.4, 5.0], [0.0, 0.9, 0.0]
    h = level_x(eye, target)
    with daemon.client() as c:
        c.request(f"add view main width=640 height=360 eye={','.join(map(str, eye))} "
                  f"target={','.join(map(str, target))}")
        c.request("load family g sex=both n=3")
        names = members(c, "g")
        assert names == [f"g_{s}_{i}" for s in ("female", "male") for i in range(4)]
        c.request("set joint g_male_2 shoulder_r 0 80deg 0")  # an arm out: a wider reach
        r = c.request("show family g row")
        s = r["spacing"]
        # each member's geometry as the glTF export gives it, posed by trimesh
        reach = {}
        for n in names:
            c.request(f"export gltf {n} {n}.glb")
            scene = trimesh.load(str(daemon.state_dir / f"{n}.glb"), force="scene")
            v = scene.to_geometry().vertices @ h
            mid = place(c, n) @ h
            reach[n] = (mid - v.min(), v.max() - mid)
        left = max(a for a, _ in reach.values())
        right = max(b for _, b in reach.values())
        assert s == pytest.approx(left + right + MARGIN, abs=1e-5)
        for i in range(len(names) - 1):  # neighbours never touch: the margin between them
            a, b = names[i], names[i + 1]
            assert (place(c, b) - place(c, a)) @ h == pytest.approx(s, abs=1e-9)
            gap = (place(c, b) @ h - reach[b][0]) - (place(c, a) @ h + reach[a][1])
            assert gap >= MARGIN - 1e-5, (a, b, gap)
        write_picture(c, "main", "kiosk_family_row_default.png")


def coverage(c, names, view, x, ys):
    """for each member, the rows of column x it covers, with the distance to it along the
    mouse line, when it is the selected one (the others, ghosts, are not picked)"""
    cov = {}
    for n in names:
        c.request(f"show family f overlay select={n}")
        cov[n] = {}
        for y in ys:
            hit = c.request(f"pick {view} {x} {y}")["hit"]
            if hit and hit["name"] == n:
                cov[n][y] = hit["distance"]
    return cov


def test_ghosts_are_translucent_and_the_selected_one_opaque(daemon):
    with daemon.client() as c:
        c.request("add view main width=640 height=360 eye=0,1.5,3 target=0,1.2,0")
        background = pixels(c, "main")
        c.request("load family f sex=female n=4")
        names = members(c, "f")
        stature = {f["name"]: f["stature"] for f in c.request("list figures")["figures"]}
        small, tall = min(names, key=stature.get), max(names, key=stature.get)
        cov = coverage(c, names, "main", 320, range(40, 200))
        # the rows above every other head: the tallest one's head alone
        alone = sorted(y for y in cov[tall] if not any(y in cov[n] for n in names if n != tall))
        assert len(alone) >= 4, cov
        c.request(f"show family f overlay select={tall}")
        opaque = pixels(c, "main")  # the tallest selected: drawn solid
        r = c.request(f"show family f overlay select={small}")
        assert {f["name"]: f["ghost"] for f in r["figures"]} == {n: n != small for n in names}
        ghosted = pixels(c, "main")
        write_picture(c, "main", "kiosk_family_overlay.png")
        for y in alone[1:-1]:  # not the edge rows, which the samples share with the sky
            for x in (319, 320, 321):
                a, b, o = (np.array(p[y][x], float) for p in (ghosted, background, opaque))
                assert a == pytest.approx(GHOST_ALPHA * o + (1 - GHOST_ALPHA) * b, abs=2.5), (x, y)
                assert np.abs(o - b).max() > 20  # the figure differs from the sky there
        # never the ghost: nothing is picked where it alone is, the selected one where it is
        assert picked(c, "main", 320, alone[len(alone) // 2]) is None
        chest = min(cov[small]) + 40
        assert picked(c, "main", 320, chest) == small
        # the selected one is drawn solid: where it is nearest, as when it stands alone
        c.request(f"show family f overlay select={tall}")
        front = pixels(c, "main")
        c.request("show family f off")
        for n in names:
            if n != tall:
                c.request(f"set location {n} 20 0 0")
        solo = pixels(c, "main")
        nearest = [y for y in cov[tall] if all(cov[tall][y] < cov[n].get(y, math.inf) - 0.01
                                                for n in names if n != tall)]
        assert len(nearest) >= 10
        for y in nearest:
            assert np.abs(np.array(front[y][320], float) - solo[y][320]).max() <= 2, y


def test_a_click_on_a_ghost_never_takes_it(daemon):
    with daemon.client() as c:
        c.request("add view main width=640 height=360 eye=0,1.5,3 target=0,1.2,0")
        c.request("load family f sex=female n=4")
        names = members(c, "f")
        stature = {f["name"]: f["stature"] for f in c.request("list figures")["figures"]}
        small, tall = min(names, key=stature.get), max(names, key=stature.get)
        cov = coverage(c, names, "main", 320, range(40, 200))
        y_ghost = min(cov[tall]) + 2  # the tallest one's head, above all the others
        y_small = min(cov[small]) + 40
        c.request(f"show family f overlay select={small}")
        # a prompt's "select a figure": the ghost's pixel has nothing, the selected's has it
        type_text(c, "show figure", enter=True)
        assert c.request("get kiosk")["prompt"]["question"] == "select a figure"
        c.request(f"input pointer main 320 {y_ghost}")
        assert c.request("get kiosk")["picked"] is None
        c.request("input button left down")
        c.request("input button left up")
        assert c.request("get kiosk")["prompt"]["question"] == "select a figure"
        c.request(f"input pointer main 320 {y_small}")
        assert c.request("get kiosk")["picked"]["figure"] == small
        c.request("input button left down")
        c.request("input button left up")
        assert c.request("get kiosk")["prompt"] is None
        # outside a prompt a click on the ghost is a click on the background: the menu opens,
        # the selection stays
        c.request(f"input pointer main 320 {y_ghost}")
        c.request("input button left down")
        c.request("input button left up")
        k = c.request("get kiosk")
        assert k["menu"] is not None and k["figure"]["name"] == small
        press(c, "KEY_ESC")
        # in a row a click on another member selects it; on the selected one nothing changes
        r = c.request("show family f row spacing=0.8")
        other = names[(names.index(small) + 1) % len(names)]
        c.request("set camera main eye=0,1.2,6 target=0,0.9,0")
        x, y = next((x, y) for y in range(120, 260, 8) for x in range(0, 640, 4)
                    if picked(c, "main", x, y) == other)
        c.request(f"input pointer main {x} {y}")
        c.request("input button left down")
        c.request("input button left up")
        assert c.request("get kiosk")["figure"]["name"] == other
        for f in r["figures"]:  # the same camera's horizontal: the row stands as it stood
            assert place(c, f["name"]) == pytest.approx(f["place"], abs=1e-9)


# the low back and the weakest joint after the scores, when they are (test_loads.py checks them)
LOADS = r"(   L5/S1 [0-9.]+ kN(, \d+ % capable)?)?"


def test_the_status_line_names_the_selected_manikin(daemon):
    with daemon.client() as c:
        c.request("add view main width=1280 height=400 eye=0,1.4,5 target=0,0.9,0")
        c.request("load human as jack")
        c.request("load human as f5 sex=female percentile=5")
        c.request("load human as w sex=female sittingheight=900 weightkg=70")
        c.request("load family f sex=female n=4")
        listed = {f["name"]: f for f in c.request("list figures")["figures"]}
        assert c.request("get kiosk")["figure"] is None
        # the figure a mode is on, then the last one a mode was on
        for name, says in [
                ("jack", "jack: 1.75 m, 75 kg male"),
                ("f5", "f5: P5 stature (ansur2 female)"),
                ("w", f"w: ansur2 female, Mahalanobis {listed['w']['mahalanobis']:.2f} "
                      "on 2 measures")]:
            c.request(f"manipulate figure {name} view=main")
            assert c.request("get kiosk")["figure"] == {"name": name, "says": says}
            press(c, "KEY_ESC")
            assert c.request("get kiosk")["figure"]["says"] == says
            c.request("render view main")
            # ... and the human's RULA and REBA grand scores now (test_assess.py checks them)
            assert re.match(rf"main   {re.escape(says)}   RULA \d, REBA \d+{LOADS}   frame ",
                            c.request("get kiosk")["status"])
        # a family shown: its selected one, Page Down and Page Up step through it, around
        c.request("show family f row")
        said = []
        for key in ["KEY_PAGEDOWN"] * 5 + ["KEY_PAGEUP"] * 2:
            k = c.request("get kiosk")["figure"]
            said.append(k["says"])
            press(c, key)
        said.append(c.request("get kiosk")["figure"]["says"])
        order = [0, 1, 2, 3, 4, 0, 4, 3]
        want = ["f_0: family f centre (90% coverage)" if i == 0 else
                f"f_{i}: family f, Mahalanobis {listed[f'f_{i}']['mahalanobis']:.2f} "
                "(90% coverage)" for i in order]
        assert said == want
        # ... as drawn: the band's text changes where the words differ, and only there
        band = pixels(c, "main")[380:400]
        line = c.request("get kiosk")["status"]
        assert re.match(rf"main   {re.escape(want[-1])}   RULA \d, REBA \d+{LOADS}   frame ",
                        line)
        press(c, "KEY_PAGEDOWN")
        other = pixels(c, "main")[380:400]
        line2 = c.request("get kiosk")["status"]
        first = next(i for i, (a, b) in enumerate(zip(line, line2)) if a != b)
        cols = [x for x in range(1280) if any(band[y][x] != other[y][x] for y in range(20))]
        # a monospaced font of 8 to 9 pixels a character, from a small margin
        assert cols and 8 * first <= min(cols) <= 9 * first + 12, (first, min(cols))
        # the kiosk's figure in a mode is the mode's, a ghost drawn solid while it is moved
        c.request("show family f overlay select=f_0")
        c.request("manipulate figure f_2 view=main")
        assert c.request("get kiosk")["figure"]["name"] == "f_2"
        assert c.request("show family f overlay")["figures"][2]["ghost"] is False
        press(c, "KEY_ESC")
        assert c.request("get kiosk")["figure"]["name"] == "f_0"
        # no family shown: Page Down says so and changes nothing
        c.request("show family f off")
        c.request("input key KEY_PAGEDOWN down")
        k = c.request("get kiosk")  # (the next line's outcome takes the message line)
        c.request("input key KEY_PAGEDOWN up")
        assert "no family shown" in k["message"]
        assert k["figure"]["name"] == "f_2"  # the last mode's


def heading(c, fig):
    """the pelvis's forward (+z) axis about the vertical, radians"""
    r = c.request(f"get site {fig} pelvis.root")["rotation"]
    return math.atan2(r[2], r[8])


def test_a_family_posed_alike_keeps_each_place(daemon):
    with daemon.client() as c:
        c.request("add view main width=640 height=360 eye=0,1.4,6 target=0,0.9,0")
        c.request("load family f sex=female n=4")
        names = members(c, "f")
        c.request("show family f row select=f_2")
        c.request("set location f_4 3 0.845 1 yaw=40deg")  # one turned and moved away,
        c.request("set root f_4 foot_l.balance")  # and rooted at its foot: the pose turns it
        for line in ("set joint f_2 knee_l 50deg", "set joint f_2 hip_l 0 0 -40deg",
                     "set joint f_2 shoulder_r 0 70deg 0", "set joint f_2 elbow_r 60deg"):
            c.request(line)
        at = {n: place(c, n) for n in names}
        face = {n: heading(c, n) for n in names}
        before = {n: c.request(f"get posture {n}") for n in names}
        r = c.request("pose family f")  # like the selected one
        assert r["like"] == "f_2" and r["figures"] == [n for n in names if n != "f_2"]
        want = c.request("get posture f_2")["posture"]
        for n in names:
            assert c.request(f"get posture {n}")["posture"] == want, n
            assert place(c, n)[[0, 2]] == pytest.approx(at[n][[0, 2]], abs=1e-9), n
            assert heading(c, n) == pytest.approx(face[n], abs=1e-9), n
            sole = min(c.request(f"get site {n} {s}")["position"][1] for s in SOLE_SITES)
            assert sole == pytest.approx(0, abs=1e-9), n
        write_picture(c, "main", "kiosk_family_posed.png")
        c.request("undo")
        assert {n: c.request(f"get posture {n}") for n in names} == before
        # like another human; refusals change nothing
        c.request("load human as jack")
        c.request("set joint jack elbow_l 90deg")
        c.request("pose family f like=jack")
        assert c.request("get joint f_0 elbow_l")["values"] == c.request(
            "get joint jack elbow_l")["values"]
        c.request("behave f_1 on")
        for line, code in [("pose family nope", "not-found"), ("pose family f like=nobody",
                                                                 "not-found"),
                           ("pose family f colour=red", "bad-argument"),
                           ("pose family f", "bad-argument")]:  # f_1 behaves
            reply = c.request_reply(line)
            assert not reply["ok"] and reply["error"]["code"] == code, (line, reply)
        assert c.request("get joint f_0 elbow_l")["values"] == c.request(
            "get joint jack elbow_l")["values"]


def test_tab_completes_a_familys_prefix(daemon):
    with daemon.client() as c:
        c.request("load family kin sex=male n=2")
        type_text(c, "show family ki")
        press(c, "KEY_TAB")  # kin, kin_0, kin_1, kin_2: their common part
        assert c.request("get kiosk")["line"] == "show family kin"


def test_bad_requests_change_nothing(daemon):
    with daemon.client() as c:
        c.request("add view main width=320 height=240 eye=0,1.4,5 target=0,0.9,0")
        c.request("load human as jack")
        c.request("load family f sex=female n=2")
        c.request("show family f overlay")
        c.request("load family b sex=male n=1")
        c.request("behave b_1 on")

        def state():  # (the behaving b_1 may settle further: the others stand still)
            return ([c.request(f"get posture {n}") for n in ("jack", "f_0", "f_1", "f_2", "b_0")],
                    c.request("list figures"), c.request("get kiosk")["figure"])
        before = state()
        for line, code in [
                ("show family nope row", "not-found"),
                ("show family f sideways", "bad-argument"),
                ("show family f row spacing=0", "bad-number"),
                ("show family f row spacing=-1", "bad-number"),
                ("show family f row spacing=1km", "bad-number"),
                ("show family f overlay spacing=1", "bad-argument"),
                ("show family f row select=jack", "bad-argument"),
                ("show family f row select=nobody", "not-found"),
                ("show family f row view=nowhere", "not-found"),
                ("show family f row colour=red", "bad-argument"),
                ("show family f off select=f_1", "bad-argument"),
                ("show family b row", "bad-argument")]:  # b_1 behaves
            reply = c.request_reply(line)
            assert not reply["ok"] and reply["error"]["code"] == code, (line, reply)
            assert state() == before, line
        assert "behave b_1 off" in c.request_reply("show family b row")["error"]["message"]


def test_sessions_undo_and_a_kill9_keep_the_arrangement_and_the_ghosts(daemon):
    with daemon.client() as c:
        # two views with other horizontals; the row follows the one the pointer is in
        c.request("add view main width=640 height=360 eye=0,1.5,3 target=0,1.2,0")
        c.request("add view side width=640 height=360 eye=4,1.4,0.5 target=0,0.9,0")
        c.request("load family f sex=female n=3")
        names = members(c, "f")
        stature = {f["name"]: f["stature"] for f in c.request("list figures")["figures"]}
        small = min(names, key=stature.get)
        c.request("input pointer side 300 200")
        r = c.request("show family f row spacing=0.7 select=f_1")
        assert r["view"] == "side"
        assert r["direction"] == pytest.approx(list(level_x([4, 1.4, 0.5], [0, 0.9, 0])), abs=1e-12)
        row = {n: list(place(c, n)) for n in names}
        c.request("save session fam.ses")
        c.request(f"show family f overlay select={small}")
        overlay = {n: list(place(c, n)) for n in names}
        ghosts = {f["name"]: f.get("ghost", False) for f in c.request("list figures")["figures"]}
        assert ghosts == {n: n != small for n in names}
        seen = {picked(c, "main", 320, y) for y in range(20, 330, 2)}
        assert seen == {None, small}  # the taller ghosts' heads are not picked
        text = (daemon.state_dir / "fam.ses").read_text()
        assert "show family f row select=f_1 spacing=0.69999999999999996\n" in text
        posture = c.request("status")["posture"]
    daemon.kill9()
    daemon.start()
    with daemon.client() as c:
        # the journal held the row's view and spacing: recovery, with no pointer, did the same
        assert c.request("status")["posture"] == posture
        assert {n: list(place(c, n)) for n in names} == overlay
        assert c.request("get kiosk")["figure"]["name"] == small
        assert {picked(c, "main", 320, y) for y in range(20, 330, 2)} == seen
        c.request("undo")  # the overlay taken back: the row, f_1 selected, no ghosts
        assert {n: list(place(c, n)) for n in names} == row
        assert c.request("get kiosk")["figure"]["name"] == "f_1"
        assert not any(f.get("ghost") for f in c.request("list figures")["figures"])
        c.request("redo")
        assert sum(bool(f.get("ghost")) for f in c.request("list figures")["figures"]) == 3
        c.request("load session fam.ses")
        assert {n: list(place(c, n)) for n in names} == row
        assert not any(f.get("ghost") for f in c.request("list figures")["figures"])
        assert c.request("get kiosk")["figure"]["name"] == "f_1"
        # a session naming no member of the family it shows is refused whole
        bad = text.replace("select=f_1", "select=nobody")
        (daemon.state_dir / "bad.ses").write_text(bad)
        err = c.request_reply("load session bad.ses")["error"]
        assert err["code"] == "bad-file" and "no member of family f" in err["message"]


def test_a_recorded_session_with_a_family_shown_replays_without_divergence(daemon_factory,
                                                                           tmp_path):
    rec = tmp_path / "rec"
    d = daemon_factory(fps=1000, extra=("--record", str(rec), "--solve-budget", "60"))
    with d.client() as c:
        c.request("add view main width=480 height=320 eye=1,1.4,4 target=0,0.9,0")
        c.request("add view top width=320 height=240 eye=0.5,6,1 target=0,0,0")
        c.request("load family f sex=female n=3")
        c.request("load human as jack")
        c.request("behave jack on")  # a body the solver works on while the family is shown
        c.request("input pointer top 100 100")
        type_text(c, "show family f row", enter=True)  # the top view's horizontal
        press(c, "KEY_PAGEDOWN")
        press(c, "KEY_PAGEDOWN")
        c.request("input pointer main 240 160")
        c.request("show family f overlay")
        c.request("move hand jack right 0.3,1.3,0.4")
        press(c, "KEY_PAGEUP")
        c.request("input pointer main 240 60")
        c.request("input button left down")
        c.request("input button left up")
        press(c, "KEY_ESC")
        type_text(c, "show family f row spacing=0.9", enter=True)
        c.request("settle")
        live = c.request("status")["posture"]
        assert c.request("get kiosk")["figure"]["name"] == "f_1"  # down, down, up
    d.stop()
    status, out, err = replay(rec)
    assert status == 0, err
    frames = int(re.search(r"state complete frames=(\d+)", (rec / "manifest").read_text())[1])
    assert out == (frames, live, 0), err
