"""Forward kinematics and centre of mass against an independent reference: Pinocchio.

Each figure is exported to URDF by posture-figure, loaded by Pinocchio, and 100 random
postures within the joint limits are evaluated by both. Every site's global frame must
agree to 1e-9 (metres, and rotation-matrix entries), and so must the centre of mass.
The same is done after re-rooting, which exports the tree with inverted joints.
"""
import numpy as np
import pinocchio as pin
import pytest

from conftest import FIGURE_ARGS, ROOT, random_postures, read_dofs, read_sites, run_tool

POSTURES = 100
TOL = 1e-9

# re-rooted exports: the URDF tree then runs through joints against their direction
REROOTS = {
    "human-male": ["foot_l.balance", "hand_r.palm", "pelvis.lower_torso"],
}


def pin_configuration(model, dofs, q):
    """maps our dof vector to Pinocchio's q by joint name (order may differ)"""
    qp = pin.neutral(model)
    for (name, _, _), v in zip(dofs, q):
        jid = model.getJointId(name)
        assert jid < model.njoints, f"URDF joint {name} missing in Pinocchio's model"
        qp[model.joints[jid].idx_q] = v
    return qp


def whole_com(model, data, q):
    """Pinocchio's centerOfMass leaves out the universe body, into which the URDF parser
    merges the root segment (fixed to "world"); add it back."""
    c = pin.centerOfMass(model, data, q)
    m1 = sum(model.inertias[i].mass for i in range(1, model.njoints))
    m0 = model.inertias[0].mass
    if m1 == 0:
        return model.inertias[0].lever.copy()
    return (m1 * c + m0 * model.inertias[0].lever) / (m1 + m0)


def check_against_pinocchio(args, root, tmp_path, seed):
    extra = ["--root", root] if root else []
    dofs = read_dofs(args)
    urdf = tmp_path / "figure.urdf"
    urdf.write_text(run_tool(*args, *extra, "urdf"))
    model = pin.buildModelFromUrdf(str(urdf))
    data = model.createData()
    assert model.nq == len(dofs)

    # a rigid figure (no dofs) has one posture to compare
    n = POSTURES if dofs else 1
    qs = random_postures(dofs, n, seed)
    qfile = tmp_path / "q.txt"
    qfile.write_text("\n".join(" ".join(repr(float(v)) for v in q) for q in qs) + "\n")
    posture = ["--q-file", qfile] if dofs else []
    ours = read_sites(run_tool(*args, *extra, *posture, "sites"))
    coms = [np.array([float(v) for v in line.split()[2:5]])
            for line in run_tool(*args, *extra, *posture, "com").splitlines()]
    assert len(ours) == n and len(coms) == n

    frame_ids = {}
    for site in ours[0]:
        seg, name = site.split(".", 1)
        fid = model.getFrameId(f"{seg}__{name}", pin.FrameType.BODY)
        assert fid < model.nframes, f"site {site} not exported"
        frame_ids[site] = fid

    worst_p = worst_r = worst_c = 0.0
    for q, sites, com in zip(qs, ours, coms):
        qp = pin_configuration(model, dofs, q)
        pin.forwardKinematics(model, data, qp)
        pin.updateFramePlacements(model, data)
        for site, (p, r) in sites.items():
            placement = data.oMf[frame_ids[site]]
            worst_p = max(worst_p, np.abs(placement.translation - p).max())
            worst_r = max(worst_r, np.abs(placement.rotation - r).max())
        c = whole_com(model, data, qp)
        worst_c = max(worst_c, np.abs(c - com).max())
    assert worst_p < TOL, f"site position differs from Pinocchio by {worst_p:.3g} m"
    assert worst_r < TOL, f"site rotation differs from Pinocchio by {worst_r:.3g}"
    assert worst_c < TOL, f"centre of mass differs from Pinocchio by {worst_c:.3g} m"


def manikins():
    """Figures built from ANSUR II subjects' 20 measures: the shortest woman, the tallest man,
    the lightest and the heaviest of all, and one more of each sex at random (seeded)."""
    import csv
    import random
    names = ("stature acromialheight wristheight trochanterionheight kneeheightmidpatella "
             "lateralmalleolusheight sittingheight eyeheightsitting acromionradialelength "
             "radialestylionlength handlength footlength buttockkneelength kneeheightsitting "
             "poplitealheight biacromialbreadth hipbreadth span thumbtipreach weightkg").split()
    people = []
    for sex in ("male", "female"):
        path = ROOT / "data" / "ansur2" / f"ANSUR_II_{sex.upper()}_Public.csv"
        with open(path, encoding="latin-1", newline="") as f:
            for r in csv.DictReader(f):
                m = {k: float(r[k]) for k in names}
                m["weightkg"] /= 10
                people.append((sex, m))
    women = [p for p in people if p[0] == "female"]
    men = [p for p in people if p[0] == "male"]
    rnd = random.Random(24)
    chosen = {
        "shortest-woman": min(women, key=lambda p: p[1]["stature"]),
        "tallest-man": max(men, key=lambda p: p[1]["stature"]),
        "lightest": min(people, key=lambda p: p[1]["weightkg"]),
        "heaviest": max(people, key=lambda p: p[1]["weightkg"]),
        "a-woman": rnd.choice(women),
        "a-man": rnd.choice(men),
    }
    out = {}
    for name, (sex, m) in chosen.items():
        args = ["--human", "--sex", sex]
        for k, v in m.items():
            args += ["--measure", f"{k}={v!r}"]
        out[name] = (args, m["weightkg"])
    return out


MANIKINS = manikins()


@pytest.mark.parametrize("manikin", sorted(MANIKINS))
def test_manikins_from_measures_match_pinocchio(manikin, tmp_path):
    """A figure built from a subject's measures: its sites and centre of mass over 100
    postures as Pinocchio computes them on its URDF, and its mass (Pinocchio's sum of the
    links' masses) the subject's weight."""
    args, weight = MANIKINS[manikin]
    check_against_pinocchio(args, None, tmp_path, seed=sorted(MANIKINS).index(manikin))
    model = pin.buildModelFromUrdf(str(tmp_path / "figure.urdf"))
    # the export gives each dof's intermediate link a negligible 1e-9 kg (about 1e-7 in all)
    mass = sum(model.inertias[i].mass for i in range(model.njoints))
    assert abs(mass - weight) < 1e-6, (mass, weight)


@pytest.mark.parametrize("figure", sorted(FIGURE_ARGS))
def test_sites_and_com_match_pinocchio(figure, tmp_path):
    check_against_pinocchio(FIGURE_ARGS[figure], None, tmp_path, seed=sorted(FIGURE_ARGS).index(figure))


@pytest.mark.parametrize("figure,root", [(f, r) for f, rs in REROOTS.items() for r in rs])
def test_rerooted_export_matches_pinocchio(figure, root, tmp_path):
    check_against_pinocchio(FIGURE_ARGS[figure], root, tmp_path, seed=7)
