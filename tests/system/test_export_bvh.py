"""The BVH export (`export bvh FIG PATH`) as a reader we did not write takes it: bvhio.

A session poses the human step by step over the socket; each step is an undo checkpoint.
The export's frames are the session's history (the checkpoints, oldest first, then now);
bvhio reads the file back, and at every frame each BVH joint's world position must be
where the daemon said that joint's child-side site was at that step (`get site`), to
1e-6 m. The skeleton's joints are ours by name, and each joint's rotation channels come
in its dofs' order. The exported file is kept in the test output for a person to open.
"""
import random
import shutil

import numpy as np
import pytest

from conftest import BUILD, FIGURE_ARGS, random_postures, read_dofs, read_sites, run_tool
from daemon import PostureError, daemon, daemon_factory  # noqa: F401 (fixtures)

bvhio = pytest.importorskip("bvhio")

TOL = 1e-6
STEPS = 24
OUTPUT = BUILD.parent / "test-output" / "export" / "bvh"


def human_joints():
    """[(joint, child-side site, dofs)] of the human as posture-figure has it"""
    return [(f[0], f[2], int(f[3])) for f in
            (line.split() for line in run_tool("--human", "joints").splitlines())
            if f and not f[0].startswith("#")]


def dof_axes():
    """joint -> its rotation dofs' axes in order ("x", "y", "z")"""
    axes = {}
    for line in run_tool("--human", "dofs").splitlines():
        if line.startswith("#") or not line.strip():
            continue
        _, joint, _, kind, *_ = line.split()
        if kind.startswith("R"):
            axes.setdefault(joint, []).append(kind[-2].lower())
    return axes


def where(client, joints):
    """every joint's child-side site, where the daemon has it now"""
    return {j: np.array(client.request(f"get site human {site}")["position"])
            for j, site, _ in joints}


def pose_randomly(client, rng, joints):
    """one step (one undo checkpoint): a joint set to random values within its limits"""
    joint = rng.choice(joints)[0]
    got = client.request(f"get joint human {joint}")
    values = [rng.uniform(lo, hi) for lo, hi in zip(got["lower"], got["upper"])]
    client.request(f"set joint human {joint} " + " ".join(repr(v) for v in values))


@pytest.mark.parametrize("root", [None, "foot_l.balance"])
def test_bvhio_reads_the_history_back(daemon, root):
    """Re-rooted, the skeleton hangs from the root's segment and runs through joints
    against their direction; a joint's two sites coincide, so where it is is the same."""
    joints = human_joints()
    rng = random.Random(5)
    c = daemon.client()
    c.request("load human as human")
    if root:
        c.request(f"set root human {root}")
    seen = []
    for _ in range(STEPS):
        seen.append(where(c, joints))
        pose_randomly(c, rng, joints)
    seen.append(where(c, joints))
    got = c.request("export bvh human motion.bvh")
    # the load's checkpoint has no human yet: its frame holds the first posture
    assert got["frames"] == STEPS + 2 + (root is not None)
    frames = [seen[0]] * (2 + (root is not None)) + seen[1:]
    path = daemon.state_dir / "motion.bvh"
    OUTPUT.mkdir(parents=True, exist_ok=True)
    shutil.copy(path, OUTPUT / f"human{'-' + root.replace('.', '-') if root else ''}.bvh")

    skeleton = bvhio.readAsHierarchy(str(path))
    by_name = {joint.Name: joint for joint, _, _ in skeleton.layout()}
    assert skeleton.Name == (root or "pelvis.root").split(".")[0]
    assert {j for j, _, _ in joints} <= set(by_name)
    worst = 0.0
    for k, want in enumerate(frames):
        skeleton.loadPose(k)
        for joint, pos in want.items():
            p = by_name[joint].PositionWorld
            worst = max(worst, np.abs(np.array([p.x, p.y, p.z]) - pos).max())
    assert worst < TOL, f"a BVH joint is {worst:.3g} m from ours"


def read_joint_sites(args):
    """posture-figure joints -> {joint: its child-side site}"""
    return {f[0]: f[2] for f in (line.split() for line in run_tool(*args, "joints").splitlines())
            if f and not f[0].startswith("#")}


# the shared figures, and the human hung from a heel (its joints then run inverted)
BVH_FIGURES = dict(FIGURE_ARGS, **{"human-heel": ["--human", "--root", "foot_r.heel"]})


@pytest.mark.parametrize("figure", sorted(BVH_FIGURES))
def test_bvhio_reads_postures_back(figure, tmp_path):
    """posture-figure bvh: 20 random postures as frames (the vehicle seat's track slides:
    position channels); bvhio puts every joint where the figure has it, to 1e-6 m."""
    args = BVH_FIGURES[figure]
    dofs = read_dofs(args)
    qs = random_postures(dofs, 20 if dofs else 1, seed=3)
    qfile = tmp_path / "q.txt"
    qfile.write_text("\n".join(" ".join(repr(float(v)) for v in q) for q in qs) + "\n")
    posture = ["--q-file", qfile] if dofs else []
    out = tmp_path / f"{figure}.bvh"
    run_tool(*args, *posture, "--out", out, "bvh")
    OUTPUT.mkdir(parents=True, exist_ok=True)
    shutil.copy(out, OUTPUT / out.name)
    sites = read_sites(run_tool(*args, *posture, "sites"))
    joint_site = read_joint_sites(args)
    skeleton = bvhio.readAsHierarchy(str(out))
    by_name = {joint.Name: joint for joint, _, _ in skeleton.layout()}
    assert set(joint_site) <= set(by_name)
    worst = 0.0
    for k, want in enumerate(sites):
        skeleton.loadPose(k)
        for joint, site in joint_site.items():
            p = by_name[joint].PositionWorld
            worst = max(worst, np.abs(np.array([p.x, p.y, p.z]) - want[site][0]).max())
    assert worst < TOL, f"a BVH joint is {worst:.3g} m from ours"


def test_channels_follow_each_joints_dofs(daemon):
    c = daemon.client()
    c.request("load human as human")
    c.request("set joint human knee_l 30deg")
    c.request("export bvh human m.bvh")
    text = (daemon.state_dir / "m.bvh").read_text()
    channels, name = {}, None
    for line in text.splitlines():
        f = line.split()
        if f and f[0] in ("ROOT", "JOINT"):
            name = f[1]
        elif f and f[0] == "CHANNELS":
            channels[name] = [w[0].lower() for w in f[2:] if w.endswith("rotation")]
    for joint, axes in dof_axes().items():
        assert channels[joint][:len(axes)] == axes, joint


def test_bad_requests_write_nothing(daemon):
    c = daemon.client()
    c.request("load human as human")
    before = sorted(p.name for p in daemon.state_dir.iterdir())
    for line, code in [("export bvh human motion.bvh", "nothing"),  # no undo step holds it
                       ("set joint human knee_l 20deg", None),
                       ("export bvh human ../out.bvh", "denied"),
                       ("export bvh nobody out.bvh", "not-found"),
                       ("export bvh human out.txt", "bad-argument"),
                       ("export bvh human .bvh", "bad-argument"),
                       ("export bvh human nodir/out.bvh", "not-found")]:
        if code is None:
            c.request(line)
            continue
        with pytest.raises(PostureError) as e:
            c.request(line)
        assert e.value.code == code, (line, e.value)
    assert sorted(p.name for p in daemon.state_dir.iterdir()) == before
