"""Behaviours through the daemon: the figures of Chapter 5 by commands, and
behaviour state that survives kill -9 exactly."""
import math

from conftest import ROOT
from daemon import Daemon, daemon, daemon_factory  # noqa: F401 (fixtures)

LIBRARY = ["--library", str(ROOT / "src" / "figure" / "library")]  # lib:box.fig, lib:table.fig


def settled(c, frames=400):
    r = c.request(f"settle frames={frames}")
    assert r["settled"], r
    return r


def test_dragging_the_centre_of_mass_forward_takes_a_step(daemon):
    """Figure 5.6: past the front of the feet the figure steps, and the balance point
    ends inside the new support polygon."""
    with daemon.client() as c:
        c.request("load human as jack")
        c.request("behave jack on")
        c.request("move com jack 0 0.35")
        settled(c)
        b = c.request("get behavior jack")
        assert b["steps"] >= 1
        assert not b["stepping"]
        assert b["balance"]["margin"] > 0
        bal = c.request("get balance jack")
        assert bal["margin"] > 0


def test_shifting_weight_keeps_the_feet_and_centres_the_mass(daemon):
    """Figure 5.4 by commands: both feet stay put to the millimetre, the centre of mass
    ends over the new balance point."""
    with daemon.client() as c:
        behaving_jack(c)
        feet = toes(c)
        c.request("move com jack 0.07 0")
        settled(c)
        for a, b in zip(feet, toes(c)):
            assert near(a, b, 1e-3)
        b = c.request("get behavior jack")
        held, point = b["balance"]["held"], b["balance"]["point"]
        assert max(abs(x - y) for x, y in zip(held, point)) < 5e-3
        assert b["balance"]["x"] < 0.3


def test_behaviour_state_survives_kill_9_exactly():
    """A settled, behaving figure comes back to the bit after kill -9: posture, balance
    parameters, the root the behaviours chose, the steps taken."""
    d = Daemon()
    d.start()
    try:
        with d.client() as c:
            c.request("load human as jack")
            c.request("behave jack on")
            c.request("set behavior jack foot=pivot hands=hips")
            c.request("move com jack 0.04 0.30")
            settled(c)
            before = (c.request("get posture jack"), c.request("get behavior jack"),
                      c.request("list constraints"))
        d.kill9()
        d.start()
        with d.client() as c:
            after = (c.request("get posture jack"), c.request("get behavior jack"),
                     c.request("list constraints"))
        assert after == before
    finally:
        d.stop()
        d.cleanup()


def signed_distance(poly, p):
    """Signed distance from p to a convex polygon's boundary (> 0 inside): the reference
    the daemon's stability margin is checked against."""
    best, inside = float("inf"), True
    for i, a in enumerate(poly):
        c = poly[(i + 1) % len(poly)]
        e = (c[0] - a[0], c[1] - a[1])
        w = (p[0] - a[0], p[1] - a[1])
        t = max(0.0, min(1.0, (w[0] * e[0] + w[1] * e[1]) / (e[0] ** 2 + e[1] ** 2)))
        q = (a[0] + t * e[0] - p[0], a[1] + t * e[1] - p[1])
        best = min(best, (q[0] ** 2 + q[1] ** 2) ** 0.5)
        if e[0] * w[1] - e[1] * w[0] < 0:
            inside = False
    return best if inside else -best


def test_stability_events_publish_the_polygon_and_alert_on_the_threshold(daemon):
    """Stability as data: every frame the support polygon, the balance point, the centre
    of mass on the floor and the margin (checked against an independent signed distance);
    one alert when the margin drops below the figure's threshold, one when it recovers."""
    with daemon.client() as c:
        c.request("load human as jack")
        c.request("behave jack on")
        c.request("set behavior jack step=off stability=3cm")
        assert c.request("get behavior jack")["parameters"]["stability"] == 0.03
        c.subscribe("stability")
        c.subscribe("alert")
        settled(c)
        ev = [e for e in c.pending_events() if e["event"] == "stability"]
        assert ev, "no stability events"
        last = ev[-1]
        assert last["figure"] == "jack" and len(last["polygon"]) >= 3
        assert abs(signed_distance(last["polygon"], last["com"]) - last["margin"]) < 1e-6
        assert last["margin"] > 0.03 and not last["low"]
        # lean forward until 1 cm from the polygon's front edge, found independently
        poly, com = last["polygon"], last["com"]
        dz = 0.0
        while signed_distance(poly, (com[0], com[1] + dz + 0.001)) > 0.01:
            dz += 0.001
        c.request(f"move com jack 0 {dz}")
        settled(c)
        events = c.pending_events()
        alerts = [e for e in events if e["event"] == "alert"]
        assert [a["stability"] for a in alerts] == ["low"], alerts
        assert alerts[0]["margin"] < 0.03
        last = [e for e in events if e["event"] == "stability"][-1]
        assert last["low"] and 0 < last["margin"] < 0.03
        assert abs(signed_distance(last["polygon"], last["com"]) - last["margin"]) < 1e-6
        c.request(f"move com jack 0 {-dz}")
        settled(c)
        alerts = [e for e in c.pending_events() if e["event"] == "alert"]
        assert [a["stability"] for a in alerts] == ["ok"], alerts
        c.unsubscribe("stability")
        c.unsubscribe("alert")
        # a live frame may have sent some just before the unsubscribe took effect: those
        # came before its reply; after it, none may come
        c.pending_events()
        c.request("settle frames=5")
        assert not [e for e in c.pending_events() if e["event"] in ("stability", "alert")]


def test_past_a_foot_the_support_foot_steps_out_sideways(daemon):
    """§D.3.1: with the balance point pushed out past the left foot, the left (support)
    foot steps out to the side; the right foot stays; the balance ends inside."""
    with daemon.client() as c:
        behaving_jack(c)
        feet = toes(c)
        c.request("move com jack 0.20 0")
        settled(c)
        after = toes(c)
        b = c.request("get behavior jack")
        assert b["steps"] >= 1 and not b["stepping"]
        assert after[0][0] - feet[0][0] > 0.15
        assert max(abs(x - y) for x, y in zip(after[1], feet[1])) < 2e-3
        assert b["balance"]["margin"] > 0


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def transpose(a):
    return [list(r) for r in zip(*a)]


def relative(c, frame, other):
    """other's pose in frame's: (position, rotation), from two `get site` replies."""
    f, o = c.request(f"get site {frame}"), c.request(f"get site {other}")
    rf, ro = f["rotation"], o["rotation"]
    if len(rf) == 9:
        rf, ro = [rf[0:3], rf[3:6], rf[6:9]], [ro[0:3], ro[3:6], ro[6:9]]
    d = [o["position"][i] - f["position"][i] for i in range(3)]
    rt = transpose(rf)
    return [sum(rt[i][k] * d[k] for k in range(3)) for i in range(3)], matmul(rt, ro)


def close(a, b, tol):
    pa, ra = a
    pb, rb = b
    return (max(abs(x - y) for x, y in zip(pa, pb)) < tol and
            max(abs(ra[i][j] - rb[i][j]) for i in range(3) for j in range(3)) < tol)


def test_a_grabbed_object_follows_the_hand_until_released(daemon_factory):
    """Figure 5.10 / Table D.4: after `grab` the box keeps its pose in the palm's frame
    while the hand is dragged; after `release` the box stays where it was put."""
    with daemon_factory(extra=LIBRARY).client() as c:
        c.request("load human as jack")
        c.request("behave jack on")
        c.request("load figure lib:box.fig as box")
        c.request("set location box -0.25 0.75 0.35")
        settled(c)
        c.request("grab jack right box")
        held = relative(c, "jack hand_r.palm", "box box.base")
        c.request("move hand jack right -0.15,1.1,0.4")
        settled(c)
        assert close(relative(c, "jack hand_r.palm", "box box.base"), held, 1e-9)
        palm = c.request("get site jack hand_r.palm")["position"]
        assert max(abs(a - b) for a, b in zip(palm, (-0.15, 1.1, 0.4))) < 2e-3
        b = c.request("get behavior jack")
        assert b["attachments"] == [{"limb": "hand", "side": "right", "kind": "grab",
                                     "object": "box", "segment": "box"}]
        # the box is its own figure still: it cannot behave while held, nor be grabbed twice
        assert c.request_reply("grab jack left box")["ok"] is False
        assert c.request_reply("grab jack right jack")["ok"] is False
        assert c.request("release hand jack right") == {"released": True}
        put = c.request("get site box box.base")
        c.request("move hand jack right -0.3,0.9,0.2")
        settled(c)
        assert c.request("get site box box.base") == put
        assert c.request("release hand jack right") == {"released": False}


def test_a_hand_holding_a_local_location_follows_the_object(daemon_factory):
    """Hold local location: the hand keeps its place on the table; when the table is
    moved, the hand goes with it (±2 mm), the rest of the body keeps its constraints."""
    with daemon_factory(extra=LIBRARY).client() as c:
        c.request("load human as jack")
        c.request("behave jack on")
        c.request("load figure lib:table.fig as table")
        c.request("set location table 0 0 0.75")
        c.request("move hand jack right -0.2,0.95,0.3")
        settled(c)
        c.request("hold hand jack right table.table")
        before = c.request("get site jack hand_r.palm")["position"]
        feet = [c.request(f"get site jack toes_{s}.toe")["position"] for s in "lr"]
        c.request("set location table 0.05 0 0.70")  # 5 cm left, 5 cm nearer
        settled(c)
        after = c.request("get site jack hand_r.palm")["position"]
        want = (before[0] + 0.05, before[1], before[2] - 0.05)
        assert max(abs(a - b) for a, b in zip(after, want)) < 2e-3, (after, want)
        for s, f in zip("lr", feet):
            now = c.request(f"get site jack toes_{s}.toe")["position"]
            assert max(abs(a - b) for a, b in zip(now, f)) < 1e-3
        b = c.request("get behavior jack")
        assert b["attachments"][0]["kind"] == "local"
        assert b["attachments"][0]["object"] == "table"
        # moving the hand by command lets go of the table
        c.request("move hand jack right -0.2,1.0,0.2")
        assert c.request("get behavior jack")["attachments"] == []
        assert c.request_reply("hold hand jack right table.nothing")["ok"] is False
        assert c.request_reply("hold hand jack middle table")["ok"] is False


def test_grabs_survive_kill_9_and_session_files():
    """The attachment is state: it comes back after kill -9 (journal and snapshot), and
    a saved session reloads with it, the box still following the hand."""
    d = Daemon(extra=LIBRARY)
    d.start()
    try:
        with d.client() as c:
            c.request("load human as jack")
            c.request("behave jack on")
            c.request("load figure lib:box.fig as box")
            c.request("set location box -0.25 0.75 0.35")
            c.request("grab jack right box")
            c.request("move hand jack right -0.15,1.1,0.4")
            settled(c)
            before = (c.request("get behavior jack"), c.request("get site box box.base"),
                      c.request("get posture jack"))
            c.request("save session grab.session")
        d.kill9()
        d.start()
        with d.client() as c:
            after = (c.request("get behavior jack"), c.request("get site box box.base"),
                     c.request("get posture jack"))
            assert after == before
            c.request("unload figure box")
            assert c.request("get behavior jack")["attachments"] == []
            c.request("load session grab.session")
            assert c.request("get behavior jack")["attachments"] == before[0]["attachments"]
            held = relative(c, "jack hand_r.palm", "box box.base")
            c.request("move hand jack right -0.1,1.0,0.3")
            settled(c)
            assert close(relative(c, "jack hand_r.palm", "box box.base"), held, 1e-9)
    finally:
        d.stop()
        d.cleanup()


def site(c, ref):
    """(position, 3x3 rotation rows) of a site."""
    r = c.request(f"get site {ref}")
    rot = r["rotation"]
    if len(rot) == 9:
        rot = [rot[0:3], rot[3:6], rot[6:9]]
    return r["position"], rot


def angle_deg(u, v):
    dot = sum(a * b for a, b in zip(u, v))
    nu = sum(a * a for a in u) ** 0.5
    nv = sum(b * b for b in v) ** 0.5
    return math.degrees(math.acos(max(-1.0, min(1.0, dot / (nu * nv)))))


def toes(c):
    return [site(c, f"jack toes_{s}.toe")[0] for s in "lr"]


def near(a, b, tol):
    return max(abs(x - y) for x, y in zip(a, b)) < tol


def behaving_jack(c):
    c.request("load human as jack")
    c.request("behave jack on")
    settled(c)


def test_fig_5_3_moving_a_foot_keeps_the_balance_parameters(daemon):
    """Figure 5.3 by commands: with "balance point follows feet" the balance point's x and
    z stay (±0.02) as the left foot moves; with it off the point stays put in space."""
    for follow in ("on", "off"):
        with daemon.client() as c:
            behaving_jack(c)
            c.request(f"set behavior jack follow_feet={follow}")
            b0 = c.request("get behavior jack")["balance"]
            toe = site(c, "jack toes_l.toe")[0]
            c.request(f"move foot jack left {toe[0] + 0.05},{toe[1]},{toe[2] + 0.20}")
            settled(c)
            assert near(site(c, "jack toes_l.toe")[0], (toe[0] + 0.05, toe[1], toe[2] + 0.20), 2e-3)
            b1 = c.request("get behavior jack")["balance"]
            moved = math.dist(b0["point"], b1["point"])
            if follow == "on":
                assert abs(b1["x"] - b0["x"]) < 0.02 and abs(b1["z"] - b0["z"]) < 0.02
                assert moved > 0.03
            else:
                assert moved < 5e-3
            c.request("unload figure jack")


def test_fig_5_5_lowering_the_centre_of_mass_squats_and_roots_the_lower_torso(daemon):
    """Figure 5.5 by commands: 40 cm down, the hips stay square and the root moves to the
    lower torso (the centre of mass is below 70 % of the leg's length)."""
    with daemon.client() as c:
        behaving_jack(c)
        hips0 = site(c, "jack pelvis.lower_torso")[0][1]
        c.request("move com jack 0 0 -0.40")
        settled(c)
        b = c.request("get behavior jack")
        assert b["root"] == "lower torso"
        hips, pelvis = site(c, "jack pelvis.lower_torso")
        assert hips[1] < hips0 - 0.25
        assert abs(pelvis[1][0]) < math.sin(math.radians(3))  # its x axis stays level


def test_tiptoe_by_commands_lifts_the_heels_and_weights_the_balls_of_the_feet(daemon):
    """Tiptoe (Table D.1): heels allowed to rise, the centre of mass 5 cm up: the heels
    leave the floor, the toes stay (±1 mm), and the weight moves over the balls of the
    feet, between each foot's toe joint and toe tip; no step."""
    with daemon.client() as c:
        behaving_jack(c)
        c.request("set behavior jack heel=rise")
        settled(c)
        feet = toes(c)
        tips = [site(c, f"jack toes_{s}.tip")[0] for s in "lr"]
        com0 = c.request("get posture jack")["com"]
        c.request("move com jack 0 0 0.05")
        settled(c)
        b = c.request("get behavior jack")
        com = c.request("get posture jack")["com"]
        assert abs(com[1] - com0[1] - 0.05) < 3e-3
        assert b["steps"] == 0
        for s, toe, tip, toe0 in zip("lr", toes(c), tips, feet):
            assert near(toe, toe0, 1e-3)
            assert site(c, f"jack foot_{s}.heel")[0][1] > 0.03
            assert min(toe[2], tip[2]) < com[2] < max(toe[2], tip[2])


def test_fig_5_7_bending_forward_keeps_balance_with_feet_planted(daemon):
    """Figure 5.7 by commands: a 45 degree bend from the waist moves the hips back, the
    centre of mass stays over the balance point (±5 mm), both feet stay (±1 mm)."""
    with daemon.client() as c:
        behaving_jack(c)
        feet = toes(c)
        hips0 = site(c, "jack pelvis.lower_torso")[0][2]
        c.request("bend torso jack 45deg 0 0 flavor=waist")
        settled(c)
        b = c.request("get behavior jack")["balance"]
        assert math.dist(b["point"], b["held"]) < 5e-3
        assert site(c, "jack pelvis.lower_torso")[0][2] < hips0 - 0.03
        for a, f in zip(toes(c), feet):
            assert near(a, f, 1e-3)


def test_fig_5_8_pelvis_rotation_keeps_the_chest_vertical_and_a_twist_steps(daemon):
    """Figure 5.8 by commands: curling the pelvis 20 degrees leaves the chest vertical
    (±2 degrees); twisting it 70 degrees about the vertical makes the figure step."""
    with daemon.client() as c:
        behaving_jack(c)
        c.request("rotate pelvis jack rot=x,20deg")
        settled(c)
        _, chest = site(c, "jack T5.chest")
        _, pelvis = site(c, "jack pelvis.lower_torso")
        up_chest = [chest[0][1], chest[1][1], chest[2][1]]
        up_pelvis = [pelvis[0][1], pelvis[1][1], pelvis[2][1]]
        assert angle_deg(up_chest, (0, 1, 0)) < 2
        assert angle_deg(up_pelvis, (0, 1, 0)) > 12
        c.request("unload figure jack")
        behaving_jack(c)
        c.request("rotate pelvis jack yaw=70deg")
        settled(c)
        assert c.request("get behavior jack")["steps"] >= 1


def test_fig_5_9_5_10_a_hand_moves_while_head_and_eyes_stay_fixated(daemon):
    """Figures 5.9 / 5.10 by commands: the head and both eyes fixate a point (±1 degree,
    measured from the sites' own axes), the hand reaches its goal, the feet stay, and
    hands on hips survive a torso bend."""
    with daemon.client() as c:
        behaving_jack(c)
        feet = toes(c)
        look = (0.6, 1.2, 1.5)
        c.request("move head jack {},{},{}".format(*look))
        c.request("move eyes jack {},{},{}".format(*look))
        c.request("set behavior jack hand_orient=laban")  # a natural palm for the reach
        c.request("move hand jack right -0.25,1.15,0.35")
        settled(c)
        assert near(site(c, "jack hand_r.palm")[0], (-0.25, 1.15, 0.35), 1e-3)
        for ref in ("head.between_eyes", "eyeball_l.gaze", "eyeball_r.gaze"):
            p, rot = site(c, f"jack {ref}")
            axis = [rot[0][2], rot[1][2], rot[2][2]]  # the aim axis: the site's z
            to = [look[i] - p[i] for i in range(3)]
            assert angle_deg(axis, to) < 1, ref
        for a, f in zip(toes(c), feet):
            assert near(a, f, 1e-3)
        # hands on hips survive a bend
        c.request("set behavior jack hands=hips head=release eyes=release")
        settled(c)
        c.request("bend torso jack 30deg 0 0")
        settled(c)
        cons = c.request("get behavior jack")["parameters"]
        assert cons["hand_l"] == "hips" and cons["hand_r"] == "hips"
        # each palm on the side of its hip: 7 cm out and 6 cm up in the hip site's frame
        for s, sigma in (("l", 1), ("r", -1)):
            hip, rot = site(c, f"jack pelvis.hip_{s}")
            off = (sigma * 0.07, 0.06, 0.0)
            want = [hip[i] + sum(rot[i][k] * off[k] for k in range(3)) for i in range(3)]
            assert math.dist(site(c, f"jack hand_{s}.palm")[0], want) < 5e-3, s


def test_seated_a_heel_holding_a_pedal_follows_it(daemon_factory):
    """§D.1.1 seated: the heel holds the foot, and with hold local location on an object
    (here a box standing in for a pedal) the heel follows it as it moves (±1 mm); the
    lower torso stays the root and does not move."""
    with daemon_factory(extra=LIBRARY).client() as c:
        behaving_jack(c)
        c.request("set behavior jack seated=on")
        assert c.request("get behavior jack")["root"] == "lower torso"
        c.request("load figure lib:box.fig as pedal")
        c.request("set location pedal -0.1 0 0.4")
        c.request("hold foot jack right pedal")
        heel0 = site(c, "jack foot_r.heel")[0]
        hips0 = site(c, "jack pelvis.lower_torso")[0]
        c.request("set location pedal -0.1 0.04 0.46")  # up 4 cm, forward 6 cm
        settled(c)
        want = (heel0[0], heel0[1] + 0.04, heel0[2] + 0.06)
        assert near(site(c, "jack foot_r.heel")[0], want, 1e-3)
        assert near(site(c, "jack pelvis.lower_torso")[0], hips0, 1e-9)
        assert c.request("get behavior jack")["parameters"]["seated"] is True
