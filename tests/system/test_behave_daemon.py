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
