"""Reach envelopes through the daemon (`analyze reach`, `list envelopes`, `set envelope`,
`remove envelope`, `export envelope`).

The envelope is checked against the daemon's own reach solver asked point by point (`can
reach`, the solve the verdicts come from), and the exported files are read by a library
we did not write (trimesh):

- every sampled envelope vertex is reached (palm within 1 mm, the solved posture within
  every joint's limits), and the point two grid steps outward along the surface's normal
  is not;
- the files are watertight and hold the volume and bounds the reply gave, and the glTF
  ones pass the Khronos validator;
- the body's envelope contains the arm's (a generalised winding number, computed here);
- the verdicts for targets are `can reach`'s, for one figure and for each manikin of a
  family, and the family's answer lists who reaches each target;
- bad requests are refused with nothing changed (posture hash, envelopes kept);
- the envelope is drawn: a view's picture changes with it, and is the old one again when
  it is hidden or removed; a figure unloaded takes its envelopes with it.

Coarse grids (8 cm) keep the time down; the sampled checks are seeded.
"""
import base64
import json
import math
import random
import struct

import numpy as np
import pytest

from daemon import PostureError, daemon, daemon_factory  # noqa: F401 (fixtures)
from test_assess_tint import decode_png

trimesh = pytest.importorskip("trimesh")

RES = 0.08          # m: the grid of the envelopes computed here
ARM_RESTARTS = 4    # envelope.h's ENVELOPE_ARM_RESTARTS: the arm's solves try again from
                    # random postures when stuck short (can reach ... restarts=N does the same)
BODY_RES = 0.25     # m: envelope.h's ENVELOPE_RES_MAX, for mode=body
TIMEOUT = 900       # s: a reply may wait for an envelope computed on a busy machine
TOL_POS = 1e-3      # m: reach.h's REACH_TOL_POS, the residual allowed
TOL_LIMIT = 1e-9    # rad: a joint value on its limit
SAMPLES = 24        # vertices checked by can reach
VIEW = "add view main width=320 height=240 eye=1.9,1.55,3.1 target=0,0.95,0"


def xyz(p):
    return ",".join(f"{x:.6f}" for x in p)


def winding(points, V, F):
    """The generalised winding number of a closed, outward-wound triangle mesh (V, F) at
    each point: 1 inside, 0 outside (Van Oosterom and Strackee's solid angle of each
    triangle, summed over 4 pi)."""
    out = []
    for p in np.atleast_2d(points):
        a, b, c = V[F[:, 0]] - p, V[F[:, 1]] - p, V[F[:, 2]] - p
        la, lb, lc = (np.linalg.norm(x, axis=1) for x in (a, b, c))
        det = np.einsum("ij,ij->i", a, np.cross(b, c))
        den = (la * lb * lc + np.einsum("ij,ij->i", a, b) * lc
               + np.einsum("ij,ij->i", b, c) * la + np.einsum("ij,ij->i", c, a) * lb)
        out.append(np.sum(2 * np.arctan2(det, den)) / (4 * math.pi))
    return np.array(out)


def export(c, daemon, name, file, *extra):
    c.request(f"export envelope {name} {file} {' '.join(extra)}".strip())
    return trimesh.load(str(daemon.state_dir / file), force="mesh")


def glb_arrays(path, mesh=0):
    """positions, normals and triangles of a GLB's mesh, read from its chunks here (trimesh
    recomputes normals from the faces; these are the file's own)"""
    b = path.read_bytes()
    jlen = struct.unpack("<I", b[12:16])[0]
    doc, binary = json.loads(b[20:20 + jlen]), b[20 + jlen + 8:]
    prim = doc["meshes"][mesh]["primitives"][0]

    def array(k, dtype, width):
        acc = doc["accessors"][k]
        view = doc["bufferViews"][acc["bufferView"]]
        raw = binary[view["byteOffset"]:view["byteOffset"] + view["byteLength"]]
        return np.frombuffer(raw, dtype=dtype).reshape(-1, width)
    return (array(prim["attributes"]["POSITION"], "<f4", 3).astype(float),
            array(prim["attributes"]["NORMAL"], "<f4", 3).astype(float),
            array(prim["indices"], "<u4", 3).astype(np.int64))


def limits(c, fig):
    return {j["name"]: (j["lower"], j["upper"]) for j in c.request(f"show figure {fig}")["joints"]}


def within_limits(posture, lim):
    for joint, values in posture.items():
        lo, hi = lim[joint]
        for v, a, b in zip(values, lo, hi):
            if not a - TOL_LIMIT <= v <= b + TOL_LIMIT:
                return False
    return True


def test_the_reply_and_the_envelope_kept(daemon):
    with daemon.client(timeout=TIMEOUT) as c:
        c.request("load human as probe")
        e = c.request(f"analyze reach probe hand=right mode=arm resolution={RES}")
        for key in ("volume", "bounds", "vertices", "triangles", "resolution", "grid", "solves",
                    "seconds"):
            assert key in e, key
        assert e["name"] == "probe.right.arm" and e["figure"] == "probe"
        assert e["resolution"] == RES and e["hand"] == "right" and e["mode"] == "arm"
        assert e["vertices"] > 0 and e["triangles"] > 0 and e["solves"] > 0
        # the arm's envelope holds the shoulder and lies within an arm's length (< 0.9 m) of it
        sh = c.request("get site probe clavicle_r.shoulder_r")["position"]
        lo, hi = e["bounds"]
        assert all(lo[i] < sh[i] < hi[i] for i in range(3))
        assert all(hi[i] - lo[i] < 2 * 0.9 for i in range(3))
        assert 4 / 3 * math.pi * 0.3 ** 3 < e["volume"] < 4 / 3 * math.pi * 0.9 ** 3
        kept = c.request("list envelopes")["envelopes"]
        assert [k["name"] for k in kept] == ["probe.right.arm"]
        assert kept[0]["volume"] == e["volume"] and kept[0]["hidden"] is False
        # computed again under the same name: replaced, not added; another name: added
        c.request(f"analyze reach probe hand=right mode=arm resolution={RES}")
        c.request(f"analyze reach probe hand=right mode=arm resolution={RES} name=second")
        assert [k["name"] for k in c.request("list envelopes")["envelopes"]] == \
            ["probe.right.arm", "second"]


def test_the_files_hold_the_surface_the_reply_describes(daemon):
    """STL, GLB and glTF read by trimesh: the reply's volume (float32 vertices: to 1e-5
    relative) and bounds (1e-6 m)."""
    with daemon.client(timeout=TIMEOUT) as c:
        c.request("load human as probe")
        e = c.request(f"analyze reach probe hand=left mode=arm resolution={RES}")
        for file in ("env.stl", "env.glb", "env.gltf"):
            m = export(c, daemon, "probe.left.arm", file)
            assert m.volume == pytest.approx(e["volume"], rel=1e-5), file
            assert np.allclose(m.bounds, e["bounds"], atol=1e-6), file
        with pytest.raises(PostureError):  # only the three endings
            c.request("export envelope probe.left.arm env.obj")
        with pytest.raises(PostureError):  # no comfort zone was asked for
            c.request("export envelope probe.left.arm env.stl part=comfort")
        with pytest.raises(PostureError):
            c.request("export envelope nothing env.stl")


def test_the_khronos_validator_finds_nothing(daemon):
    """The glTF files (binary and text, with the comfort zone as a second mesh) pass the
    Khronos glTF validator with no error, warning, info or hint."""
    from test_export_gltf import validate
    with daemon.client(timeout=TIMEOUT) as c:
        c.request("load human as probe")
        c.request(f"analyze reach probe hand=right mode=arm resolution={RES} comfort=on")
        for file in ("env.glb", "env.gltf"):
            assert c.request(f"export envelope probe.right.arm {file}")["meshes"] == 2
            report = validate(daemon.state_dir / file)
            assert report["issues"]["messages"] == [], (file, report["issues"])
            assert report["issues"]["numErrors"] == report["issues"]["numWarnings"] == 0


def test_vertices_are_reached_and_points_outside_are_not(daemon):
    """On the human: each sampled vertex is reached by can reach's arm solve (palm within
    1 mm, every joint within its limits); the point two grid steps outward along the
    surface's normal is not reached."""
    with daemon.client(timeout=TIMEOUT) as c:
        c.request("load human as probe")
        c.request(f"analyze reach probe hand=right mode=arm resolution={RES}")
        c.request("export envelope probe.right.arm arm.glb")
        V, N, F = glb_arrays(daemon.state_dir / "arm.glb")
        assert np.allclose(np.linalg.norm(N, axis=1), 1, atol=1e-5)
        lim = limits(c, "probe")
        rng = random.Random(5)
        idx = rng.sample(range(len(V)), SAMPLES)
        short, outside_reached, checked_out = [], [], 0
        for i in idx:
            v, n = V[i], N[i]
            r = c.request(f"can reach probe hand=right {xyz(v)} mode=arm restarts={ARM_RESTARTS}")
            if not (r["reached"] and r["distance"] <= TOL_POS and within_limits(r["posture"], lim)):
                short.append((list(v), r["distance"]))
            out = v + 2 * RES * n
            if winding(out, V, F)[0] > 0.5:
                continue  # a fold of the surface: two steps out is inside it again
            checked_out += 1
            if c.request(f"can reach probe hand=right {xyz(out)} mode=arm "
                         f"restarts={ARM_RESTARTS}")["reached"]:
                outside_reached.append(list(out))
        assert not short, short
        assert checked_out >= SAMPLES * 3 // 4
        assert not outside_reached, outside_reached


def test_the_body_envelope_contains_the_arm_envelope(daemon):
    with daemon.client(timeout=TIMEOUT) as c:
        c.request("load human as probe")
        # the body's solves are slow (minutes at 20 cm on two busy cores): the coarsest grid
        arm = c.request(f"analyze reach probe hand=right mode=arm resolution={BODY_RES}")
        body = c.request(f"analyze reach probe hand=right mode=body resolution={BODY_RES}")
        assert body["name"] == "probe.right.body"
        assert body["volume"] > arm["volume"]
        a = export(c, daemon, "probe.right.arm", "arm.stl")
        b = export(c, daemon, "probe.right.body", "body.stl")
        w = winding(a.vertices, b.vertices, b.faces)
        outside = a.vertices[w < 0.5]
        # contained to the grid's resolution: where the two surfaces meet (the body reaching
        # no further than its arm), a vertex of the arm's may lie outside the body's mesh, but
        # within a grid step of it, and it is one the body reaches
        for p in outside:
            assert np.min(np.linalg.norm(b.vertices - p, axis=1)) <= BODY_RES, p
            assert c.request(f"can reach probe hand=right {xyz(p)} mode=body")["reached"], p
        assert len(outside) <= 0.1 * len(a.vertices)


def test_target_verdicts_are_can_reachs(daemon):
    with daemon.client(timeout=TIMEOUT) as c:
        c.request("load human as probe")
        sh = c.request("get site probe clavicle_r.shoulder_r")["position"]
        pts = [[sh[0] + dx, sh[1] + dy, sh[2] + dz]
               for dx, dy, dz in ((0, 0, 0.4), (-0.3, -0.2, 0.3), (0, 0, 1.2), (0.8, 0.4, 0.6),
                                  (0, -0.9, 0.3), (-0.5, 0.3, 0.1))]
        for mode in ("arm", "torso", "body"):
            h0 = c.request("status")["posture"]
            r = c.request(f"analyze reach probe hand=right mode={mode} "
                          f"targets={';'.join(xyz(p) for p in pts)}")
            assert c.request("status")["posture"] == h0
            assert "volume" not in r  # targets alone: no envelope
            assert len(r["targets"]) == len(pts)
            for p, v in zip(pts, r["targets"]):
                rs = ARM_RESTARTS if mode == "arm" else 0
                ref = c.request(f"can reach probe hand=right {xyz(p)} mode={mode} restarts={rs}")
                assert v["restarts"] == rs
                assert v["reached"] == ref["reached"], (mode, p)
                assert v["distance"] == pytest.approx(ref["distance"], abs=1e-9), (mode, p)
                assert v["shortfall"] == (0 if ref["reached"] else pytest.approx(ref["distance"]))
            got = [v["reached"] for v in r["targets"]]
            assert any(got) and not all(got), mode
        assert c.request("list envelopes")["envelopes"] == []


def test_which_manikins_reach_the_control(daemon):
    """A family at once: each manikin's verdicts are can reach's for it, and each target
    lists the manikins that reach it; the envelope form keeps one envelope per manikin."""
    with daemon.client(timeout=TIMEOUT) as c:
        c.request("load family fam sex=female n=2")
        members = [f["name"] for f in c.request("list figures")["figures"]]
        assert len(members) == 3
        sh = c.request("get site fam_0 clavicle_r.shoulder_r")["position"]
        pts = [[sh[0], sh[1], sh[2] + 0.3], [sh[0], sh[1], sh[2] + 1.5],
               [sh[0] - 0.1, sh[1] - 0.2, sh[2] + 0.62]]
        r = c.request(f"analyze reach family=fam hand=right mode=arm "
                      f"targets={';'.join(xyz(p) for p in pts)}")
        assert r["family"] == "fam" and len(r["figures"]) == 3
        expect = [[] for _ in pts]
        for f in r["figures"]:
            for k, (p, v) in enumerate(zip(pts, f["targets"])):
                ref = c.request(f"can reach {f['figure']} hand=right {xyz(p)} mode=arm "
                                f"restarts={ARM_RESTARTS}")
                assert v["reached"] == ref["reached"]
                if ref["reached"]:
                    expect[k].append(f["figure"])
        assert [sorted(t["reached_by"]) for t in r["targets"]] == [sorted(e) for e in expect]
        assert sorted(expect[0]) == sorted(members) and expect[1] == []
        e = c.request(f"analyze reach family=fam hand=right mode=arm resolution={RES}")
        assert sorted(f["name"] for f in e["figures"]) == sorted(f"{m}.right.arm" for m in members)
        assert len(c.request("list envelopes")["envelopes"]) == 3
        # a manikin unloaded takes its envelope; undo brings the manikin back, not the envelope
        c.request("unload figure fam_1")
        assert "fam_1.right.arm" not in [x["name"] for x in c.request("list envelopes")["envelopes"]]
        c.request("undo")
        assert len(c.request("list envelopes")["envelopes"]) == 2


def test_bad_requests_change_nothing(daemon_factory):
    from test_assess import LIBRARY
    with daemon_factory(extra=LIBRARY).client() as c:
        c.request("load human as probe")
        c.request("load figure lib:box.fig as box")
        c.request(f"analyze reach probe hand=right mode=arm resolution={RES}")
        h0 = c.request("status")["posture"]
        kept = c.request("list envelopes")
        bad = ["analyze reach nobody hand=right",
               "analyze reach box hand=right",
               "analyze reach family=nofamily hand=right",
               "analyze reach probe",
               "analyze reach probe hand=middle",
               "analyze reach probe hand=right mode=fly",
               "analyze reach probe hand=right mode=arm balance=on",
               "analyze reach probe hand=right resolution=1mm",
               "analyze reach probe hand=right resolution=30cm",
               "analyze reach probe hand=right resolution=fine",
               "analyze reach probe hand=right comfort=maybe",
               "analyze reach probe hand=right ranges=shoulder.0=0,10",
               "analyze reach probe hand=right comfort=on ranges=nojoint.0=0,10",
               "analyze reach probe hand=right comfort=on ranges=shoulder.0=10",
               "analyze reach probe hand=right targets=0.1,1.2",
               "analyze reach probe hand=right targets=0.1,1.2,0.3;;",
               "analyze reach probe hand=right targets=0.1,nan,0.3",
               "analyze reach probe hand=right targets=",
               "analyze reach probe hand=right name=a/b",
               "analyze reach probe hand=right targets=0.1,1.2,0.3 name=x",
               "analyze reach probe hand=right 0.1,1.2,0.3",
               "set envelope nothing hidden=yes",
               "set envelope probe.right.arm hidden=maybe",
               "remove envelope nothing",
               "export envelope probe.right.arm ../out.stl"]
        for req in bad:
            with pytest.raises(PostureError):
                c.request(req)
        assert c.request("status")["posture"] == h0
        assert c.request("list envelopes") == kept


BAND = 2 * 20  # the message and status lines at the bottom of a picture (they change)


def pixels(c):
    """view main now, without its message and status lines, as an h x w x 3 int array"""
    png = base64.b64decode(c.request("render view main")["png"])
    return decode_png(png)[:-BAND, :, :3].astype(int)


def test_the_envelope_is_drawn_and_hidden(daemon):
    """A view's picture changes where the envelope is (see-through: the figure shows
    through it), and is the same picture as before when it is hidden or removed."""
    with daemon.client(timeout=TIMEOUT) as c:
        c.request("load human as probe")
        c.request(VIEW)
        before = pixels(c)
        c.request(f"analyze reach probe hand=right mode=arm resolution={RES}")
        drawn = pixels(c)
        changed = np.any(np.abs(drawn - before) > 8, axis=2)
        assert changed.sum() > 0.02 * changed.size
        c.request("set envelope probe.right.arm hidden=yes")
        assert np.array_equal(pixels(c), before)
        c.request("set envelope probe.right.arm hidden=no")
        assert np.array_equal(pixels(c), drawn)
        c.request("remove envelope probe.right.arm")
        assert np.array_equal(pixels(c), before)
        assert c.request("list envelopes")["envelopes"] == []


def test_sessions_and_undo_leave_envelopes_alone(daemon):
    """An envelope is not part of the state: a session saved and loaded, and undo, work
    as before; the envelope of a figure still there stays."""
    with daemon.client(timeout=TIMEOUT) as c:
        c.request("load human as probe")
        c.request("load human as other")
        c.request(f"analyze reach probe hand=right mode=arm resolution={RES}")
        c.request("save session s.session")
        assert "envelope" not in (daemon.state_dir / "s.session").read_text()
        c.request("undo")  # the second human goes; probe's envelope stays
        assert [x["name"] for x in c.request("list envelopes")["envelopes"]] == ["probe.right.arm"]
        c.request("load session s.session")
        assert [x["name"] for x in c.request("list envelopes")["envelopes"]] == ["probe.right.arm"]
        c.request("unload figure probe")
        assert c.request("list envelopes")["envelopes"] == []


def test_the_comfort_zone(daemon):
    """comfort=on: the zone lies inside the envelope, each range in the reply says where
    its default comes from, and a range set says "set"."""
    with daemon.client(timeout=TIMEOUT) as c:
        c.request("load human as probe")
        e = c.request(f"analyze reach probe hand=right mode=arm resolution={RES} comfort=on")
        z = e["comfort"]
        assert 0 < z["volume"] < e["volume"]
        assert z["ranges"] and all(r["source"] and r["source"] != "set" for r in z["ranges"])
        reach = export(c, daemon, "probe.right.arm", "reach.stl")
        zone = export(c, daemon, "probe.right.arm", "zone.stl", "part=comfort")
        assert zone.volume == pytest.approx(z["volume"], rel=1e-5)
        # inside the envelope; where the two surfaces meet (the comfort ranges not binding)
        # a zone vertex may lie a grid step outside the envelope's surface: still reached
        pts = zone.vertices[::7]
        outside = pts[winding(pts, reach.vertices, reach.faces) < 0.5]
        assert len(outside) <= 0.25 * len(pts)
        for p in outside[:8]:
            assert c.request(f"can reach probe hand=right {xyz(p)} mode=arm "
                             f"restarts={ARM_RESTARTS}")["reached"], p
        r0 = z["ranges"][0]
        key = f"{r0['joint']}.{r0['dof']}"
        lo, hi = r0["lo"], (r0["lo"] + r0["hi"]) / 2  # a narrower range: a smaller zone
        e2 = c.request(f"analyze reach probe hand=right mode=arm resolution={RES} comfort=on "
                       f"ranges={key}={lo},{hi}")
        r1 = e2["comfort"]["ranges"][0]
        assert r1["source"] == "set" and r1["lo"] == pytest.approx(lo) and r1["hi"] == pytest.approx(hi)
        assert e2["comfort"]["volume"] <= z["volume"]
        # targets with comfort=on: reached within the comfort ranges or not, no envelope made;
        # the zone's vertices are; envelope vertices two grid steps from the zone are not
        rng = random.Random(9)
        inside = [zone.vertices[i] for i in rng.sample(range(len(zone.vertices)), 4)]
        far = [v for v in reach.vertices
               if np.min(np.linalg.norm(zone.vertices - v, axis=1)) > 2 * RES
               and winding(v, zone.vertices, zone.faces)[0] < 0.5]
        far = rng.sample(far, 4)
        t = c.request(f"analyze reach probe hand=right mode=arm comfort=on "
                      f"targets={';'.join(xyz(p) for p in inside + far)}")
        assert "volume" not in t
        assert [v["comfortable"] for v in t["targets"]] == [True] * 4 + [False] * 4
        assert all(v["reached"] for v in t["targets"])
        assert all(v["comfort_shortfall"] > RES for v in t["targets"][4:])


@pytest.mark.parametrize("part", ["reach", "comfort"])
def test_the_files_are_closed_surfaces(daemon, part):
    """The envelope's and the comfort zone's STL, read by trimesh, are watertight and
    consistently wound."""
    with daemon.client(timeout=TIMEOUT) as c:
        c.request("load human as probe")
        c.request(f"analyze reach probe hand=left mode=arm resolution={RES} comfort=on")
        m = export(c, daemon, "probe.left.arm", f"{part}.stl", f"part={part}")
        assert m.is_watertight
        assert m.is_winding_consistent
