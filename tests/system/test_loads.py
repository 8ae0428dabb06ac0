"""Loads on the body through the protocol (issue 26): external loads as the environment's
objects (add, list, delete load) kept by sessions, undo, the journal and recordings; the
weight of a carried object on the hands that hold it; and bad input refused with nothing
changed.

References: a weight's force is its mass times standard gravity, 9.80665 m/s^2 (3rd CGPM,
1901); the share of two hands on a carried object is the lever rule of statics, written out
again here from the palms' and the object's centre of mass's positions the daemon reports.
"""
import math
import pathlib
import re

import pytest

from daemon import ROOT, daemon, daemon_factory, journal_records  # noqa: F401 (fixtures)

LIBRARY = ("--library", str(ROOT / "src" / "figure" / "library"))
G = 9.80665


def loads_state(c):
    """What a refused command must leave as it was: the loads, postures, undo."""
    s = c.request("status")
    return c.request("list loads"), s["posture"], s["undo"], s["figures"]


def close3(a, b, tol=1e-9):
    return all(abs(x - y) <= tol * max(1.0, abs(y)) for x, y in zip(a, b))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


# ---- the loads as objects -------------------------------------------------------------

def test_add_list_and_delete_a_force_and_a_weight(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        f = c.request("add load jack hand_r.palm force=10,-40,5.5 torque=0,1.5,0 as push")
        assert re.fullmatch(r"l\d+\.\d+", f["load"]) and f["name"] == "push"
        w = c.request("add load jack hand_l.palm mass=7.5kg")
        assert w["name"] == "l1"
        palm = c.request("get site jack hand_l.palm")["position"]
        listed = {x["name"]: x for x in c.request("list loads jack")["loads"]}
        assert listed["push"] == {
            "load": f["load"], "name": "push", "figure": "jack", "site": "hand_r.palm",
            "force": [10, -40, 5.5], "torque": [0, 1.5, 0], "mass": None,
            "position": listed["push"]["position"]}
        bag = listed["l1"]
        assert bag["mass"] == 7.5 and bag["torque"] == [0, 0, 0]
        assert bag["force"] == [0, -7.5 * G, 0]  # the weight: mass x standard gravity, down
        assert bag["position"] == palm
        # by id or by name; the id is stale once the slot is reused
        c.request(f"delete load {f['load']}")
        err = c.request_reply(f"delete load {f['load']}")["error"]
        assert err["code"] == "not-found"
        again = c.request("add load jack head.origin force=0,0,20")
        if again["load"].split(".")[0] == f["load"].split(".")[0]:
            assert c.request_reply(f"delete load {f['load']}")["error"]["code"] == "stale-id"
        c.request("delete load l1")
        assert [x["name"] for x in c.request("list loads")["loads"]] == [again["name"]]
        c.request("load human as other")
        c.request("add load other hand_r.palm mass=2")
        assert [x["figure"] for x in c.request("list loads other")["loads"]] == ["other"]
        assert len(c.request("list loads")["loads"]) == 2


def test_a_figure_unloaded_takes_its_loads_with_it(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        c.request("load human as jill")
        c.request("add load jack hand_r.palm mass=3 as a")
        c.request("add load jill hand_r.palm mass=4 as b")
        c.request("unload figure jack")
        assert [x["name"] for x in c.request("list loads")["loads"]] == ["b"]
        assert c.request_reply("delete load a")["error"]["code"] == "not-found"
        c.request("undo")  # jack comes back with his load
        assert sorted(x["name"] for x in c.request("list loads")["loads"]) == ["a", "b"]


BAD = [
    ("add load jack hand_r.palm force=nan,0,0", "bad-number", "finite"),
    ("add load jack hand_r.palm force=inf,0,0", "bad-number", "finite"),
    ("add load jack hand_r.palm force=1e308,0,0", "bad-number", "at most 100000 N"),
    ("add load jack hand_r.palm force=0,0,0 torque=0,1e300,0", "bad-number", "at most 10000 N m"),
    ("add load jack hand_r.palm force=1,2", "bad-number", "three"),
    ("add load jack hand_r.palm force=1,2,3,4", "bad-number", "three"),
    ("add load jack hand_r.palm force=1,2,x", "bad-number", "three"),
    ("add load jack hand_r.palm mass=nan", "bad-number", "mass"),
    ("add load jack hand_r.palm mass=0", "bad-number", "above 0"),
    ("add load jack hand_r.palm mass=-3", "bad-number", "above 0"),
    ("add load jack hand_r.palm mass=1001", "bad-number", "at most 1000"),
    ("add load jack hand_r.palm mass=5lb", "bad-number", "kg"),
    ("add load jack hand_r.palm mass=5 torque=1,0,0", "bad-argument", "no torque"),
    ("add load jack hand_r.palm mass=5 force=0,-49,0", "arity", "one of the two"),
    ("add load jack hand_r.palm torque=1,0,0", "arity", "one of the two"),
    ("add load jack hand_r.palm as x", "arity", "one of the two"),
    ("add load jack hand_r.nowhere mass=5", "not-found", "no site 'hand_r.nowhere'"),
    ("add load jack palm mass=5", "not-found", "no site"),
    ("add load gone hand_r.palm mass=5", "not-found", "no figure 'gone'"),
    ("add load f9.9 hand_r.palm mass=5", "not-found", "no figure"),
    ("add load jack hand_r.palm mass=5 as bag", "exists", "a load named 'bag' exists"),
    ("add load jack hand_r.palm mass=5 as 9x", "bad-argument", "'as' takes a name"),
    ("add load jack hand_r.palm mass=5 colour=red", "bad-argument", "unexpected 'colour=red'"),
    ("add load jack hand_r.palm", "arity", "add load FIG SEG.SITE"),
    ("delete load nothing", "not-found", "no load 'nothing'"),
    ("delete load l63.999", "not-found", "no load"),
    ("delete load", "arity", "delete load LOAD"),
    ("list loads gone", "not-found", "no figure 'gone'"),
    ("list loads jack extra", "arity", "list loads"),
]


def test_bad_input_is_refused_clearly_and_changes_nothing(daemon):
    with daemon.client() as c:
        gone = c.request("load human as ghost")["figure"]
        c.request("unload figure ghost")
        c.request("load human as jack")  # in the ghost's slot: its id is stale
        c.request("add load jack hand_r.palm mass=5 as bag")
        before = loads_state(c)
        stale = [(f"add load {gone} hand_r.palm mass=5", "stale-id", "is stale"),
                 (f"list loads {gone}", "stale-id", "is stale"),
                 (f"analyze loads {gone}", "stale-id", "is stale")]
        for line, code, words in BAD + stale:
            r = c.request_reply(line)
            assert r["ok"] is False, line
            assert r["error"]["code"] == code, (line, r)
            assert words in r["error"]["message"], (line, r["error"]["message"])
            assert loads_state(c) == before, line


# ---- sessions, undo, the journal ------------------------------------------------------

def add_some(c):
    c.request("load human as jack")
    c.request("load human as jill")
    c.request("add load jack hand_r.palm force=1.25,-30.5,0.1 torque=0.5,0,-0.25 as push")
    c.request("add load jill hand_l.palm mass=4.2 as bag")
    c.request("add load jack head.origin mass=1")


def test_sessions_keep_the_loads_and_older_sessions_still_load(daemon):
    with daemon.client() as c:
        add_some(c)
        c.request("delete load l1")  # a gap in the slots: kept as it was
        kept = c.request("list loads")
        c.request("save session s.session")
        text = (daemon.state_dir / "s.session").read_text()
        assert text.startswith("session 5\n")
        lines = [ln for ln in text.splitlines() if ln.startswith("load ")]
        assert len(lines) == 2 and any("force=1.25,-30.5,0.10000000000000001" in ln
                                       and "torque=0.5,0,-0.25" in ln for ln in lines)
        assert any(ln.endswith(" figure=jill site=hand_l.palm mass=4.2000000000000002")
                   for ln in lines)
        c.request("delete load push")
        c.request("add load jill head.origin force=0,5,0 as other")
        c.request("load session s.session")
        assert c.request("list loads") == kept  # ids, names, numbers bit for bit
        # the ids' generations go on from the session's: a new load is not an old id
        new = c.request("add load jack head.origin mass=2")["load"]
        assert new not in {x["load"] for x in kept["loads"]}
        # a session of version 4 (before loads) still loads, with none
        old = re.sub(r"^load .*\n", "", text.replace("session 5\n", "session 4\n"), flags=re.M)
        (daemon.state_dir / "old.session").write_text(old)
        c.request("load session old.session")
        assert c.request("list loads")["loads"] == []
        assert len(c.request("list figures")["figures"]) == 2
        # a session naming a load badly is refused whole, and the state stays
        c.request("load session s.session")
        good = "site=hand_l.palm mass=4.2000000000000002"
        for bad, words in [("site=hand_l.nowhere mass=4.2", "load bag: jill has no site"),
                           ("site=hand_l.palm mass=-4", "load bag: mass="),
                           ("site=hand_l.palm mass=nan", "load bag: mass="),
                           ("site=hand_l.palm mass=5000", "load bag: out of range"),
                           ("site=hand_l.palm mass=4 force=0,-40,0", "expected: load NAME")]:
            (daemon.state_dir / "bad.session").write_text(text.replace(good, bad))
            r = c.request_reply("load session bad.session")
            assert r["ok"] is False and words in r["error"]["message"], (bad, r)
            assert c.request("list loads") == kept


def test_undo_and_redo_take_loads_back_and_forth(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        c.request("add load jack hand_r.palm mass=3 as a")
        one = c.request("list loads")
        c.request("add load jack hand_l.palm force=0,0,12 as b")
        two = c.request("list loads")
        c.request("delete load a")
        three = c.request("list loads")
        c.request("undo")
        assert c.request("list loads") == two
        c.request("undo")
        assert c.request("list loads") == one
        c.request("redo")
        c.request("redo")
        assert c.request("list loads") == three


def test_a_crash_keeps_every_load_command(daemon):
    """kill -9 after each change: the journal's records give back what was replied."""
    with daemon.client() as c:
        add_some(c)
        c.request("delete load push")
        want = c.request("list loads")
    assert sum(1 for _, kind, body in journal_records(daemon.state_dir)
               if "load" in body and kind != "snapshot") >= 4
    daemon.restart()
    with daemon.client() as c:
        assert c.request("list loads") == want
        c.request("add load jill head.origin force=3,0,0 as late")
        want = c.request("list loads")
    daemon.restart()
    with daemon.client() as c:
        assert c.request("list loads") == want
    daemon.stop()  # a clean stop: the snapshot alone
    daemon.start()
    with daemon.client() as c:
        assert c.request("list loads") == want


def test_a_crash_keeps_what_the_loads_do(daemon_factory):
    """kill -9 with a box carried in two hands and loads on both: the analysis after
    recovery is the one before, number for number."""
    d = daemon_factory(extra=LIBRARY)
    with d.client() as c:
        box_scene(c, at=(0.05, 0.75, 0.3))
        c.request("grab jack right box")
        c.request("hold hand jack left box")
        c.request("add load box box.top mass=3")
        c.request("add load jack head.origin force=0,-20,5")
        c.request("settle")
        before = c.request("analyze loads jack")
    d.restart()
    with d.client() as c:
        after = c.request("analyze loads jack")
    before.pop("frame"), after.pop("frame")
    assert after == before


# ---- what the hands carry -------------------------------------------------------------

def carried(c, fig="jack"):
    return {(x["hand"], x["load"]): x for x in c.request(f"list loads {fig}")["carried"]}


def box_scene(c, at=(-0.25, 0.75, 0.35)):
    c.request("load human as jack")
    c.request("behave jack on")
    c.request("load figure lib:box.fig as box")
    c.request("set location box %g %g %g" % at)
    c.request("settle")


def test_a_grabbed_object_weighs_on_the_hand_at_its_centre_of_mass(daemon_factory):
    with daemon_factory(extra=LIBRARY).client() as c:
        box_scene(c)
        assert c.request("list loads")["carried"] == []
        c.request("grab jack right box")
        c.request("add load box box.top mass=2.5 as books")  # something in the box
        c.request("settle")
        box = c.request("show figure box")
        got = carried(c)
        books_id = c.request("list loads box")["loads"][0]["load"]
        assert set(got) == {("right", None), ("right", books_id)}
        weight = got[("right", None)]
        assert weight["object"] == "box" and weight["share"] == 1
        assert weight["mass"] == box["mass"] == 10
        assert close3(weight["force"], [0, -10 * G, 0], 1e-12)
        assert close3(weight["position"], box["com"], 1e-9)  # the weight at the centre of mass
        books = got[("right", books_id)]
        top = c.request("get site box box.top")["position"]
        assert books["mass"] == 2.5 and close3(books["position"], top, 1e-9)
        # the box follows the hand: its weight stays at its centre of mass
        c.request("move hand jack right 0,1.1,0.4")
        c.request("settle")
        assert close3(carried(c)[("right", None)]["position"],
                      c.request("show figure box")["com"], 1e-9)
        c.request("release hand jack right")
        assert c.request("list loads")["carried"] == []


def lever_shares(p_left, p_right, com):
    """The lever rule on the floor plane (x, z): the right hand's share t, clamped."""
    d = [p_right[0] - p_left[0], p_right[2] - p_left[2]]
    span2 = d[0] ** 2 + d[1] ** 2
    t = ((com[0] - p_left[0]) * d[0] + (com[2] - p_left[2]) * d[1]) / span2
    t = min(1.0, max(0.0, t))
    return 1 - t, t


@pytest.mark.parametrize("box_x", [-0.12, 0.05, 0.6])
def test_two_hands_share_the_weight_by_the_lever_rule(daemon_factory, box_x):
    """grab with the right hand, hold hand with the left on the box: each hand carries its
    lever-rule share of the weight (0.6: the centre of mass beyond the left palm, all on the
    left), and the two shares together are the weight at the centre of mass (equal force
    and moment about the origin)."""
    with daemon_factory(extra=LIBRARY).client() as c:
        box_scene(c, at=(box_x, 0.75, 0.3))
        c.request("grab jack right box")
        c.request("hold hand jack left box")
        c.request("settle")
        got = carried(c)
        left, right = got[("left", None)], got[("right", None)]
        p_l = c.request("get site jack hand_l.palm")["position"]
        p_r = c.request("get site jack hand_r.palm")["position"]
        box = c.request("show figure box")
        s_l, s_r = lever_shares(p_l, p_r, box["com"])
        assert left["share"] == pytest.approx(s_l, abs=1e-12)
        assert right["share"] == pytest.approx(s_r, abs=1e-12)
        if box_x == 0.6:
            assert left["share"] == 1 and right["share"] == 0
        else:
            assert 0.05 < right["share"] < 0.95
        W = [0, -10 * G, 0]
        total = [left["force"][i] + right["force"][i] for i in range(3)]
        assert close3(total, W, 1e-12)
        assert left["mass"] + right["mass"] == pytest.approx(10, abs=1e-12)
        moment = [a + b for a, b in zip(cross(left["position"], left["force"]),
                                        cross(right["position"], right["force"]))]
        assert close3(moment, cross(box["com"], W), 1e-9)
        # a share's point: its palm moved by the centre of mass's offset from the palms'
        # weighted middle (stated in load_set.h)
        mid = [s_l * a + s_r * b for a, b in zip(p_l, p_r)]
        for x, p in ((left, p_l), (right, p_r)):
            assert close3(x["position"], [p[i] + box["com"][i] - mid[i] for i in range(3)], 1e-9)


def test_more_than_two_hands_share_equally(daemon_factory):
    """Two people carrying one box, three hands on it: a third each (the rule for more than
    two hands), together the weight at the centre of mass."""
    with daemon_factory(extra=LIBRARY).client() as c:
        box_scene(c, at=(0.05, 0.75, 0.3))
        c.request("load human as jill")
        c.request("set location jill 0 0 0.7")
        c.request("behave jill on")
        c.request("grab jack right box")
        c.request("hold hand jack left box")
        c.request("hold hand jill right box")
        c.request("settle")
        hands = c.request("list loads")["carried"]
        assert sorted((x["figure"], x["hand"]) for x in hands) == [
            ("jack", "left"), ("jack", "right"), ("jill", "right")]
        box = c.request("show figure box")
        W = [0, -10 * G, 0]
        for x in hands:
            assert x["share"] == pytest.approx(1 / 3, abs=1e-15)
            assert close3(x["force"], [w / 3 for w in W], 1e-12)
        assert close3(add3(*(x["force"] for x in hands)), W, 1e-12)
        moment = add3(*(cross(x["position"], x["force"]) for x in hands))
        assert close3(moment, cross(box["com"], W), 1e-9)
        # each person's analysis counts its own hands' shares
        assert len(c.request("analyze loads jill")["loads"]) == 1


def test_a_place_held_on_a_fixed_thing_carries_nothing(daemon_factory):
    """hold hand on a table (not grabbed by anyone): the hand follows it, it weighs nothing
    on the hand; the same as soon as the box is grabbed by the other hand weighs."""
    with daemon_factory(extra=LIBRARY).client() as c:
        box_scene(c)
        c.request("load figure lib:table.fig as table")
        c.request("set location table 0 0 0.75")
        c.request("move hand jack left 0.2,0.95,0.3")
        c.request("settle")
        c.request("hold hand jack left table.table")
        c.request("hold hand jack right box")
        c.request("settle")
        assert c.request("list loads")["carried"] == []
        c.request("release hand jack right")
        c.request("grab jack right box")
        got = carried(c)
        assert set(got) == {("right", None)} and got[("right", None)]["share"] == 1


# ---- analyze loads ----------------------------------------------------------------------

def add3(*vs):
    return [sum(v[i] for v in vs) for i in range(3)]


def residual(c, fig, r):
    """The whole body's equilibrium from a reply alone and the figure's weight at its centre
    of mass (show figure): sum of forces and of moments about the origin, and their scale."""
    body = c.request(f"show figure {fig}")
    W = [0, -r["weight"], 0]
    assert r["weight"] == pytest.approx(body["mass"] * G, rel=1e-12)
    force, moment = list(W), cross(body["com"], W)
    for s in r["supports"]:
        force = add3(force, s["force"])
        moment = add3(moment, cross(s["point"], s["force"]), s["moment"])
    for x in r["loads"]:
        force = add3(force, x["force"])
        moment = add3(moment, cross(x["point"], x["force"]), x["torque"])
    scale = r["weight"] + sum(math.sqrt(sum(v * v for v in x["force"])) for x in r["loads"])
    return force, moment, scale


def assert_equilibrium(c, fig, r):
    force, moment, scale = residual(c, fig, r)
    assert max(abs(v) for v in force) <= 1e-9 * scale, force
    assert max(abs(v) for v in moment) <= 1e-9 * scale, moment  # lever arms about 1 m


def test_the_whole_body_is_in_equilibrium_under_every_kind_of_load(daemon_factory):
    """Supports + loads + weight = 0, force and moment, to 1e-9 relative: standing still, a
    push on a hand with a torque, a weight on the other, a box carried in two hands, seated,
    and a figure that is no human (held at its root)."""
    with daemon_factory(extra=LIBRARY).client() as c:
        box_scene(c, at=(0.05, 0.75, 0.3))
        r = c.request("analyze loads jack")
        assert r["loads"] == [] and len(r["supports"]) == 2
        assert_equilibrium(c, "jack", r)
        c.request("add load jack hand_r.palm force=15,-60,25 torque=1,-2,0.5 as push")
        c.request("add load jack hand_l.palm mass=4 as bag")
        assert_equilibrium(c, "jack", c.request("analyze loads jack"))
        c.request("grab jack right box")
        c.request("hold hand jack left box")
        c.request("bend torso jack 30deg 8deg 10deg")
        c.request("settle")
        r = c.request("analyze loads jack")
        assert len(r["loads"]) == 4  # push, bag, and each hand's share of the box
        assert_equilibrium(c, "jack", r)
        # the analysis's loads are list loads' own and carried ones, at the same points
        listed = c.request("list loads jack")
        points = sorted(tuple(round(v, 12) for v in x["point"]) for x in r["loads"])
        assert points == sorted(tuple(round(v, 12) for v in x["position"])
                                for x in listed["loads"] + listed["carried"])
        c.request("set behavior jack seated=on")
        c.request("settle")
        r = c.request("analyze loads jack")
        assert r["seated"] is True and {s["kind"] for s in r["supports"]} >= {"seat"}
        assert_equilibrium(c, "jack", r)
        r = c.request("analyze loads box")  # carried: the statics of any figure
        assert r["low_back"] is None and "not a human" in r["low_back_why"]
        assert r["strength"] is None
        assert_equilibrium(c, "box", r)


def test_the_low_back_is_fed_what_the_body_above_l5_s1_carries(daemon):
    """The low back model's input is the negated wrench of spine_0 (the L5/S1 joint): its
    sagittal, lateral and axial moments are that moment's parts on three orthogonal axes,
    and the disc's compression less the muscle force, with the two shears, that force's."""
    with daemon.client() as c:
        c.request("load human as jack")
        c.request("behave jack on")
        c.request("bend torso jack 40deg 10deg -10deg")
        c.request("set joint jack shoulder_r 80deg 0 0")
        c.request("add load jack hand_r.palm mass=12")
        r = c.request("analyze loads jack")
        lb, j = r["low_back"], r["joints"]["spine_0"]
        assert lb["level"] == "L5/S1" and lb["limit"]["action"] == 3400 and \
            lb["limit"]["max"] == 6400 and lb["limit"]["zone"] == "below_action"
        assert "abdominal_pressure" in lb["unmodelled"]
        m2 = lb["moment_sagittal"] ** 2 + lb["moment_lateral"] ** 2 + lb["moment_axial"] ** 2
        assert m2 == pytest.approx(sum(v * v for v in j["moment"]), rel=1e-9)
        f2 = (lb["compression"] - lb["muscle_force"]) ** 2 + lb["shear_ap"] ** 2 + \
            lb["shear_lat"] ** 2
        assert f2 == pytest.approx(sum(v * v for v in j["force"]), rel=1e-9)
        # and its sense: bent forward with 12 kg held out, the extensors pull (the moment
        # flexes the trunk) and the disc is pressed by about the weight above it and in the
        # hand (the disc tilts a few degrees: within 10 %)
        body = c.request("show figure jack")
        legs = ("pelvis", "thigh", "shank", "foot", "toes")
        above = sum(s["mass"] for s in body["segments"] if not s["name"].startswith(legs))
        assert lb["moment_sagittal"] > 0 and lb["muscle_force"] > 0
        assert "flexors" not in lb["unmodelled"]
        pressed = lb["compression"] - lb["muscle_force"]
        assert 0.9 * (above + 12) * G < pressed <= (above + 12) * G * (1 + 1e-12)
        # heavier in the hand: more compression (Chaffin's model is monotone in the load)
        c.request("add load jack hand_r.palm mass=10")
        assert c.request("analyze loads jack")["low_back"]["compression"] > lb["compression"] + 50


def test_a_family_is_analysed_member_by_member(daemon):
    with daemon.client() as c:
        c.request("load family f sex=both n=2")
        c.request("add load f_male_1 hand_r.palm mass=8")
        fam = c.request("analyze loads family=f")
        names = [m["figure"] for m in fam["figures"]]
        assert fam["family"] == "f" and names == [f"f_{s}_{i}" for s in ("female", "male")
                                                  for i in range(3)]
        for m in fam["figures"]:
            one = c.request(f"analyze loads {m['figure']}")
            m.pop("frame"), one.pop("frame")  # the live frames run on between the two
            assert m == one
            assert_equilibrium(c, m["figure"], m)
        assert [len(m["loads"]) for m in fam["figures"]] == [0, 0, 0, 0, 1, 0]


ANALYZE_BAD = [
    ("analyze loads gone", "not-found", "no figure 'gone'"),
    ("analyze loads family=nope", "not-found", "no family 'nope'"),
    ("analyze loads family=", "not-found", "no family"),
    ("analyze loads jack extra", "arity", "analyze loads FIG|family=PREFIX"),
    ("analyze loads", "arity", "analyze loads"),
    ("analyze things jack", "unknown-command", "loads"),
]


def test_analyze_refuses_what_it_cannot_analyse_and_changes_nothing(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        c.request("add load jack hand_r.palm mass=5 as bag")
        before = loads_state(c)
        for line, code, words in ANALYZE_BAD:
            r = c.request_reply(line)
            assert r["ok"] is False and r["error"]["code"] == code, (line, r)
            assert words in r["error"]["message"], (line, r["error"]["message"])
            assert loads_state(c) == before, line


# ---- live: events, the status line, only when asked ------------------------------------

TELL_COMPRESSION_N, TELL_SUPPORT_N, TELL_CAPABLE_PCT = 50.0, 10.0, 1.0  # events.c's thresholds


def told_of(r):
    """What a loads event would tell of an analysis (events.c, loads_told_of)."""
    lb, st = r["low_back"], r["strength"]
    weak = st and st["weakest"]
    return {"compression": lb["compression"], "zone": lb["limit"]["zone"],
            "weakest": (weak["joint"], weak["axis"]) if weak else None,
            "capable": st["capable"] if weak else None,
            "supports": [(s["site"], s["force"]) for s in r["supports"]],
            "tips": r["balance"]["tips"],
            "loads": [(x["load"], x["carried"], x["hand"]) for x in r["loads"]]}


def tells(was, now):
    """events.c's loads_changed, written out again: is now worth an event after was?"""
    if (was["zone"], was["weakest"], was["tips"], was["loads"]) != \
            (now["zone"], now["weakest"], now["tips"], now["loads"]):
        return True
    if [s for s, _ in was["supports"]] != [s for s, _ in now["supports"]]:
        return True
    if abs(now["compression"] - was["compression"]) >= TELL_COMPRESSION_N:
        return True
    if now["weakest"] and abs(now["capable"] - was["capable"]) >= TELL_CAPABLE_PCT:
        return True
    return any(math.dist(a, b) >= TELL_SUPPORT_N
               for (_, a), (_, b) in zip(was["supports"], now["supports"]))


def test_an_event_tells_a_load_added_at_its_frame(daemon_factory):
    d = daemon_factory(fps=1)
    with d.client() as c, d.client() as watch:
        c.request("load human as jack")
        watch.subscribe("loads")
        first = watch.next_event(timeout=5)  # what a new subscriber hears: the analysis now
        assert first["event"] == "loads" and first["figure"] == "jack" and first["loads"] == 0
        assert first["low_back"]["level"] == "L5/S1"
        assert [s["site"] for s in first["supports"]] == ["foot_l.balance", "foot_r.balance"]
        assert watch.next_event(timeout=0.3) is None  # at rest: nothing more
        replies = c.pipeline(["add load jack hand_r.palm force=0,0,5 as nudge",
                              "analyze loads jack"])
        now = replies[1]["result"]
        ev = watch.next_event(timeout=5)
        # a 5 N push changes no number past a threshold, but a load added is told
        assert ev["frame"] == now["frame"] and ev["loads"] == 1
        assert ev["low_back"]["compression"] == now["low_back"]["compression"]
        assert ev["supports"] == [{"site": s["site"], "force": s["force"]} for s in now["supports"]]
        assert ev["weakest"] is None or ev["weakest"]["percent_capable"] == \
            now["strength"]["capable"]
        c.request("delete load nudge")
        assert watch.next_event(timeout=5)["loads"] == 0


def test_a_drag_tells_the_compression_at_the_frame_it_changes(daemon_factory):
    """A hand holding 10 kg dragged up and forward along an arc, a frame at a time: each
    loads event comes at the very frame whose analysis first differs from the last one told
    by a threshold (events.c, written out again in tells()), and at no other frame."""
    d = daemon_factory(fps=1)  # live frames far apart: the drag's frames are settle's
    with d.client() as c, d.client() as watch:
        c.request("load human as jack")
        c.request("add load jack hand_r.palm mass=10 as weight")
        shoulder = c.request("get site jack upperarm_r.origin")["position"]
        c.request("add constraint jack effector=hand_r.palm as drag start=shoulder_r "
                  f"goal={shoulder[0]},{shoulder[1] - 0.58},{shoulder[2] + 0.05}")
        c.request("settle frames=20")
        watch.subscribe("loads")
        told = watch.next_event(timeout=5)
        seen = {}
        for step in range(0, 121, 6):
            t = math.radians(step)
            goal = (shoulder[0], shoulder[1] - 0.58 * math.cos(t), shoulder[2] + 0.58 * math.sin(t))
            replies = c.pipeline(["set goal drag %.6f %.6f %.6f" % goal, "settle frames=1",
                                  "analyze loads jack"])
            assert all(r["ok"] for r in replies), replies
            got = replies[2]["result"]
            seen[got["frame"]] = told_of(got)
        events = [e for e in watch.events(timeout=1.0) if e["figure"] == "jack"]
    frames = sorted(seen)
    assert frames == list(range(frames[0], frames[-1] + 1)), "a frame ran unseen"
    assert seen[frames[-1]]["compression"] > seen[frames[0]]["compression"] + 500
    last = {"compression": told["low_back"]["compression"],
            "zone": told["low_back"]["limit"]["zone"],
            "weakest": None, "capable": None, "tips": told["tips"],
            "supports": [(s["site"], s["force"]) for s in told["supports"]],
            "loads": seen[frames[0]]["loads"]}
    if told["weakest"]:
        last["weakest"] = (told["weakest"]["joint"], told["weakest"]["axis"])
        last["capable"] = told["weakest"]["percent_capable"]
    expected = []
    for f in frames:
        if tells(last, seen[f]):
            expected.append(f)
            last = seen[f]
    assert len(expected) >= 5
    assert [e["frame"] for e in events] == expected
    for e in events:
        assert e["low_back"]["compression"] == seen[e["frame"]]["compression"]


def test_the_loops_own_frames_tell_the_change_with_no_command_running(daemon_factory):
    """A goal moved, then the loop's own frames (as a drag at the kiosk runs): the loads
    event of the frame that moved the arm comes while no command runs, numbered as that
    frame, the one right after the goal moved."""
    d = daemon_factory(fps=10)
    with d.client() as c, d.client() as watch:
        c.request("load human as jack")
        c.request("add load jack hand_r.palm mass=10")
        shoulder = c.request("get site jack upperarm_r.origin")["position"]
        arc = [(shoulder[0], shoulder[1] - 0.58 * math.cos(math.radians(t)),
                shoulder[2] + 0.58 * math.sin(math.radians(t))) for t in (30, 50)]
        c.request("add constraint jack effector=hand_r.palm as drag start=shoulder_r "
                  "goal=%.6f,%.6f,%.6f" % arc[0])
        c.request("settle frames=20")
        watch.subscribe("loads")
        told = watch.next_event(timeout=5)
        replies = c.pipeline(["set goal drag %.6f %.6f %.6f" % arc[1], "analyze loads jack"])
        moved_at = replies[1]["result"]["frame"]
        event = watch.next_event(timeout=5)  # c sends nothing meanwhile
        assert event["frame"] == moved_at + 1
        assert event["low_back"]["compression"] > told["low_back"]["compression"] + 50


def test_the_status_line_shows_the_low_back_and_the_weakest_joint(daemon):
    with daemon.client() as c:
        c.request("add view main width=1280 height=400 eye=0,1.4,5 target=0,0.9,0")
        c.request("load human as jack")
        c.request("add load jack hand_r.palm mass=20")
        c.request("manipulate figure jack view=main")
        c.request("render view main")
        line = c.request("get kiosk")["status"]
        r = c.request("analyze loads jack")
        part = "   L5/S1 %.1f kN" % (r["low_back"]["compression"] / 1000)
        if r["strength"]["capable"] is not None:
            part += ", %d %% capable" % math.floor(r["strength"]["capable"])
        else:  # no published strength model ships: no number made up
            assert "capable" not in line
        rula, reba = c.request("assess rula jack")["score"], c.request("assess reba jack")["score"]
        assert f"   RULA {rula}, REBA {reba}{part}   frame " in line, line


def test_nothing_is_analysed_unless_asked(daemon):
    with daemon.client() as c, daemon.client() as watch:
        c.request("load human as jack")
        c.request("add load jack hand_r.palm mass=5")
        c.request("add constraint jack effector=hand_r.palm as reach start=shoulder_r "
                  "goal=-0.2,1.3,0.45")
        before = c.request("status")["load_analyses"]
        c.request("settle frames=5")
        assert c.request("status")["load_analyses"] == before
        watch.subscribe("loads")
        watch.next_event(timeout=5)
        n0 = c.request("status")["load_analyses"]
        c.request("set goal reach -0.2 1.6 0.45")
        ran = c.request("settle frames=20")["frames"]
        n1 = c.request("status")["load_analyses"]
        assert 1 <= n1 - n0 <= ran + 2, (n0, n1, ran)
        c.request("settle frames=10")  # at rest: the cache answers
        assert c.request("status")["load_analyses"] - n1 <= 2


# ---- a recording replayed -------------------------------------------------------------

def test_a_recording_replays_to_the_same_analysis(daemon_factory, tmp_path):
    """Loads added and deleted, a box grabbed and held in two hands, the arm moved, a
    session saved and loaded: `--replay ... --after` analyses the replayed state and gets
    the live analysis, number for number."""
    import subprocess
    from daemon import POSTURED
    rec = tmp_path / "rec"
    d = daemon_factory(fps=200, extra=LIBRARY + ("--record", str(rec)))
    with d.client() as c:
        box_scene(c, at=(0.05, 0.75, 0.3))
        c.request("add load jack hand_r.palm force=5,-20,8 as push")
        c.request("add load jack head.origin mass=2 as hat")
        c.request("grab jack right box")
        c.request("hold hand jack left box")
        c.request("add load box box.top mass=3")
        c.request("move hand jack right 0.0,1.05,0.45")
        c.request("settle")
        c.request("delete load push")
        c.request("save session s.session")
        c.request("add load jack hand_l.palm mass=9")
        c.request("load session s.session")
        c.request("settle")
        live = c.request("analyze loads jack")
        again = c.request("analyze loads jack")
        live.pop("frame"), again.pop("frame")
        assert live == again, "not at rest"
        assert len(live["loads"]) == 5  # the hat, each hand's share of the box and of its load
    d.stop()
    after = tmp_path / "after.txt"
    after.write_text("analyze loads jack\n")
    p = subprocess.run([str(POSTURED), "--replay", str(rec), "--after", str(after)],
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    import json
    replies = [json.loads(ln[len("reply: "):]) for ln in p.stdout.splitlines()
               if ln.startswith("reply: ")]
    assert len(replies) == 1 and replies[0]["ok"], p.stdout
    replayed = replies[0]["result"]
    replayed.pop("frame")
    assert replayed == live


def test_more_loads_than_the_statics_solves_are_refused_clearly(daemon_factory):
    """64 loads on a box, carried in one hand: 65 loads on the hand's figure, one more than
    the statics solves: analyze refuses it and says so, the rest goes on."""
    with daemon_factory(extra=LIBRARY).client() as c:
        box_scene(c)
        c.request("grab jack right box")
        added = c.pipeline([f"add load box box.top mass=0.1 as w{i}" for i in range(64)])
        assert all(r["ok"] for r in added)
        r = c.request_reply("add load jack head.origin mass=1")
        assert r["error"]["code"] == "limit" and "64 loads at most" in r["error"]["message"]
        err = c.request_reply("analyze loads jack")["error"]
        assert err["code"] == "bad-argument" and "65 loads" in err["message"], err
        assert len(c.request("list loads jack")["carried"]) == 65
        c.request("delete load w0")
        assert len(c.request("analyze loads jack")["loads"]) == 64
