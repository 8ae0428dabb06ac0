"""`set view VIEW tint=strength`: each human's segment just below a strength joint drawn in
the band of that joint's percent capable under the posture and its loads (green >= 99 %,
yellow 75-99 %, orange 25-75 %, red < 25 %), grey where no published curve covers the
joint, the pelvis, clavicles and head in their own colours.

The expected colour of each segment is worked out here from `analyze loads` (the
joint's least percent over its axes, null where there is none) and the bands as the
research notes give them; which pixel shows which segment is asked of `pick`. The key
shows the four bands and grey in order. The tint is kept in sessions.
"""
import numpy as np

from daemon import daemon, daemon_factory  # noqa: F401 (fixtures)
from test_assess_tint import FRONT, hue_class, picture, segment_colours

BELOW = {"wrist": ["hand"], "elbow": ["forearm"], "shoulder": ["upperarm"], "hip": ["thigh"],
         "knee": ["shank"], "ankle": ["foot", "toes"]}
TRUNK = ["L5", "L4", "L3", "L2", "L1"] + [f"T{k}" for k in range(12, 0, -1)]


def band_class(percent):
    if percent is None:
        return "grey"
    return "green" if percent >= 99 else "yellow" if percent >= 75 else \
        "orange" if percent >= 25 else "red"


def expected(analysis):
    """{segment: colour class} from the analysis' percent capable per joint"""
    out = {}
    for joint, axes in analysis["strength"]["joints"].items():
        got = [a["percent"] for a in axes.values() if a["percent"] is not None]
        cls = band_class(min(got) if got else None)
        if joint == "spine_0":
            segs = TRUNK
        else:
            limb, side = joint.rsplit("_", 1)
            segs = [f"{s}_{side}" for s in BELOW[limb]]
        for s in segs:
            out[s] = cls
    return out


def test_strength_tint_colours_each_joint_by_its_percent_capable(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        c.request(FRONT)
        c.request("set joint jack shoulder_r 90deg 0 0")
        c.request("add load jack hand_r.palm mass=15 as box")
        own = segment_colours(c, picture(c), step=8)
        assert c.request("set view front tint=strength")["tint"] == "strength"
        want = expected(c.request("analyze loads jack"))
        assert len(want) == len(TRUNK) + 2 * 7  # every strength joint answers
        colours = segment_colours(c, picture(c), step=8)
    seen = 0
    for seg, cls in want.items():
        if seg in colours:
            seen += 1
            assert hue_class(colours[seg]) == cls, (seg, colours[seg], cls)
    assert seen >= 10, colours.keys()
    for seg in ("pelvis", "head"):  # held up by no strength joint: as untinted
        assert np.abs(colours[seg] - own[seg]).max() <= 3, (seg, colours[seg], own[seg])


def test_the_key_shows_the_bands_and_grey_in_order(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        c.request(FRONT.replace("width=360", "width=480"))  # room for the whole key
        c.request("set view front tint=strength")
        img = picture(c)
    row = img[14, :, :3].astype(int)  # the key's middle row
    want = {"green": (41, 168, 61), "yellow": (237, 204, 26), "orange": (242, 120, 18),
            "red": (214, 28, 26), "grey": (158, 158, 158)}
    first = {}
    for name, rgb in want.items():
        xs = [x for x in range(row.shape[0]) if np.abs(row[x] - rgb).max() <= 2]
        assert len(xs) >= 8, (name, rgb)  # a swatch 12 px wide
        first[name] = xs[0]
    assert first["green"] < first["yellow"] < first["orange"] < first["red"] < first["grey"]


def test_a_session_keeps_the_strength_tint(daemon):
    with daemon.client() as c:
        c.request(FRONT)
        c.request("set view front tint=strength loads=off")
        c.request("save session s.ses")
        line = [ln for ln in (daemon.state_dir / "s.ses").read_text().splitlines()
                if ln.startswith("view ")][0]
        assert line.endswith(" tint=strength loads=off"), line
    daemon.restart()
    with daemon.client() as c:
        v = c.request("list views")["views"][0]
        assert (v["tint"], v["loads"]) == ("strength", "off")
