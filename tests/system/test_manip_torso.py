"""bend torso as an interactive mode (Table 5.2): CONTROL and a button turn G,
which sits on the chest in the pelvis's axes; the turn is the spine's bend. The reference
is the `bend torso` command itself on an identical second figure, with totals summed here
from the spine's joint values (the spine model's totals are the sums of its joints,
§5.5.3), and the sign checked on the body: a forward bend takes the head forward."""
import math

import pytest

from daemon import daemon, daemon_factory, write_picture  # noqa: F401 (fixtures)


def spine_totals(c, fig):
    posture = c.request(f"get posture {fig}")["posture"]
    return [sum(posture[f"spine_{k}"][d] for k in range(18)) for d in range(3)]


# each wheel seen along its axis, so the 20 degree rule lets it turn
@pytest.mark.parametrize("button,direction,eye", [("left", 0, "3,1.8,0.4"), ("middle", 2, "0.3,4.5,0.4"),
                                                  ("right", 1, "0.4,1.8,3")])
def test_a_turn_of_g_bends_the_torso_as_bend_torso_does(daemon, button, direction, eye):
    with daemon.client() as c:
        for fig in ("a", "b"):
            c.request(f"load human as {fig}")
            c.request(f"behave {fig} on")
        c.request(f"add view side width=320 height=240 eye={eye} target=0,1.3,0")
        c.request("settle frames=30")
        before = spine_totals(c, "a")
        assert before == pytest.approx(spine_totals(c, "b"), abs=1e-12)
        head0 = c.request("get site a head.between_eyes")["position"]
        assert c.request("manipulate torso a view=side")["mode"] == "torso"
        g = c.request("get manip")
        assert g["mode"] == "torso"
        # CONTROL and SHIFT: about G's own axis, the pelvis's; 12 degrees typed exactly
        c.request("input key KEY_LEFTCTRL down")
        c.request("input key KEY_LEFTSHIFT down")
        c.request("input pointer side 200 100")
        c.request(f"input button {button} down")
        manip = c.request("get manip")
        assert manip["state"] == "rotate", manip
        c.request("set manip 12deg")
        write_picture(c, "side", f"manip_torso_{button}.png")
        c.request(f"input button {button} up")
        c.request("input key KEY_ESC down")
        # the same totals by command on b: flexion about x, axial about y, lateral about -z
        want = list(before)
        sign = -1 if direction == 1 else 1
        want[direction] += sign * math.radians(12)
        c.request("bend torso b " + " ".join(f"{v:.17g}" for v in want))
        c.request("settle frames=60")
        assert spine_totals(c, "a") == pytest.approx(spine_totals(c, "b"), abs=1e-6)
        pa = c.request("get posture a")["posture"]
        pb = c.request("get posture b")["posture"]
        for joint, values in pa.items():
            assert values == pytest.approx(pb[joint], abs=1e-6), joint
        if direction == 0:  # flexion: + forward, the head goes forward (+z, the way it faces)
            head = c.request("get site a head.between_eyes")["position"]
            assert head[2] - head0[2] > 0.05, (head, head0)
