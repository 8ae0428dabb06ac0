"""`analyze visibility FIG TARGET`: what a manikin sees of a target.

- The share seen, against independent ray casting: trimesh (its ray_triangle engine, no
  embree) on `export gltf * PATH` of the same scene, rays from the reply's eye through the
  reply's map (aim, field, 96 x 96): at the pixel centres the share agrees with the id
  pass to a few pixels; on a 2 x 2 finer grid (the share itself, to the pixel's
  resolution) within the map's resolution (the reply's edge pixels' share). Scenes: a box
  partly behind a thin box, a box behind another manikin, the manikin's own hand behind
  its body. The occluders named are the ones the rays hit, with their shares.
- The manikin's head and eyeballs, which the eye sits in, hide nothing (left out of the
  reference too).
- The angle and the cone of a point placed at a known angle from the line of sight.
- Fixation: the eye joints set to the reply's eye rotation (and the figure turned about
  the eye by the head rotation) put the line of sight through the target, within the
  eyes' limits, and analysed again from there the target is on the line of sight.
- Points: seen (1) or hidden (0), the first thing on the ray named.
- Bad input is refused and changes nothing.
"""
import math
import re
import shutil

import numpy as np
import pytest

from daemon import daemon, daemon_factory  # noqa: F401 (fixtures)

trimesh = pytest.importorskip("trimesh")
pytest.importorskip("rtree")  # trimesh's ray_triangle engine indexes the triangles with it

OWN = ("head", "eyeball_l", "eyeball_r")  # the parts the eye sits in: no occluders
FINE = 2  # rays a pixel's side on the finer grid


def box_figure(name, size_cm, at_cm):
    sx, sy, sz = size_cm
    x, y, z = at_cm
    return (f"figure {name} {{ segment {name} {{ mass = 1kg; color = (0.7, 0.5, 0.3);\n"
            f"geometry = box({sx}cm, {sy}cm, {sz}cm) at trans(0cm, 0cm, 0cm);\n"
            f"site base->location = trans(0cm, 0cm, 0cm); }}\n"
            f"root = {name}.base; location = trans({x}cm, {y}cm, {z}cm); }}\n")


def load_box(c, daemon, name, size_cm, at_cm):
    (daemon.state_dir / f"{name}.fig").write_text(box_figure(name, size_cm, at_cm))
    c.request(f"load figure {name}.fig")


def scene_meshes(c, daemon):
    """every segment's triangles in the world from the glTF export of the scene, labelled
    FIG.SEG (trimesh poses the scene graph; the node under the root is the figure)"""
    c.request("export gltf * vis.glb")
    path = daemon.state_dir / "vis.glb"
    scene = trimesh.load(str(path), force="scene")
    parents = scene.graph.transforms.parents
    segments = {}
    for f in c.request("list figures")["figures"]:
        segments[f["name"]] = {s["name"] for s in c.request(f"show figure {f['name']}")["segments"]}
    meshes = {}
    for node in scene.graph.nodes_geometry:
        matrix, geometry = scene.graph[node]
        chain = [node]
        while chain[-1] in parents and parents[chain[-1]] != scene.graph.base_frame:
            chain.append(parents[chain[-1]])
        fig = chain[-1]
        # trimesh gives a repeated name a suffix (_1): the segment's own name without it
        seg = node if node in segments[fig] else re.sub(r"_\d+$", "", node)
        assert seg in segments[fig], (node, fig)
        mesh = scene.geometry[geometry].copy()
        mesh.apply_transform(matrix)
        meshes[f"{fig}.{seg}"] = mesh
    return meshes


def map_rays(reply, sub):
    """rays from the reply's eye through a sub x sub grid in each pixel of its map: origins,
    unit directions, each ray's solid angle weight (cos^3 off the axis), pixel index"""
    m = reply["map"]
    eye, aim, n = np.array(reply["eye"]), np.array(m["aim"]), m["size"]
    f = aim - eye
    f /= np.linalg.norm(f)
    x = np.cross(f, [0, 1, 0])  # the camera's x horizontal (view_camera_aim)
    x /= np.linalg.norm(x)
    y = np.cross(x, f)
    t = math.tan(math.radians(m["fov"] / 2))
    k = (np.arange(n * sub) + 0.5) / (n * sub)
    xn = (2 * k - 1) * t
    yn = (1 - 2 * k) * t
    XN, YN = np.meshgrid(xn, yn)
    d = f + XN[..., None] * x + YN[..., None] * y
    w = 1 / (1 + XN ** 2 + YN ** 2) ** 1.5
    d = d.reshape(-1, 3)
    d /= np.linalg.norm(d, axis=1)[:, None]
    py, px = np.meshgrid(np.arange(n * sub) // sub, np.arange(n * sub) // sub, indexing="ij")
    return np.tile(eye, (len(d), 1)), d, w.reshape(-1), (py * n + px).reshape(-1)


def first_hits(meshes, names, origins, dirs, chunk=4000):
    """the label of the first triangle each ray (one origin) hits among the named meshes
    ('' none). Only the triangles that can meet the rays' cone are given to trimesh (its
    candidates are every triangle a ray's long box meets), and the rays go in chunks."""
    eye = origins[0]
    axis = dirs.mean(axis=0)
    axis /= np.linalg.norm(axis)
    spread = math.acos(max(-1.0, min(1.0, float((dirs @ axis).min()))))
    tris, labels = [], []
    for k, nm in enumerate(names):
        t = meshes[nm].triangles  # n x 3 x 3
        c = t.mean(axis=1)
        rad = np.linalg.norm(t - c[:, None, :], axis=2).max(axis=1)
        v = c - eye
        dist = np.linalg.norm(v, axis=1)
        off = np.arccos(np.clip((v @ axis) / np.maximum(dist, 1e-12), -1, 1))
        near = np.arcsin(np.clip(rad / np.maximum(dist, 1e-12), 0, 1))
        keep = (dist <= rad) | (off - near <= spread + 1e-3)
        tris.append(t[keep])
        labels.append(np.full(int(keep.sum()), k))
    tris = np.concatenate(tris)
    label = np.concatenate(labels)
    who = np.full(len(origins), -1)
    if len(tris):
        whole = trimesh.Trimesh(vertices=tris.reshape(-1, 3),
                                faces=np.arange(3 * len(tris)).reshape(-1, 3), process=False)
        engine = trimesh.ray.ray_triangle.RayMeshIntersector(whole)
        for a in range(0, len(origins), chunk):
            tri, ray = engine.intersects_id(origins[a:a + chunk], dirs[a:a + chunk],
                                            multiple_hits=False)[:2]
            who[a + ray] = label[tri]
    return np.array([names[i] if i >= 0 else "" for i in who])


def reference(meshes, reply, target, manikin, sub):
    """the share of the target seen and each occluder's share, by rays on the map's grid"""
    o, d, w, pix = map_rays(reply, sub)
    alone = first_hits(meshes, [target], o, d) == target
    names = [nm for nm in meshes if not (nm.split(".")[0] == manikin and
                                          nm.split(".")[1] in OWN and nm != target)]
    sel = np.nonzero(alone)[0]
    hit = first_hits(meshes, names, o[sel], d[sel])
    ws = w[sel]
    total = ws.sum()
    seen = ws[hit == target].sum() / total
    occ = {}
    for nm in set(hit) - {target}:
        occ[nm] = ws[hit == nm].sum() / total
    return seen, occ, len(sel)


def check_against_rays(c, daemon, manikin, target):
    reply = c.request(f"analyze visibility {manikin} {target}")
    meshes = scene_meshes(c, daemon)
    m = reply["map"]
    # at the pixel centres: the id pass, but for a few pixels along edges
    seen1, occ1, npix = reference(meshes, reply, target, manikin, 1)
    assert abs(npix - m["pixels"]) <= 0.02 * m["pixels"] + 2, (npix, m["pixels"])
    assert abs(reply["fraction"] - seen1) <= 0.01, (reply["fraction"], seen1)
    # the share itself (a finer grid): within the map's resolution
    seen4, occ4, _ = reference(meshes, reply, target, manikin, FINE)
    assert abs(reply["fraction"] - seen4) <= m["resolution"], (reply["fraction"], seen4, m)
    # the occluders: those the rays hit, each share within the resolution
    got = {o["name"]: o["fraction"] for o in reply["occluders"]}
    big = {nm for nm, s in occ4.items() if s > m["resolution"]}
    assert big <= set(got), (big, got)
    for nm, s in got.items():
        assert abs(s - occ4.get(nm, 0.0)) <= m["resolution"], (nm, s, occ4)
    assert abs(reply["fraction"] + sum(got.values()) + reply["hidden_by_others"] - 1) < 1e-9
    return reply, seen4, occ4


def test_a_box_partly_behind_a_thin_box(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        load_box(c, daemon, "target", (40, 40, 10), (0, 164, 200))
        load_box(c, daemon, "screen", (20, 60, 2), (16, 164, 120))
        reply, seen, occ = check_against_rays(c, daemon, "jack", "target.target")
        # the screen's edge at x = 6 cm, 1.1 m away, is at 10.4 cm on the target's face
        # 1.85 m away (its left 30 of 40 cm seen, by area; the rays weigh solid angle)
        assert 0.6 < reply["fraction"] < 0.8, reply
        assert [o["name"] for o in reply["occluders"]] == ["screen.screen"]
        assert reply["map"]["resolution"] < 0.15
        # nothing between: all of it
        c.request("unload figure screen")
        assert c.request("analyze visibility jack target.target")["fraction"] == 1.0


def test_a_box_behind_another_manikin(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        c.request("load human as jill")
        x, y, z = c.request("get site jack pelvis.root")["position"]
        c.request(f"set location jill {x + 0.12} {y} {z + 1.0}")
        load_box(c, daemon, "target", (50, 50, 10), (0, 150, 250))
        reply, seen, occ = check_against_rays(c, daemon, "jack", "target.target")
        assert 0.05 < reply["fraction"] < 0.95, reply
        assert reply["occluders"] and all(o["name"].startswith("jill.")
                                          for o in reply["occluders"]), reply


def test_the_manikins_own_body_hides_its_hand(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        reply, seen, occ = check_against_rays(c, daemon, "jack", "jack.hand_r")
        assert reply["fraction"] < 0.2 and reply["occluders"], reply
        assert all(o["name"].startswith("jack.") and o["name"].split(".")[1] not in OWN
                   for o in reply["occluders"]), reply
        # the hand held up in front of the face: all of it seen, the head hides nothing
        c.request("set joint jack shoulder_r 90deg 0 0")
        c.request("set joint jack elbow_r 90deg")
        reply, seen, occ = check_against_rays(c, daemon, "jack", "jack.hand_r")
        assert reply["fraction"] > 0.9, reply


def point(p):
    return ",".join(repr(float(v)) for v in p)


def eyes_line(c, fig="jack"):
    ps, zs = [], []
    for s in ("eyeball_l.gaze", "eyeball_r.gaze"):
        r = c.request(f"get site {fig} {s}")
        ps.append(np.array(r["position"]))
        zs.append(np.array(r["rotation"]).reshape(3, 3)[:, 2])
    d = zs[0] + zs[1]
    return (ps[0] + ps[1]) / 2, d / np.linalg.norm(d)


def angle(a, b):
    return math.degrees(math.acos(max(-1.0, min(1.0, float(np.dot(a, b))))))


def test_angle_and_cone_of_a_point_at_a_known_angle(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        eye, sight = eyes_line(c)
        assert np.abs(sight - [0, 0, 1]).max() < 1e-9  # standing, looking along +z
        # (deg off the line of sight, turned about it by deg) -> the narrowest default cone
        for a, about, cone in ((1.2, 0, 3), (1.6, 90, 20), (7, 30, 20), (25, 200, 60),
                               (19.9, 300, 40), (35, 45, None), (120, 10, None)):
            u = np.array([math.sin(math.radians(a)) * math.cos(math.radians(about)),
                          math.sin(math.radians(a)) * math.sin(math.radians(about)),
                          math.cos(math.radians(a))])
            p = eye + 1.5 * u
            r = c.request(f"analyze visibility jack {point(p)}")
            assert abs(r["angle"] - a) < 1e-9, (a, r)
            assert r["cone"] == cone, (a, r)
            assert r["fraction"] == 1.0 and r["occluders"] == []
            assert np.abs(np.array(r["eye"]) - eye).max() < 1e-12
        # the eye view's cones, when it has them
        c.request("add view eyes eyes=jack")
        c.request("set view eyes cones=10,50")
        p = eye + 1.5 * np.array([math.sin(math.radians(4)), 0, math.cos(math.radians(4))])
        assert c.request(f"analyze visibility jack {point(p)}")["cone"] == 10
        q = eye + 1.5 * np.array([math.sin(math.radians(6)), 0, math.cos(math.radians(6))])
        assert c.request(f"analyze visibility jack {point(q)}")["cone"] == 50
        c.request("set view eyes cones=off")
        assert c.request(f"analyze visibility jack {point(p)}")["cone"] is None


def rot_about(axis, deg):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    a = math.radians(deg)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(a) * k + (1 - math.cos(a)) * k @ k


def axis_angle(r):
    a = math.acos(max(-1.0, min(1.0, (np.trace(r) - 1) / 2)))
    if a < 1e-12:
        return np.array([0, 1, 0]), 0.0
    v = np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]])
    return v / np.linalg.norm(v), a


@pytest.mark.parametrize("target", [(0.6, 1.9, 1.5), (-0.4, 1.1, 1.2), (2.0, 1.7, 0.3),
                                    (-1.0, 2.6, -0.8), (0.3, 0.2, 0.9), (0.2, 1.5, -2.0)])
def test_the_rotations_fixate_the_target(daemon, target):
    with daemon.client() as c:
        c.request("load human as jack")
        eye, _ = eyes_line(c)
        p = np.array(target)
        r = c.request(f"analyze visibility jack {point(p)}")
        ey, ep = r["eye_rotation"]["yaw"], r["eye_rotation"]["pitch"]
        hy, hp = r["head_rotation"]["yaw"], r["head_rotation"]["pitch"]
        assert -45 - 1e-9 <= ey <= 45 + 1e-9 and -45 - 1e-9 <= ep <= 35 + 1e-9, r
        # the head's turn about the eye: the whole figure turned so (standing, its head
        # frame is the world's): yaw about y, then pitch up (about -x) in the turned frame
        turn = rot_about([0, 1, 0], hy) @ rot_about([-1, 0, 0], hp)
        root = np.array(c.request("get site jack pelvis.root")["position"])
        assert np.abs(np.array(c.request("get site jack pelvis.root")["rotation"]) -
                      np.eye(3).reshape(-1)).max() < 1e-12
        new_root = eye + turn @ (root - eye)
        ax, ang = axis_angle(turn)
        c.request(f"set location jack {' '.join(repr(float(v)) for v in new_root)} "
                  f"rot={point(ax)},{float(ang)!r}")
        # the eyes: the left's abduction turns it to +x, the right's mirrored
        c.request(f"set joint jack eye_l {float(ey)!r}deg {float(ep)!r}deg")
        c.request(f"set joint jack eye_r {float(-ey)!r}deg {float(ep)!r}deg")
        eye2, sight = eyes_line(c)
        assert np.abs(eye2 - eye).max() < 1e-9
        to = (p - eye2) / np.linalg.norm(p - eye2)
        assert angle(sight, to) < 0.01, (r, angle(sight, to))
        # analysed again from there: on the line of sight, no turn needed
        again = c.request(f"analyze visibility jack {point(p)}")
        assert again["angle"] < 0.01, again
        assert max(abs(v) for v in again["head_rotation"].values()) < 1e-6, again


def test_points_and_sites_seen_or_hidden(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        load_box(c, daemon, "screen", (20, 60, 2), (10, 164, 120))
        eye, _ = eyes_line(c)
        hidden = c.request(f"analyze visibility jack {point((0.1, eye[1], 2))}")
        assert hidden["fraction"] == 0.0 and hidden["occluders"] == [
            {"name": "screen.screen", "fraction": 1.0}], hidden
        seen = c.request(f"analyze visibility jack {point((-0.1, eye[1], 2))}")
        assert seen["fraction"] == 1.0 and seen["occluders"] == []
        # far to the left at the eyes' height: the ray leaves through the left eyeball,
        # which the eye sits beside and which hides nothing
        side = c.request(f"analyze visibility jack {point((2.0, eye[1], eye[2]))}")
        assert side["fraction"] == 1.0 and side["occluders"] == [], side
        # a site: its own segment does not hide it (the screen's base, inside the box, is
        # seen as the box is); the palm at the side is behind the body
        base = c.request("analyze visibility jack screen.screen.base")
        assert base["fraction"] == 1.0 and base["occluders"] == [], base
        palm = c.request("analyze visibility jack jack.hand_r.palm")
        assert palm["fraction"] == 0.0 and palm["occluders"][0]["name"].startswith("jack.T")
        # the trimesh ray agrees: the first thing hit on the way is that segment
        meshes = scene_meshes(c, daemon)
        p = np.array(palm["point"])
        d = (p - eye) / np.linalg.norm(p - eye)
        names = [nm for nm in meshes if nm.split(".")[1] not in OWN + ("hand_r",)]
        first = first_hits(meshes, names, eye[None, :], d[None, :])[0]
        assert first == palm["occluders"][0]["name"]


def test_bad_input_is_refused_and_changes_nothing(daemon):
    with daemon.client() as c:
        c.request("load human as jack")
        load_box(c, daemon, "box", (20, 20, 20), (0, 100, 100))
        before = c.request("status")["posture"]
        undo = c.request("status")["undo"]
        for line, code in (("analyze visibility nobody 0,1,2", "not-found"),
                           ("analyze visibility box 0,1,2", "bad-argument"),
                           ("analyze visibility jack 0,1", "bad-number"),
                           ("analyze visibility jack 0,1,x", "bad-number"),
                           ("analyze visibility jack box", "bad-argument"),
                           ("analyze visibility jack .box", "bad-argument"),
                           ("analyze visibility jack box.", "bad-argument"),
                           ("analyze visibility jack nobody.box", "not-found"),
                           ("analyze visibility jack box.lid", "not-found"),
                           ("analyze visibility jack jack.hand_r.nothing", "not-found"),
                           ("analyze visibility jack jack.head", "bad-argument"),
                           ("analyze visibility jack", "arity"),
                           ("analyze visibility jack 0,1,2 3,4,5", "arity")):
            reply = c.request_reply(line)
            assert not reply["ok"] and reply["error"]["code"] == code, (line, reply)
        eye, _ = eyes_line(c)
        reply = c.request_reply(f"analyze visibility jack {point(eye)}")
        assert not reply["ok"] and reply["error"]["code"] == "bad-argument", reply
        assert c.request("status")["posture"] == before
        assert c.request("status")["undo"] == undo
        # and it keeps answering
        assert c.request("analyze visibility jack box.box")["fraction"] == 1.0
