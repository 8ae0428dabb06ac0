"""The URDF export as the receiving tools take it, without edits: MuJoCo, PyBullet and
urdfdom's check_urdf.

Each figure is exported with its meshes (posture-figure --out), loaded by each tool, and
100 random postures within the joint limits are set by joint name. Every site (a body in
MuJoCo) or joint (a link in PyBullet) must be where ours is to 1e-9 m, turned as ours to 1e-9;
the total mass and the centre of mass must match ours to 1e-6 (the links between the
dofs of a joint carry URDF_NEGLIGIBLE_MASS, 1e-9 kg each, as does "world"). Every segment with geometry
has a visual and a collision mesh that the tools load. The exported files are kept in
the test's output folder (build/test-output/export/), for a person to open.
"""
import os
import pathlib
import shutil
import subprocess
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from conftest import BUILD, FIGURE_ARGS, random_postures, read_dofs, read_sites, run_tool
from daemon import daemon, daemon_factory  # noqa: F401 (fixtures)

mujoco = pytest.importorskip("mujoco")
pybullet = pytest.importorskip("pybullet")

POSTURES = 100
TOL = 1e-9
MASS_TOL = 1e-6
OUTPUT = BUILD.parent / "test-output" / "export"


def export(figure, tmp_path):
    """the figure's URDF with its meshes, in tmp_path and copied to the test output"""
    (tmp_path / "out").mkdir()
    path = tmp_path / "out" / f"{figure}.urdf"
    run_tool(*FIGURE_ARGS[figure], "--out", path, "urdf")
    dest = OUTPUT / "urdf" / figure
    shutil.rmtree(dest, ignore_errors=True)
    shutil.copytree(tmp_path / "out", dest)
    return path


def ours(figure, tmp_path, seed):
    """dofs, the postures, our sites and centres of mass for each, and the total mass"""
    args = FIGURE_ARGS[figure]
    dofs = read_dofs(args)
    n = POSTURES if dofs else 1
    qs = random_postures(dofs, n, seed)
    qfile = tmp_path / f"{figure}.q"
    qfile.write_text("\n".join(" ".join(repr(float(v)) for v in q) for q in qs) + "\n")
    posture = ["--q-file", qfile] if dofs else []
    sites = read_sites(run_tool(*args, *posture, "sites"))
    com_lines = run_tool(*args, *posture, "com").splitlines()
    coms = [np.array([float(v) for v in line.split()[2:5]]) for line in com_lines]
    mass = float(com_lines[0].split()[6])
    assert len(sites) == n and len(coms) == n
    return dofs, qs, sites, coms, mass


def site_link(site):
    seg, name = site.split(".", 1)
    return f"{seg}__{name}"


@pytest.mark.parametrize("figure", sorted(FIGURE_ARGS))
def test_mujoco_loads_it_and_agrees(figure, tmp_path):
    urdf = export(figure, tmp_path)
    dofs, qs, sites, coms, mass = ours(figure, tmp_path, seed=11)
    model = mujoco.MjModel.from_xml_path(str(urdf))
    data = mujoco.MjData(model)
    assert model.nq == len(dofs)
    adr = [model.joint(name).qposadr[0] for name, _, _ in dofs]
    # our limits are MuJoCo's ranges, enforced
    for name, lo, hi in dofs:
        j = model.joint(name)
        assert j.limited[0] and np.allclose(j.range, [lo, hi], rtol=0, atol=1e-12), name
    bodies = {site: model.body(site_link(site)).id for site in sites[0]}
    # every segment's meshes came through: one visual and one collision geom each
    with_geometry = sum(1 for s in ET.parse(urdf).getroot().iter("link") if s.find("visual") is not None)
    assert model.ngeom == 2 * with_geometry and model.nmesh >= with_geometry
    assert abs(model.body_mass.sum() - mass) < MASS_TOL

    worst_p = worst_r = worst_c = 0.0
    for q, want, com in zip(qs, sites, coms):
        data.qpos[adr] = q
        mujoco.mj_kinematics(model, data)
        mujoco.mj_comPos(model, data)
        for site, (p, r) in want.items():
            b = bodies[site]
            worst_p = max(worst_p, np.abs(data.xpos[b] - p).max())
            worst_r = max(worst_r, np.abs(data.xmat[b].reshape(3, 3) - r).max())
        worst_c = max(worst_c, np.abs(data.subtree_com[0] - com).max())
    assert worst_p < TOL, f"a body is {worst_p:.3g} m from our site"
    assert worst_r < TOL, f"a body's rotation differs from our site's by {worst_r:.3g}"
    assert worst_c < MASS_TOL, f"MuJoCo's centre of mass is {worst_c:.3g} m from ours"


# PyBullet returns the states of at most this many links of a body
BULLET_MAX_LINKS = 128

ONE_JOINT = """<?xml version="1.0"?>
<robot name="one_joint">
 <link name="a"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
 <link name="b"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
 <joint name="j" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0 0.1 0"/>
  <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
 <link name="c"/>
 <joint name="f" type="fixed"><parent link="b"/><child link="c"/><origin xyz="0.5 0 0"/></joint>
</robot>
"""


def bullet_floor(tmp_path):
    """PyBullet's own error on a chain with an analytic answer: one joint turned by q,
    a point 0.5 m out. Its wheels compute in single precision: about 1e-8 m here."""
    path = tmp_path / "one_joint.urdf"
    path.write_text(ONE_JOINT)
    client = pybullet.connect(pybullet.DIRECT)
    try:
        robot = pybullet.loadURDF(str(path), useFixedBase=True, physicsClientId=client)
        worst = 0.0
        for q in np.linspace(-3, 3, 25):
            pybullet.resetJointState(robot, 0, q, physicsClientId=client)
            st = pybullet.getLinkState(robot, 1, computeForwardKinematics=True,
                                       physicsClientId=client)
            want = np.array([0.5 * np.cos(q), 0.1 + 0.5 * np.sin(q), 0])
            worst = max(worst, np.abs(np.array(st[4]) - want).max())
    finally:
        pybullet.disconnect(client)
    return worst


def read_joints(args):
    """posture-figure joints -> [(joint, parent-side site, child-side site, dofs)]"""
    return [(f[0], f[1], f[2], int(f[3])) for f in
            (line.split() for line in run_tool(*args, "joints").splitlines())
            if f and not f[0].startswith("#")]


def quat_matrix(q):
    x, y, z, w = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def bullet_load(urdf, merged):
    client = pybullet.connect(pybullet.DIRECT)
    flags = pybullet.URDF_MERGE_FIXED_LINKS if merged else 0
    robot = pybullet.loadURDF(str(urdf), physicsClientId=client, flags=flags)
    n = pybullet.getNumJoints(robot, physicsClientId=client)
    info = [pybullet.getJointInfo(robot, i, physicsClientId=client) for i in range(n)]
    masses = np.array([pybullet.getDynamicsInfo(robot, i, physicsClientId=client)[0]
                       for i in range(-1, n)])
    return client, robot, info, masses


@pytest.mark.parametrize("figure", sorted(FIGURE_ARGS))
def test_pybullet_loads_it_and_agrees(figure, tmp_path):
    """Loaded as it is (not fixed to the world: a fixed base has no mass in PyBullet;
    nothing is simulated, the joints are set and the links' frames read). PyBullet reads
    the states of at most 128 links, and the human has 230 (segments, the links between
    dofs, sites), so a figure with more is loaded again with its fixed links merged
    (URDF_MERGE_FIXED_LINKS, as PyBullet users load big robots): a link a dof is left,
    and a joint's last one carries the child segment, so its frame is the child-side
    site's. The merge loses the merged links' centres of mass (PyBullet keeps the
    parent's inertial origin), so the centre of mass is compared where no merge is
    needed. PyBullet computes in single precision: positions and rotations must agree
    within 50 times its error on a one-joint chain with an analytic answer (1e-9 when
    it has none)."""
    urdf = export(figure, tmp_path)
    dofs, qs, sites, coms, mass = ours(figure, tmp_path, seed=12)
    tol = max(TOL, 50 * bullet_floor(tmp_path))
    client, robot, info, masses = bullet_load(urdf, merged=False)
    n = len(info)
    merged = n > BULLET_MAX_LINKS
    try:
        assert abs(masses.sum() - mass) < MASS_TOL
        shapes = pybullet.getVisualShapeData(robot, physicsClientId=client)
        with_geometry = sum(1 for s in ET.parse(urdf).getroot().iter("link")
                            if s.find("visual") is not None)
        assert sum(1 for s in shapes if s[2] == pybullet.GEOM_MESH) == with_geometry
        if merged:
            pybullet.disconnect(client)
            client, robot, info, masses = bullet_load(urdf, merged=True)
            n = len(info)
    except BaseException:
        pybullet.disconnect(client)
        raise
    joint = {i[1].decode(): i[0] for i in info}
    link = {i[12].decode(): i[0] for i in info}
    # what is compared: every site (unmerged), or every joint's child side (merged)
    targets = ([(site, link[site_link(site)]) for site in sites[0]] if not merged else
               [(child, joint[f"{j}__{ndof - 1}"])
                for j, _, child, ndof in read_joints(FIGURE_ARGS[figure])])
    worst_p = worst_r = worst_c = 0.0
    try:
        assert set(name for name, _, _ in dofs) <= set(joint)
        for q, want, com in zip(qs, sites, coms):
            for (name, _, _), v in zip(dofs, q):
                pybullet.resetJointState(robot, joint[name], float(v), physicsClientId=client)
            states = pybullet.getLinkStates(robot, list(range(n)), computeForwardKinematics=True,
                                            physicsClientId=client)
            for site, i in targets:
                p, r = want[site]
                worst_p = max(worst_p, np.abs(np.array(states[i][4]) - p).max())
                worst_r = max(worst_r, np.abs(quat_matrix(states[i][5]) - r).max())
            if not merged:
                base = pybullet.getBasePositionAndOrientation(robot, physicsClientId=client)[0]
                centres = np.array([base] + [st[0] for st in states])
                c = (masses[:, None] * centres).sum(axis=0) / masses.sum()
                worst_c = max(worst_c, np.abs(c - com).max())
    finally:
        pybullet.disconnect(client)
    assert targets and worst_p < tol, f"PyBullet puts a site {worst_p:.3g} m from ours"
    assert worst_r < tol, f"PyBullet turns a site from ours by {worst_r:.3g}"
    assert worst_c < MASS_TOL, f"PyBullet's centre of mass is {worst_c:.3g} m from ours"


@pytest.mark.skipif(not shutil.which("check_urdf"),
                    reason="check_urdf missing (make deps installs liburdfdom-tools)")
@pytest.mark.parametrize("figure", sorted(FIGURE_ARGS))
def test_check_urdf_parses_it(figure, tmp_path):
    urdf = export(figure, tmp_path)
    proc = subprocess.run(["check_urdf", str(urdf)], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "Successfully Parsed XML" in proc.stdout
    # the tree it read: our root under world, every joint's dofs as joints
    assert "root Link: world has 1 child(ren)" in proc.stdout


@pytest.mark.parametrize("root", [None, "hand_r.palm"])
def test_daemon_export_is_the_posture_mujoco_shows(daemon, root):
    """`export urdf` over the socket, of a figure posed and moved in a session (and
    re-rooted): MuJoCo, given the joint values the daemon reports, puts every site where
    the daemon has it, to 1e-9 m: the root's placement now is in the file."""
    c = daemon.client()
    c.request("load human as jack")
    if root:
        c.request(f"set root jack {root}")
    c.request("set joint jack shoulder_r 20deg 40deg -30deg")
    c.request("set joint jack knee_l 50deg")
    c.request("set joint jack spine_4 2deg 1deg 1deg")
    (daemon.state_dir / "out").mkdir()
    got = c.request("export urdf jack out/jack.urdf")
    assert got["files"] == 1 + sum(1 for _ in (daemon.state_dir / "out").glob("jack_*.stl"))
    model = mujoco.MjModel.from_xml_path(str(daemon.state_dir / "out" / "jack.urdf"))
    data = mujoco.MjData(model)
    for joint, values in c.request("get posture jack")["posture"].items():
        for k, v in enumerate(values):
            data.qpos[model.joint(f"{joint}__{k}").qposadr[0]] = v
    mujoco.mj_kinematics(model, data)
    sites = list(read_sites(run_tool("--human", "sites"))[0])
    worst = 0.0
    for site in sites:
        want = np.array(c.request(f"get site jack {site}")["position"])
        worst = max(worst, np.abs(data.xpos[model.body(site_link(site)).id] - want).max())
    assert worst < TOL, f"a site is {worst:.3g} m from where the daemon has it"


def test_a_failed_export_leaves_no_mesh_behind(tmp_path):
    """the URDF cannot be written (its temporary name is taken by a directory): the meshes
    written before it are removed, and nothing is left"""
    out = tmp_path / "out"
    out.mkdir()
    (out / "human.urdf.part").mkdir()
    proc = subprocess.run([str(BUILD / "bin" / "posture-figure"), "--human", "--out",
                           str(out / "human.urdf"), "urdf"], capture_output=True, text=True,
                          timeout=60)
    assert proc.returncode == 1 and "human.urdf.part" in proc.stderr, proc.stderr
    assert [p.name for p in out.iterdir()] == ["human.urdf.part"]
