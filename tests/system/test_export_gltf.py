"""The glTF export as the receiving tools take it: the Khronos glTF validator and trimesh.

Each figure is exported as a binary glTF (posture-figure --out FILE.glb gltf), once posed
(--random) and once with postures of a q-file as its animation. The validator must report
no error and no warning on either. trimesh must load the posed one with every segment's
mesh where ours is: each mesh node's world transform equal to our segment's frame to 1e-6,
and the bounding box of all the posed vertices equal to ours (posture-figure bounds) to
1 mm. The animation, evaluated here from the parsed file (trimesh does not play
animations) at each keyframe, must put every segment node where our segment is in that
posture, to 1e-6 m and 1e-6 in the rotation (its keyframes are float32; the human's
come within 1e-7). A bad request gives an error and leaves no file. The exported files
are kept in build/test-output/export/gltf/, for a person to open.
"""
import json
import os
import shutil
import struct
import subprocess

import numpy as np
import pytest

from conftest import (BUILD, FIGURE_ARGS, ROOT, quat_matrix, random_postures, read_dofs,
                      read_segments, run_tool)

from daemon import PostureError, daemon, daemon_factory  # noqa: F401 (fixtures)

trimesh = pytest.importorskip("trimesh")

TOL = 1e-6
BOX_TOL = 1e-3
FRAME_SECONDS = 0.5
KEYFRAMES = 5
OUTPUT = BUILD.parent / "test-output" / "export" / "gltf"
NODE_MODULES = BUILD.parent / "npm" / "node_modules"
VALIDATE_JS = ROOT / "tests" / "system" / "gltf_validate.js"

# the shared figures, and what they lack: a child-side site placed off its segment's
# origin and turned, a root site off its origin, inverted joints (re-rooted), a joint that
# both slides and turns, a translucent segment
FIGURES = {
    **FIGURE_ARGS,
    "meshfig": ["--figure", ROOT / "tests" / "figures" / "meshfig.fig"],
    "meshfig-rooted-at-tip": ["--figure", ROOT / "tests" / "figures" / "meshfig.fig",
                              "--root", "carriage.tip"],
    "human-rooted-at-heel": ["--human", "--root", "foot_l.heel"],
}


def export(figure, tmp_path, *extra, kind):
    """the figure's .glb in tmp_path, copied to the test output as FIGURE-KIND.glb"""
    path = tmp_path / f"{figure}-{kind}.glb"
    run_tool(*FIGURES[figure], *extra, "--out", path, "gltf")
    OUTPUT.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(path, OUTPUT / path.name)
    return path


def write_qfile(figure, tmp_path, seed):
    """KEYFRAMES random postures within the limits; None for a figure without dofs (a
    q-file has no line for its posture: it has one posture only)"""
    dofs = read_dofs(FIGURES[figure])
    if not dofs:
        return None
    qs = random_postures(dofs, KEYFRAMES, seed)
    path = tmp_path / f"{figure}.q"
    path.write_text("\n".join(" ".join(repr(float(v)) for v in q) for q in qs) + "\n")
    return path


def read_glb(path):
    """the JSON document and the BIN chunk of a .glb"""
    data = path.read_bytes()
    magic, version, length = struct.unpack_from("<III", data, 0)
    assert (magic, version, length) == (0x46546C67, 2, len(data))
    jlen, jtype = struct.unpack_from("<II", data, 12)
    assert jtype == 0x4E4F534A and jlen % 4 == 0
    doc = json.loads(data[20:20 + jlen])
    rest = data[20 + jlen:]
    if not rest:
        return doc, b""
    blen, btype = struct.unpack_from("<II", rest, 0)
    assert btype == 0x004E4942 and blen % 4 == 0
    return doc, rest[8:8 + blen]


def accessor(doc, binary, index):
    """an accessor's floats as an array (count x components)"""
    acc = doc["accessors"][index]
    view = doc["bufferViews"][acc["bufferView"]]
    assert acc["componentType"] == 5126
    n = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}[acc["type"]]
    start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    return np.frombuffer(binary, dtype="<f4", count=acc["count"] * n, offset=start).reshape(-1, n)


def trs_matrix(t, r):
    m = np.eye(4)
    m[:3, :3] = quat_matrix(np.asarray(r, dtype=float))
    m[:3, 3] = t
    return m


def world_frames(doc, local):
    """node index -> world 4x4, from each node's local 4x4 and the scene's hierarchy"""
    world = {}

    def walk(i, parent):
        world[i] = parent @ local[i]
        for c in doc["nodes"][i].get("children", []):
            walk(c, world[i])

    for i in doc["scenes"][doc.get("scene", 0)]["nodes"]:
        walk(i, np.eye(4))
    return world


def sample(times, values, t, rotation):
    """a LINEAR sampler at time t: lerp, or for rotations slerp (the spec's rule)"""
    k = int(np.clip(np.searchsorted(times, t, side="right") - 1, 0, len(times) - 2))
    u = float(np.clip((t - times[k]) / (times[k + 1] - times[k]), 0, 1))
    a, b = values[k].astype(float), values[k + 1].astype(float)
    if not rotation:
        return (1 - u) * a + u * b
    d = float(np.clip(np.dot(a, b), -1, 1))
    if d < 0:  # the spec takes the short way round
        b, d = -b, -d
    th = np.arccos(d)
    if th < 1e-9:
        return (1 - u) * a + u * b
    return (np.sin((1 - u) * th) * a + np.sin(u * th) * b) / np.sin(th)


def pose_at(doc, binary, t):
    """every node's local 4x4 with the animation evaluated at time t"""
    trs = [[np.array(n.get("translation", [0, 0, 0]), dtype=float),
            np.array(n.get("rotation", [0, 0, 0, 1]), dtype=float)] for n in doc["nodes"]]
    anim = doc["animations"][0]
    for ch in anim["channels"]:
        s = anim["samplers"][ch["sampler"]]
        assert s.get("interpolation", "LINEAR") == "LINEAR"
        times = accessor(doc, binary, s["input"])[:, 0]
        values = accessor(doc, binary, s["output"])
        path = ch["target"]["path"]
        trs[ch["target"]["node"]][path == "rotation"] = sample(times, values, t, path == "rotation")
    return [trs_matrix(t_, r) for t_, r in trs]


def read_segment_names(doc):
    return [m["name"] for m in doc.get("meshes", [])]


def our_segment_nodes(doc, segments):
    """segment name -> node index, found by the hierarchy: the top node's child is the root
    segment; under a segment are its joints, under a joint its child segment"""
    found = {}

    def walk(i, is_segment):
        if is_segment:
            name = doc["nodes"][i]["name"]
            assert name in segments and name not in found, name
            found[name] = i
        for c in doc["nodes"][i].get("children", []):
            walk(c, not is_segment)

    for top in doc["scenes"][0]["nodes"]:
        for c in doc["nodes"][top]["children"]:
            walk(c, True)
    return found


# ---- the Khronos validator ----------------------------------------------------

def validate(path):
    if not shutil.which("node"):
        pytest.skip("node missing (make deps installs Debian's nodejs and npm)")
    if not (NODE_MODULES / "gltf-validator").is_dir():
        pytest.skip("npm gltf-validator missing (make deps installs it under build/npm)")
    proc = subprocess.run(["node", str(VALIDATE_JS), str(path)], capture_output=True, text=True,
                          timeout=120, env={**os.environ, "NODE_PATH": str(NODE_MODULES)})
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


@pytest.mark.parametrize("figure", sorted(FIGURES))
def test_validator_reports_nothing(figure, tmp_path):
    qfile = write_qfile(figure, tmp_path, seed=21)
    posed = export(figure, tmp_path, "--random", "21", kind="posed")
    exports = [(posed, 0)]
    if qfile:
        exports.append((export(figure, tmp_path, "--q-file", qfile, kind="animated"), 1))
    nsegments = len(read_segments(run_tool(*FIGURES[figure], "segments"))[0])
    for path, animations in exports:
        report = validate(path)
        issues = report["issues"]
        assert issues["numErrors"] == 0 and issues["numWarnings"] == 0, \
            json.dumps(issues["messages"][:20], indent=1)
        info = report["info"]
        assert info["animationCount"] == animations
        doc, _ = read_glb(path)
        assert 0 < info["drawCallCount"] == len(doc["meshes"]) <= nsegments


# ---- trimesh --------------------------------------------------------------

@pytest.mark.parametrize("figure", sorted(FIGURES))
def test_trimesh_loads_it_posed(figure, tmp_path):
    """the posture now (--random) in the nodes: trimesh's world transforms and bounds"""
    args = FIGURES[figure]
    path = export(figure, tmp_path, "--random", "22", kind="posed")
    ours = read_segments(run_tool(*args, "--random", "22", "segments"))[0]
    box = np.array([float(v) for v in run_tool(*args, "--random", "22", "bounds").split()[2:]])
    scene = trimesh.load(str(path), force="scene")
    # each mesh node (named after its segment, as its mesh is) where our segment is
    seen = set()
    worst = 0.0
    for node in scene.graph.nodes_geometry:
        matrix, geometry = scene.graph[node]
        segment = geometry
        assert segment in ours, segment
        seen.add(segment)
        worst = max(worst, np.abs(matrix - ours[segment]).max())
    doc, _ = read_glb(path)
    assert seen == set(read_segment_names(doc)) and seen
    assert worst < TOL, f"a segment's node is {worst:.3g} from our frame"
    # every segment node, meshless ones too, by the hierarchy evaluated here
    local = [trs_matrix(n["translation"], n["rotation"]) for n in doc["nodes"]]
    world = world_frames(doc, local)
    nodes = our_segment_nodes(doc, ours)
    assert set(nodes) == set(ours)
    worst = max(np.abs(world[i] - ours[s]).max() for s, i in nodes.items())
    assert worst < TOL, f"a segment's node is {worst:.3g} from our frame"
    np.testing.assert_allclose(scene.bounds.reshape(-1), box, rtol=0, atol=BOX_TOL)


# ---- the animation --------------------------------------------------------

@pytest.mark.parametrize("figure", sorted(FIGURES))
def test_animation_plays_the_postures(figure, tmp_path):
    args = FIGURES[figure]
    qfile = write_qfile(figure, tmp_path, seed=23)
    if not qfile:
        pytest.skip(f"{figure} has no dofs: one posture, nothing to animate")
    path = export(figure, tmp_path, "--q-file", qfile, kind="animated")
    frames = read_segments(run_tool(*args, "--q-file", qfile, "segments"))
    initial = read_segments(run_tool(*args, "segments"))[0]
    doc, binary = read_glb(path)
    assert len(doc["animations"]) == 1
    anim = doc["animations"][0]
    nodes = our_segment_nodes(doc, initial)
    # the nodes hold the posture now: the initial one
    world = world_frames(doc, [trs_matrix(n["translation"], n["rotation"]) for n in doc["nodes"]])
    assert max(np.abs(world[i] - initial[s]).max() for s, i in nodes.items()) < TOL
    for s in anim["samplers"]:
        times = accessor(doc, binary, s["input"])[:, 0]
        np.testing.assert_allclose(times, FRAME_SECONDS * np.arange(len(frames)), atol=1e-7)
        acc = doc["accessors"][s["input"]]
        assert acc["min"] == [float(times[0])] and acc["max"] == [float(times[-1])]
    # rotations keep to one hemisphere key to key, so a viewer turns the short way
    for ch in anim["channels"]:
        if ch["target"]["path"] == "rotation":
            q = accessor(doc, binary, anim["samplers"][ch["sampler"]]["output"])
            assert (np.sum(q[1:] * q[:-1], axis=1) >= 0).all()
    worst = 0.0
    for k, ours in enumerate(frames):
        world = world_frames(doc, pose_at(doc, binary, k * FRAME_SECONDS))
        worst = max(worst, max(np.abs(world[i] - ours[s]).max() for s, i in nodes.items()))
    print(f"{figure}: the keyframes put the segments within {worst:.3g} of ours")
    assert worst < TOL, f"a keyframe puts a segment {worst:.3g} from our frame"


# ---- bad requests ---------------------------------------------------------

BAD = {
    "unknown option": (["--bogus", "1"], "out/x.glb", "unknown option"),
    "not .glb": ([], "out/x.gltf", "ending in .glb"),
    "no --out": ([], None, "needs --out"),
    "no such directory": ([], "out/missing/x.glb", "No such file or directory"),
    "a file for a directory": ([], "out/file/x.glb", "Not a directory"),
    "a read-only directory": ([], "out/x.glb", "Permission denied"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_request_writes_nothing(case, tmp_path):
    extra, out, says = BAD[case]
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "file").write_text("")
    if case == "a read-only directory":
        if os.geteuid() == 0:
            pytest.skip("root writes into a read-only directory")
        (tmp_path / "out").chmod(0o555)
    cmd = [str(BUILD / "bin" / "posture-figure"), *extra]
    if out:
        cmd += ["--out", str(tmp_path / out)]
    try:
        proc = subprocess.run([*cmd, "gltf"], capture_output=True, text=True, timeout=60)
    finally:
        (tmp_path / "out").chmod(0o755)
    assert proc.returncode != 0
    assert says in proc.stderr, proc.stderr
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["file"]


# ---- over the socket: the environment and its history -------------------------

def test_daemon_exports_the_environment_and_its_history(daemon_factory):
    """`export gltf * PATH session`: a human posed step by step beside a chair that comes
    in half way. The validator reports nothing; the animation has a keyframe a history
    step; at each one the human's segments are where ours are for the joint values the
    daemon reported at that step, and the chair, absent before it came, holds its place."""
    daemon = daemon_factory(extra=["--library", str(ROOT / "src" / "figure" / "library")])
    c = daemon.client()
    c.request("load human as jack")
    dofs = read_dofs(["--human"])
    rng = np.random.default_rng(31)
    steps = []

    def posture():
        got = c.request("get posture jack")["posture"]
        return [got[name.rsplit("__", 1)[0]][int(name.rsplit("__", 1)[1])] for name, _, _ in dofs]

    for k, joint in enumerate(["knee_l", "shoulder_r", "hip_r", "elbow_l"]):
        steps.append(posture())
        if k == 2:
            c.request("load figure lib:chair.fig as chair")
            steps.append(posture())
        lo, hi = zip(*[(lo, hi) for name, lo, hi in dofs if name.startswith(joint + "__")])
        c.request(f"set joint jack {joint} " + " ".join(repr(float(v)) for v in rng.uniform(lo, hi)))
    steps.append(posture())
    got = c.request("export gltf * scene.glb session")
    # the first undo step is the empty environment: it holds the first posture
    assert got == {"path": "scene.glb", "figures": 2, "frames": len(steps) + 1}
    path = daemon.state_dir / "scene.glb"
    OUTPUT.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(path, OUTPUT / "environment-session.glb")
    issues = validate(path)["issues"]
    assert issues["numErrors"] == 0 and issues["numWarnings"] == 0, issues["messages"][:20]

    doc, binary = read_glb(path)
    tops = {doc["nodes"][i]["name"]: i for i in doc["scenes"][0]["nodes"]}
    assert set(tops) == {"jack", "chair"}
    qfile = daemon.dir / "steps.q"
    qfile.write_text("\n".join(" ".join(repr(v) for v in q) for q in [steps[0]] + steps) + "\n")
    ours = read_segments(run_tool("--human", "--q-file", qfile, "segments"))
    chair = read_segments(run_tool(*FIGURE_ARGS["chair"], "segments"))[0]
    worst = 0.0
    for k, want in enumerate(ours):
        world = world_frames(doc, pose_at(doc, binary, k * FRAME_SECONDS))
        jack = {doc["nodes"][i]["name"]: w for i, w in world.items()
                if i in subtree(doc, tops["jack"]) and doc["nodes"][i]["name"] in want}
        worst = max(worst, max(np.abs(jack[s] - want[s]).max() for s in want))
        worst = max(worst, np.abs(world[doc["nodes"][tops["chair"]]["children"][0]]
                                  - chair["chair"]).max())
    assert worst < TOL, f"a keyframe puts a segment {worst:.3g} from ours"


def subtree(doc, i):
    """node i and every node below it"""
    out = {i}
    for c in doc["nodes"][i].get("children", []):
        out |= subtree(doc, c)
    return out


def test_daemon_gltf_refusals_write_nothing(daemon):
    c = daemon.client()
    c.request("load human as jack")
    before = sorted(p.name for p in daemon.state_dir.iterdir())
    for line, code in [("export gltf jack x.glb session", "nothing"),  # no history yet
                       ("export gltf jack x.glb pose", "bad-argument"),
                       ("export gltf jack x.gltf", "bad-argument"),
                       ("export gltf nobody x.glb", "not-found"),
                       ("export gltf * ../x.glb", "denied")]:
        with pytest.raises(PostureError) as e:
            c.request(line)
        assert e.value.code == code, (line, e.value)
    assert sorted(p.name for p in daemon.state_dir.iterdir()) == before
