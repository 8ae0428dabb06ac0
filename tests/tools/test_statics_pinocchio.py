"""Joint moments (src/assess/statics.c, through posture-figure loads) against Pinocchio.

Each figure is exported to URDF by posture-figure and loaded by Pinocchio with a free-flyer
joint above its root. For a posture and a set of loads, our solve gives the support forces and,
for every dof, its generalised torque (the joint's moment projected on the dof's axis: what
RNEA returns for that URDF joint, the exporter splitting a 3-dof joint into a chain of three
revolute joints). Pinocchio's recursive Newton-Euler algorithm, with zero velocity and
acceleration, gravity (0, -9.80665, 0) and as external forces our supports' forces and free
moments plus the loads (each in its joint's local frame about the joint's origin, as
Pinocchio wants them), must give every dof's torque within 1e-6 N m, and zero on the free
flyer: that the supports close the whole body's equilibrium, checked by Pinocchio's own sums.

Cases, each 100 random postures within the joint limits with loads drawn afresh for each:
gravity only (the human, the female default, a chair, a vehicle seat with six dofs), forces and torques at the hands (also
on a short heavy manikin built from measures), a
weight on one hand, a box held in both hands, seated, and figures re-rooted at a foot and at
a hand (the URDF then exported with the tree running from there, the free flyer above it).
"""
import json
import os
import pathlib
import re
import subprocess

import numpy as np
import pinocchio as pin
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
FIGURES = ROOT / "src" / "figure" / "library"
G = 9.80665
POSTURES = 100
TOL = 1e-6  # N m, N
URDF_NEGLIGIBLE_MASS, URDF_NEGLIGIBLE_INERTIA = 1e-9, 1e-12  # src/export/urdf.h


def tool(*args):
    proc = subprocess.run([str(BUILD / "bin" / "posture-figure"), *map(str, args)],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, f"posture-figure {args}: {proc.stderr}"
    return proc.stdout


def read_dofs(fig):
    """posture-figure dofs -> [(urdf joint name, lower, upper)] in dof order"""
    dofs = []
    for line in tool(*fig, "dofs").splitlines():
        if line.startswith("#") or not line.strip():
            continue
        _, joint, k, _, lo, hi, _ = line.split()
        dofs.append((joint, int(k), float(lo), float(hi)))
    return dofs


class Reference:
    """Pinocchio's model of the figure's URDF (exported with the given root), free-flyer based"""

    def __init__(self, fig, root, tmp_path):
        urdf = tmp_path / "figure.urdf"
        urdf.write_text(tool(*fig, *(["--root", root] if root else []), "urdf"))
        self.model = pin.buildModelFromUrdf(str(urdf), pin.JointModelFreeFlyer())
        self.model.gravity.linear = np.array([0.0, -G, 0.0])
        self.data = self.model.createData()
        self.dofs = read_dofs(fig)
        assert self.model.nq == 7 + len(self.dofs)
        self.drop_negligible_masses()
        # the world link sits at the exported root's frame: Pinocchio's base moves with ours
        self.base0 = self.placement(pin.neutral(self.model), "world")

    def drop_negligible_masses(self):
        """The exporter gives each dof's link ("<joint>__<k>_link") and "world" 1e-9 kg
        (urdf.h: simulators refuse massless moving bodies); the figure has no such masses.
        Their ~1e-7 kg would weigh up to ~1e-6 N m on the joints: take each out of the
        Pinocchio body it was merged into (inertias add as spatial inertias in the joint's
        frame, so each subtracts exactly)."""
        negligible = pin.Inertia(URDF_NEGLIGIBLE_MASS, np.zeros(3),
                                 np.eye(3) * URDF_NEGLIGIBLE_INERTIA)
        dropped = 0
        for f in self.model.frames:
            if f.type == pin.FrameType.BODY and (f.name == "world" or
                                                 re.fullmatch(r".+__\d+_link", f.name)):
                self.model.inertias[f.parentJoint] -= f.placement.act(negligible)
                dropped += 1
        assert dropped == 1 + len(self.dofs)

    def frame(self, name):
        fid = self.model.getFrameId(name)
        assert fid < self.model.nframes, f"no frame {name} in the URDF"
        return fid

    def placement(self, q, frame):
        pin.forwardKinematics(self.model, self.data, q)
        pin.updateFramePlacements(self.model, self.data)
        return self.data.oMf[self.frame(frame)].copy()

    def configuration(self, qs, seg_now, seg_name):
        """Pinocchio's q for our dof values, its base placed so that segment seg_name's frame
        is seg_now (4x4, from our output) as ours is"""
        q = pin.neutral(self.model)
        for (joint, k, _, _), v in zip(self.dofs, qs):
            jid = self.model.getJointId(f"{joint}__{k}")
            assert jid < self.model.njoints
            q[self.model.joints[jid].idx_q] = v
        # base: world placement W with W * (segment relative to world) = seg_now
        rel = self.base0.inverse() * self.placement(q, seg_name)
        W = pin.SE3(seg_now[:3, :3], seg_now[:3, 3]) * rel.inverse()
        q[:7] = pin.SE3ToXYZQUAT(W)
        return q

    def torques(self, q, pushes):
        """RNEA's generalised forces for q at rest under gravity and pushes: (frame of the
        segment or site, world point, world force, world moment about the point)"""
        pin.forwardKinematics(self.model, self.data, q)
        pin.updateFramePlacements(self.model, self.data)
        fext = [pin.Force.Zero() for _ in range(self.model.njoints)]
        for frame, point, force, moment in pushes:
            jid = self.model.frames[self.frame(frame)].parentJoint
            oMi = self.data.oMi[jid]
            R, o = oMi.rotation, oMi.translation
            about_origin = np.asarray(moment) + np.cross(np.asarray(point) - o, force)
            fext[jid] += pin.Force(R.T @ np.asarray(force), R.T @ about_origin)
        zero = np.zeros(self.model.nv)
        return pin.rnea(self.model, self.data, q, zero, zero, fext)

    def dof_index(self, joint, k):
        return self.model.joints[self.model.getJointId(f"{joint}__{k}")].idx_v


def segment_frames(fig, extra, qfile):
    """posture-figure segments -> per posture {segment: 4x4}"""
    out, cur = [], None
    for line in tool(*fig, *extra, "--q-file", qfile, "segments").splitlines():
        if line.startswith("posture "):
            cur = {}
            out.append(cur)
            continue
        v = line.split()
        T = np.eye(4)
        T[:3, 3] = [float(x) for x in v[5:8]]
        T[:3, :3] = np.array([float(x) for x in v[8:17]]).reshape(3, 3)
        cur[v[0]] = T
    return out


def draw_loads(rng, kind):
    """command-line loads and the pushes they make: (option, site, force, moment)"""
    loads = []
    if kind == "hands":
        for site in ("hand_l.palm", "hand_r.palm"):
            f, t = rng.uniform(-150, 150, 3), rng.uniform(-10, 10, 3)
            loads.append(("--load", site, f, t))
    elif kind == "weight":
        kg = rng.uniform(1, 25)
        loads.append(("--weight", "hand_r.palm", np.array([0, -kg * G, 0]), np.zeros(3)))
    elif kind == "box":
        kg = rng.uniform(5, 20) / 2  # a box held in both hands, half its weight in each
        for site in ("hand_l.palm", "hand_r.palm"):
            loads.append(("--weight", site, np.array([0, -kg * G, 0]), np.zeros(3)))
    args = []
    for opt, site, f, t in loads:
        if opt == "--weight":
            args += [opt, f"{site},{float(-f[1] / G)!r}"]
        else:
            args += [opt, site + "," + ",".join(repr(float(x)) for x in (*f, *t))]
    return args, loads


CASES = {
    # name: (figure args, extra args, load kind, URDF root)
    "human-gravity": (["--human"], [], None, None),
    "female-gravity": (["--human", "--sex", "female"], [], None, None),
    "manikin-hand-forces": (["--human", "--sex", "female", "--measure", "stature=1550",
                             "--measure", "weightkg=85"], [], "hands", None),
    "chair-gravity": (["--figure", FIGURES / "chair.fig"], [], None, None),
    "vehicle-seat-gravity": (["--figure", FIGURES / "vehicle_seat.fig"], [], None, None),
    "human-hand-forces": (["--human"], [], "hands", None),
    "human-hand-weight": (["--human"], [], "weight", None),
    "human-held-box": (["--human"], [], "box", None),
    "human-seated-hands": (["--human"], ["--seated"], "hands", None),
    "rerooted-foot-hands": (["--human"], ["--root", "foot_l.balance"], "hands", "foot_l.balance"),
    "rerooted-hand-box": (["--human"], ["--root", "hand_r.palm"], "box", "hand_r.palm"),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_joint_torques_match_pinocchio_rnea(case, tmp_path):
    fig, extra, kind, root = CASES[case]
    ref = Reference(fig, root, tmp_path)
    rng = np.random.default_rng(sorted(CASES).index(case))
    lo = np.array([d[2] for d in ref.dofs])
    hi = np.array([d[3] for d in ref.dofs])
    n = POSTURES if ref.dofs else 1
    qs = lo + (hi - lo) * rng.random((n, len(ref.dofs)))
    qfile = tmp_path / "q.txt"
    qfile.write_text("\n".join(" ".join(repr(float(v)) for v in q) for q in qs) + "\n")
    posture = ["--q-file", qfile] if ref.dofs else []
    frames = segment_frames(fig, extra, qfile) if ref.dofs else [None]
    worst = worst_base = 0.0
    seg0 = None
    for i, q in enumerate(qs):
        args, loads = draw_loads(rng, kind)
        # one posture a run, so that each gets loads of its own
        (tmp_path / "one.txt").write_text(" ".join(repr(float(v)) for v in q) + "\n")
        out = json.loads(tool(*fig, *extra, *args,
                              *(["--q-file", tmp_path / "one.txt"] if ref.dofs else []),
                              "loads"))
        pushes = []
        for u in out["supports"]:
            pushes.append((u["segment"], u["point"], u["force"], u["moment"]))
        qp = None
        if frames[i] is not None:
            seg0 = seg0 or next(iter(frames[i]))
            qp = ref.configuration(q, frames[i][seg0], seg0)
        else:
            qp = pin.neutral(ref.model)
        for opt, site, f, t in loads:
            seg, name = site.split(".", 1)
            point = ref.placement(qp, f"{seg}__{name}").translation
            pushes.append((seg, point, f, t))
        tau = ref.torques(qp, pushes)
        worst_base = max(worst_base, np.abs(tau[:6]).max())
        for joint, j in out["joints"].items():
            for k, ours in enumerate(j["dofs"]):
                worst = max(worst, abs(tau[ref.dof_index(joint, k)] - ours))
    assert worst < TOL, f"a dof's torque differs from Pinocchio's RNEA by {worst:.3g}"
    assert worst_base < TOL, f"the supports leave {worst_base:.3g} on the free flyer"


@pytest.mark.parametrize("args,says", [
    (["--load", "hand_r.palm,1,2"], "and then a force FX,FY,FZ (N) and optionally a torque"),
    (["--load", "hand_r.palm,1,2,3,4"], "and then a force FX,FY,FZ (N) and optionally a torque"),
    (["--load", "hand_r.nowhere,1,2,3"], "no such site"),
    (["--load", "hand_r.palm,1,x,3"], "and then a force"),
    (["--weight", "hand_r.palm,-2"], "above 0 kg"),
    (["--weight", "hand_r.palm,2,3"], "SEGMENT.SITE and then the mass (kg)"),
    (["--weight", "hand_r.palm"], "no such site"),
    (["--seated", "--figure", FIGURES / "chair.fig"], "ischial"),
])
def test_loads_refuses_bad_options_saying_why(args, says):
    """a bad load is an error that says what is wrong, and nothing is printed"""
    proc = subprocess.run([str(BUILD / "bin" / "posture-figure"), *map(str, args), "loads"],
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode != 0
    assert says in proc.stderr, proc.stderr
    assert proc.stdout == ""
