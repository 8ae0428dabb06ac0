"""can reach through the daemon: the verdict agrees with what the daemon's own
`move hand` + `settle` does to the figure on the same target, nothing the person
sees changes (the posture hash and every joint value), and bad requests are
refused with nothing changed."""
import math

import pytest
from posture.client import PostureError

from daemon import Daemon, daemon, daemon_factory  # noqa: F401 (fixtures)

TOL_POS = 1e-3               # m: reach.h's REACH_TOL_POS
TOL_ORI = math.radians(1.0)  # rad: REACH_TOL_ORI
# the figure's own solve polishes less (the knee and elbow springs of §D.1.6, goals walked
# frame by frame): its palm is said to be there within 5 mm; the targets are 20 cm or more
# inside or outside the arm's reach, so no verdict turns on the tolerance
TOL_MOVED = 5e-3


def palm(c, fig):
    s = c.request(f"get site {fig} hand_r.palm")
    return s["position"], s["rotation"]


def shoulder(c, fig):
    return c.request(f"get site {fig} clavicle_r.shoulder_r")["position"]


def angle_between(r, g):
    tr = sum(a * b for a, b in zip(r, g))
    return math.acos(max(-1.0, min(1.0, (tr - 1) / 2)))


# directions from the right shoulder (x left, y up, z forward) and distances: inside the
# arm's reach by 20 cm or more, or beyond it by 25 cm or more (the arm is about 0.65 m)
DIRECTIONS = [(0, 0, 1), (-1, 0, 0), (0, -1, 0), (-0.7, -0.7, 0), (0, -0.7, 0.7),
              (-0.6, 0, 0.8)]
DISTANCES = [0.35, 0.45, 0.9]


def targets(sh):
    for d in DIRECTIONS:
        n = math.sqrt(sum(x * x for x in d))
        for dist in DISTANCES:
            yield [sh[i] + dist * d[i] / n for i in range(3)]


def test_the_verdict_is_what_move_hand_and_settle_do(daemon):
    """mode=arm moves what the behaviours' hand constraint moves (the arm from the
    clavicle): on each target, the figure's own move hand + settle reaches it (palm
    within the tolerance) exactly when can reach says so."""
    with daemon.client() as c:
        c.request("load human as probe")
        sh = shoulder(c, "probe")
        agreed, checked = [], 0
        for i, t in enumerate(targets(sh)):
            fig = f"j{i}"
            c.request(f"load human as {fig}")
            c.request(f"behave {fig} on")
            c.request("settle frames=600")  # the behaviours stand it; then nothing moves
            xyz = ",".join(f"{x:.6f}" for x in t)
            before = c.request(f"get posture {fig}")["posture"]
            v = c.request(f"can reach {fig} hand=right {xyz} rot=y,0deg mode=arm")
            assert c.request(f"get posture {fig}")["posture"] == before
            c.request(f"move hand {fig} right {xyz} rot=y,0deg")
            c.request("settle frames=600")
            p, r = palm(c, fig)
            dist = math.dist(p, t)
            moved = dist <= TOL_MOVED and angle_between(r, [1, 0, 0, 0, 1, 0, 0, 0, 1]) <= TOL_ORI
            agreed.append((t, v["reached"], moved, v["distance"], dist))
            checked += 1
            c.request(f"unload figure {fig}")
        assert checked >= 10
        assert any(a[1] for a in agreed) and not all(a[1] for a in agreed)
        wrong = [a for a in agreed if a[1] != a[2]]
        assert not wrong, wrong


def test_nothing_the_person_sees_changes(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        c.request("behave jack on")
        c.request("settle frames=50")
        h0 = c.request("status")["posture"]
        p0 = c.request("get posture jack")
        sh = shoulder(c, "jack")
        for mode in ("arm", "torso", "body"):
            v = c.request(f"can reach jack hand=right {sh[0]},{0.3},{sh[2] + 0.4} mode={mode}")
            assert v["mode"] == mode
            assert set(v) >= {"reached", "distance", "posture", "limiting", "margin"}
        assert c.request("status")["posture"] == h0
        assert c.request("get posture jack") == p0
        # the body bends and squats for a point low in front, the arm alone cannot
        lo = f"{sh[0]},0.3,{sh[2] + 0.4}"
        assert not c.request(f"can reach jack hand=right {lo} mode=arm")["reached"]
        assert c.request(f"can reach jack hand=right {lo} mode=body")["reached"]


def test_bad_requests_are_refused_and_change_nothing(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        h0 = c.request("status")["posture"]
        bad = ["can reach jack hand=middle 0.2,1.2,0.4",
               "can reach jack hand=right 0.2,1.2",
               "can reach jack hand=right 0.2,nan,0.4",
               "can reach jack hand=right 0.2,1.2,0.4 mode=fly",
               "can reach jack hand=right 0.2,1.2,0.4 mode=arm balance=on",
               "can reach jack hand=right 0.2,1.2,0.4 balance=maybe",
               "can reach jack 0.2,1.2,0.4",
               "can reach nobody hand=right 0.2,1.2,0.4",
               "can reach jack hand=right 0.2,1.2,0.4 0.1,0.1,0.1"]
        for req in bad:
            with pytest.raises(PostureError):
                c.request(req)
        assert c.request("status")["posture"] == h0
        assert c.request("help")  # it still serves


# ---- reach: the solved posture taken --------------------------------------------------------

def xyz(p):
    return ",".join(f"{x:.6f}" for x in p)


def test_reach_takes_the_posture_and_undo_gives_the_old_one_back(daemon):
    """A behaving figure's body reach: the palm is on the target after the reply and stays
    there through frames (the behaviours hold the new posture, not the old goals); one undo
    gives back the old posture exactly (posture hash and every joint)."""
    with daemon.client() as c:
        c.request("load human as jack")
        c.request("behave jack on")
        c.request("settle frames=50")
        h0 = c.request("status")["posture"]
        p0 = c.request("get posture jack")
        sh = shoulder(c, "jack")
        t = [sh[0], 0.3, sh[2] + 0.4]  # low in front: the arm alone does not reach it
        v = c.request(f"reach jack hand=right {xyz(t)} mode=body")
        assert v["reached"] and v["applied"]
        assert set(v) >= {"distance", "posture", "limiting", "margin", "mode"}
        assert math.dist(palm(c, "jack")[0], t) <= TOL_POS
        got = c.request("get posture jack")["posture"]
        assert set(got) == set(v["posture"])
        # the loop's frames between the reply and this request may run the behaviours,
        # which hold the taken posture but polish it by nanoradians (2.2e-9 seen)
        for j, vals in v["posture"].items():
            assert got[j] == pytest.approx(vals, abs=1e-6), j
        c.request("settle frames=300")
        assert math.dist(palm(c, "jack")[0], t) <= TOL_POS
        assert c.request("status")["posture"] != h0
        c.request("undo")
        assert c.request("status")["posture"] == h0
        assert c.request("get posture jack") == p0


def test_reach_on_a_figure_without_behaviours(daemon):
    """mode=arm on a figure without behaviours: the arm is placed, the palm on the target,
    and frames leave it there."""
    with daemon.client() as c:
        c.request("load human as jill")
        sh = shoulder(c, "jill")
        t = [sh[0], sh[1], sh[2] + 0.45]
        v = c.request(f"reach jill hand=right {xyz(t)} mode=arm")
        assert v["reached"] and v["applied"]
        assert math.dist(palm(c, "jill")[0], t) <= TOL_POS
        c.request("settle frames=50")
        assert math.dist(palm(c, "jill")[0], t) <= TOL_POS


def test_an_unreached_target_is_not_taken_unless_nearest(daemon):
    """Out of reach: the reply says so, nothing changes and it is no undo step (undo takes
    back the change before it); with nearest=yes the nearest posture is taken."""
    with daemon.client() as c:
        c.request("load human as jack")
        h0 = c.request("status")["posture"]
        c.request("set joint jack elbow_l 40deg")
        h1 = c.request("status")["posture"]
        sh = shoulder(c, "jack")
        far = [sh[0], sh[1], sh[2] + 0.9]
        v = c.request(f"reach jack hand=right {xyz(far)} mode=arm")
        assert not v["reached"] and not v["applied"]
        assert v["distance"] > 0.1
        assert c.request("status")["posture"] == h1
        c.request("undo")  # the elbow's, not the reach's
        assert c.request("status")["posture"] == h0
        v = c.request(f"reach jack hand=right {xyz(far)} mode=arm nearest=yes")
        assert not v["reached"] and v["applied"]
        assert math.dist(palm(c, "jack")[0], far) == pytest.approx(v["distance"], abs=1e-6)
        assert c.request("status")["posture"] != h0


def test_reach_is_journaled():
    """kill -9 after a reach: the restart gives back the reached posture, and the reach as
    the undo step it was (a posture the solver left is recovered too, so the undo step is
    what tells that the command itself was journaled)."""
    d = Daemon()
    try:
        d.start()
        with d.client() as c:
            c.request("load human as jack")
            h0 = c.request("status")["posture"]
            sh = shoulder(c, "jack")
            t = [sh[0] - 0.2, sh[1] - 0.2, sh[2] + 0.35]
            assert c.request(f"reach jack hand=right {xyz(t)} mode=torso")["applied"]
            h = c.request("status")["posture"]
            p = c.request("get posture jack")
        d.restart()
        with d.client() as c:
            assert c.request("get posture jack") == p
            assert c.request("status")["posture"] == h
            assert math.dist(palm(c, "jack")[0], t) <= TOL_POS
            c.request("undo")
            assert c.request("status")["posture"] == h0
    finally:
        d.kill9()
        d.cleanup()


def test_bad_reach_requests_change_nothing(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        c.request("set joint jack elbow_l 40deg")
        h0 = c.request("status")["posture"]
        bad = ["reach jack hand=middle 0.2,1.2,0.4",
               "reach jack hand=right 0.2,1.2",
               "reach jack hand=right 0.2,nan,0.4",
               "reach jack hand=right 0.2,1.2,0.4 mode=fly",
               "reach jack hand=right 0.2,1.2,0.4 mode=arm balance=on",
               "reach jack hand=right 0.2,1.2,0.4 nearest=maybe",
               "reach jack 0.2,1.2,0.4",
               "reach nobody hand=right 0.2,1.2,0.4",
               "can reach jack hand=right 0.2,1.2,0.4 nearest=yes"]
        for req in bad:
            with pytest.raises(PostureError):
                c.request(req)
        assert c.request("status")["posture"] == h0
        c.request("undo")  # the elbow's: the refusals made no undo step
        assert c.request("status")["posture"] != h0
