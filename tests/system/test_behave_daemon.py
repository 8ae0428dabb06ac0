"""Behaviours through the daemon (issue 6): the figures of Chapter 5 by commands, and
behaviour state that survives kill -9 exactly."""
from daemon import Daemon, daemon, daemon_factory  # noqa: F401 (fixtures)


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
        c.request("load human as jack")
        c.request("behave jack on")
        settled(c)
        feet = [c.request(f"get site jack toes_{s}.toe")["position"] for s in "lr"]
        c.request("move com jack 0.07 0")
        settled(c)
        after = [c.request(f"get site jack toes_{s}.toe")["position"] for s in "lr"]
        for a, b in zip(feet, after):
            assert max(abs(x - y) for x, y in zip(a, b)) < 1e-3
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
        c.request("settle frames=5")
        assert not [e for e in c.pending_events() if e["event"] in ("stability", "alert")]


def test_past_a_foot_the_support_foot_steps_out_sideways(daemon):
    """§D.3.1: with the balance point pushed out past the left foot, the left (support)
    foot steps out to the side; the right foot stays; the balance ends inside."""
    with daemon.client() as c:
        c.request("load human as jack")
        c.request("behave jack on")
        settled(c)
        feet = [c.request(f"get site jack toes_{s}.toe")["position"] for s in "lr"]
        c.request("move com jack 0.20 0")
        settled(c)
        after = [c.request(f"get site jack toes_{s}.toe")["position"] for s in "lr"]
        b = c.request("get behavior jack")
        assert b["steps"] >= 1 and not b["stepping"]
        assert after[0][0] - feet[0][0] > 0.15
        assert max(abs(x - y) for x, y in zip(after[1], feet[1])) < 2e-3
        assert b["balance"]["margin"] > 0
