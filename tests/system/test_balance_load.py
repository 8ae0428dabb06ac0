"""Balance feels the load, through the daemon: the centre of mass get balance answers and
the behaviours hold over the support is the body's with the weights it carries, against
the combined centre of mass worked out here from show figure (the body's own centre of
mass and mass) and the weight's site; a pure force moves none; a weight held out in front
moves the hips back by the lever rule; the state survives kill -9 exactly."""
from daemon import Daemon, daemon, daemon_factory  # noqa: F401 (fixtures)

BOX = 15.0


def settled(c, frames=400):
    r = c.request(f"settle frames={frames}")
    assert r["settled"], r
    return r


def combined(c, fig, site, kg):
    """sum m c / sum m of the body (its centre of mass and mass) and a weight at a site"""
    f = c.request(f"show figure {fig}")
    p = c.request(f"get site {fig} {site}")["position"]
    m = f["mass"]
    return [(m * f["com"][i] + kg * p[i]) / (m + kg) for i in range(3)], f


def test_get_balance_answers_the_combined_centre_of_mass(daemon):
    with daemon.client() as c:
        c.request("load human as jack")  # no behaviour: nothing solves, the posture stays
        bare = c.request("get balance jack")
        assert bare["carried"] == 0
        body = c.request("show figure jack")["com"]
        assert max(abs(a - b) for a, b in zip(bare["com"], body)) < 1e-12
        c.request(f"add load jack hand_r.palm mass={BOX} as box")
        bal = c.request("get balance jack")
        want, _ = combined(c, "jack", "hand_r.palm", BOX)
        assert bal["carried"] == BOX
        assert max(abs(a - b) for a, b in zip(bal["com"], want)) < 1e-9
        assert abs(bal["point"][0] - want[0]) < 1e-9 and abs(bal["point"][1] - want[2]) < 1e-9
        assert abs(bal["point"][0] - bare["point"][0]) > 0.01  # the hand hangs at the side
        # a pure force has no mass: it moves no centre of mass (a second weight does)
        c.request("add load jack hand_l.palm force=50,0,0 as push")
        assert c.request("get balance jack")["com"] == bal["com"]
        c.request("delete load box")
        assert c.request("get balance jack")["com"] == bare["com"]


def hold_out(c):
    """the right hand out in front of the chest, settled"""
    c.request("load human as jack")
    c.request("behave jack on")
    settled(c)
    p = c.request("get site jack hand_r.palm")["position"]
    c.request(f"move hand jack right {p[0]},{p[1] + 0.4},{p[2] + 0.4}")
    settled(c)


def test_a_box_held_out_in_front_moves_the_hips_back(daemon):
    with daemon.client() as c:
        hold_out(c)
        pelvis0 = c.request("get site jack pelvis.hip_r")["position"]
        body0 = c.request("show figure jack")["com"]
        c.request(f"add load jack hand_r.palm mass={BOX} as box")
        settled(c)
        beh = c.request("get behavior jack")["balance"]
        bp = beh["held"]
        want, f = combined(c, "jack", "hand_r.palm", BOX)
        # the combined centre of mass is over the balance point the behaviours hold
        assert abs(want[0] - bp[0]) < 5e-4 and abs(want[2] - bp[1]) < 5e-4, (want, bp)
        assert beh["margin"] > 0
        # the lever rule along the feet's forward (+z here): the body's own centre of
        # mass goes (m / M)(p - bp) back from the balance point
        palm = c.request("get site jack hand_r.palm")["position"]
        assert palm[2] - bp[1] > 0.2
        lever = -(BOX / f["mass"]) * (palm[2] - bp[1])
        shift = f["com"][2] - body0[2]
        assert abs(shift - lever) < 2e-3, (shift, lever)
        pelvis = c.request("get site jack pelvis.hip_r")["position"]
        assert 2 * lever < pelvis[2] - pelvis0[2] < 0.5 * lever
        # off again: the body's own centre of mass is balanced again (the posture
        # that does it need not be the first one: the body has more joints than goals)
        c.request("delete load box")
        settled(c)
        body1 = c.request("show figure jack")["com"]
        assert abs(body1[0] - bp[0]) < 5e-4 and abs(body1[2] - bp[1]) < 5e-4
        assert c.request("get site jack pelvis.hip_r")["position"][2] > pelvis[2] + 0.5 * abs(lever)


def test_a_loaded_behaving_figure_survives_kill_9_exactly():
    d = Daemon()
    d.start()
    try:
        with d.client() as c:
            hold_out(c)
            c.request(f"add load jack hand_r.palm mass={BOX} as box")
            c.request("move com jack 0 0 -0.05")  # a held elevation: the weight's jump held
            settled(c)
            before = (c.request("get posture jack"), c.request("get behavior jack"),
                      c.request("get balance jack"))
        d.kill9()
        d.start()
        with d.client() as c:
            after = (c.request("get posture jack"), c.request("get behavior jack"),
                     c.request("get balance jack"))
            assert after == before
            c.request("settle frames=20")
            assert c.request("get posture jack") == before[0]
    finally:
        d.stop()
        d.cleanup()
