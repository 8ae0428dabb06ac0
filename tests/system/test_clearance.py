"""analyze clearance against python-fcl on the exported meshes.

The human and the vehicle seat are loaded in the daemon, the human in random
postures (60 in make test; POSTURE_CLEARANCE_POSES=500 for the full run) (every dof uniform within its limits: hands and feet through the seat, limbs
through the body); each posture's `analyze clearance` (with the seat, and with itself) is
checked against python-fcl, FCL as Python users call it, on the segments' meshes the
URDF export writes (posture-figure urdf: each segment's mesh in its frame) placed by the
segment frames posture-figure computes for the joint values the daemon reports:

- each pair listed has python-fcl's distance to 1e-6 m (apart: the minimum distance with
  its closest points; interpenetrating: minus the deepest contact's depth);
- the pairs listed are every pair python-fcl finds nearer than the threshold, among the
  pairs the fit analysis checks (self: not jointed, not in the table of pairs touching at
  rest, as docs/fit.md states it), and the minimum is python-fcl's over all of them.

Also: boxes at a known gap give the gap; bad requests are refused with nothing changed.
"""
import os

import numpy as np
import pytest

from conftest import FIGURE_ARGS, ROOT, read_dofs, read_segments, run_tool
from daemon import PostureError, daemon, daemon_factory  # noqa: F401 (fixtures)

fcl = pytest.importorskip("fcl")
trimesh = pytest.importorskip("trimesh")

POSES = int(os.environ.get("POSTURE_CLEARANCE_POSES", "60"))
THRESHOLD = 0.05
TOL = 1e-6
LIBRARY = ROOT / "src" / "figure" / "library"


def meshes(args, tmp_path, stem):
    """segment -> (vertices, faces) from the URDF export's STL files (segment frames)"""
    out = tmp_path / stem
    out.mkdir()
    run_tool(*args, "--out", out / f"{stem}.urdf", "urdf")
    got = {}
    for path in out.glob(f"{stem}_*.stl"):
        m = trimesh.load(str(path), process=False)
        if len(m.faces):
            got[path.stem[len(stem) + 1:]] = (np.asarray(m.vertices, float), np.asarray(m.faces))
    return got


def bvh(vertices, faces):
    m = fcl.BVHModel()
    m.beginModel(len(vertices), len(faces))
    m.addSubModel(vertices, faces)
    m.endModel()
    return m


def place(model, frame):
    return fcl.CollisionObject(model, fcl.Transform(frame[:3, :3], frame[:3, 3]))


def separation(a, b):
    """FCL's answer the fit analysis gives: distance, or minus the deepest contact"""
    req = fcl.DistanceRequest(enable_nearest_points=True)
    res = fcl.DistanceResult()
    d = fcl.distance(a, b, req, res)
    if d > 0:
        return d, res.nearest_points
    creq = fcl.CollisionRequest(num_max_contacts=100000, enable_contact=True)
    cres = fcl.CollisionResult()
    fcl.collide(a, b, creq, cres)
    if not cres.contacts:
        return 0.0, res.nearest_points
    deep = max(cres.contacts, key=lambda c: c.penetration_depth)
    return -deep.penetration_depth, (deep.pos, deep.pos)


TRUNK = {"pelvis", "head"} | {f"L{k}" for k in range(1, 6)} | {f"T{k}" for k in range(1, 13)}


def touching_at_rest(a, b):
    """the table of docs/fit.md: pairs of the human left out of self-clearance"""
    pair = {a, b}
    clav = {"clavicle_l", "clavicle_r"}
    thighs = {"thigh_l", "thigh_r"}
    if pair <= TRUNK:
        return True
    if len(pair & clav) >= 1 and pair <= TRUNK | clav:
        return True
    if len(pair & thighs) == 1 and len(pair & {"L3", "L4", "L5"}) == 1:
        return True
    return pair == thighs


def jointed_pairs():
    pairs = set()
    for line in run_tool("--human", "joints").splitlines():
        if line.startswith("#"):
            continue
        _, above, below, _ = line.split()
        pairs.add(frozenset((above.split(".")[0], below.split(".")[0])))
    return pairs


def posture_of(c, dofs):
    got = c.request("get posture jack")["posture"]
    return [got[name.rsplit("__", 1)[0]][int(name.rsplit("__", 1)[1])] for name, _, _ in dofs]


def test_clearance_agrees_with_python_fcl(daemon_factory, tmp_path):
    daemon = daemon_factory(extra=["--library", str(LIBRARY)])
    c = daemon.client()
    c.request("load human as jack")
    c.request("load figure lib:vehicle_seat.fig as seat")
    human = {k: bvh(*v) for k, v in meshes(["--human"], tmp_path, "jack").items()}
    seat_args = FIGURE_ARGS["vehicle-seat"]
    seat = {k: bvh(*v) for k, v in meshes(seat_args, tmp_path, "seat").items()}
    seat_frames = read_segments(run_tool(*seat_args, "segments"))[0]
    dofs = read_dofs(["--human"])
    joints = {}
    for i, (name, lo, hi) in enumerate(dofs):
        joints.setdefault(name.rsplit("__", 1)[0], []).append(i)
    jointed = jointed_pairs()
    rng = np.random.default_rng(28)
    replies, postures = [], []
    for k in range(POSES):
        for joint, idx in joints.items():
            values = [rng.uniform(dofs[i][1], dofs[i][2]) for i in idx]
            c.request(f"set joint jack {joint} " + " ".join(repr(float(v)) for v in values))
        postures.append(posture_of(c, dofs))
        replies.append(c.request(f"analyze clearance jack with=seat threshold={THRESHOLD}"))
    qfile = tmp_path / "poses.q"
    qfile.write_text("\n".join(" ".join(repr(v) for v in q) for q in postures) + "\n")
    frames = read_segments(run_tool("--human", "--q-file", qfile, "segments"))
    worst, listed, penetrating = 0.0, 0, 0
    for reply, frame in zip(replies, frames):
        placed = {f"jack.{s}": place(m, frame[s]) for s, m in human.items()}
        placed.update({f"seat.{s}": place(m, seat_frames[s]) for s, m in seat.items()})
        # every pair the analysis checks, by python-fcl
        want = {}
        for a in human:
            for b in seat:
                want[(f"jack.{a}", f"seat.{b}")] = separation(placed[f"jack.{a}"],
                                                              placed[f"seat.{b}"])
            for b in human:
                if a < b and frozenset((a, b)) not in jointed and not touching_at_rest(a, b):
                    want[(f"jack.{a}", f"jack.{b}")] = separation(placed[f"jack.{a}"],
                                                                  placed[f"jack.{b}"])
        got = {}
        for p in reply["pairs"]:
            key = (p["a"], p["b"]) if (p["a"], p["b"]) in want else (p["b"], p["a"])
            assert key in want, f"{p['a']} - {p['b']} is no pair the analysis checks"
            got[key] = p
            d, points = want[key]
            worst = max(worst, abs(p["distance"] - d))
            if key == (p["a"], p["b"]) and d > 0:
                worst = max(worst, np.abs(np.array(p["points"]) - np.array(points)).max())
            penetrating += p["distance"] < 0
        near = {k for k, (d, _) in want.items() if d < THRESHOLD}
        assert set(got) == near, (sorted(set(got) - near), sorted(near - set(got)))
        assert abs(reply["minimum"] - min(d for d, _ in want.values())) < TOL
        listed += len(got)
    print(f"clearance: {POSES} postures, {listed} pairs listed ({penetrating} "
          f"interpenetrating), worst difference {worst:.3g} m")
    assert worst < TOL
    assert listed > POSES and penetrating > 0


def test_boxes_at_a_known_gap(daemon_factory):
    """two boxes of the library 0.3 m apart face to face: 0.3 m, points on the faces"""
    daemon = daemon_factory(extra=["--library", str(LIBRARY)])
    c = daemon.client()
    c.request("load figure lib:box.fig as a")
    c.request("load figure lib:box.fig as b")
    box = run_tool("--figure", LIBRARY / "box.fig", "bounds").split()
    lo, hi = np.array(box[2:5], float), np.array(box[5:8], float)
    width = hi[0] - lo[0]
    c.request(f"set location b {width + 0.3} 0 0")
    got = c.request("analyze clearance a with=b threshold=1")
    assert abs(got["minimum"] - 0.3) < 1e-9, got["minimum"]
    p = got["pairs"][0]
    assert abs(p["points"][0][0] - hi[0]) < 1e-9 and abs(p["points"][1][0] - (hi[0] + 0.3)) < 1e-9


@pytest.mark.parametrize("request_, says", [
    ("analyze clearance nobody", "nobody"),
    ("analyze clearance jack threshold=-1cm", "threshold"),
    ("analyze clearance jack threshold=abc", "threshold"),
    ("analyze clearance jack with=nobody", "nobody"),
    ("analyze clearance jack with=jack", "itself"),
    ("analyze clearance jack self=maybe", "self"),
    ("analyze clearance jack colour=red", "unexpected"),
    ("analyze clearance family=nobody", "no family"),
])
def test_bad_requests_change_nothing(daemon, request_, says):
    with daemon.client() as c:
        c.request("load human as jack")
        before = c.request("status")["posture"]
        with pytest.raises(PostureError) as e:
            c.request(request_)
        assert says in str(e.value)
        assert c.request("status")["posture"] == before
