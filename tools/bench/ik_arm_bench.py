#!/usr/bin/env python3
"""Arm inverse kinematics: ours beside NLopt, Pinocchio's CLIK and IKPy, in one run.

The right arm of the standard human (clavicle_r, shoulder_r, elbow_r, wrist_r: 9 dofs) reaches
for 1000 random reachable 6-D targets, the frame of site hand_r.palm in postures drawn within
the limits, each from the neutral posture. build/rel/bench/ik_arm draws the targets (srand(1)),
writes them to a file and measures ours and NLopt's LD_LBFGS and LD_SLSQP on our objective;
build/rel/bench/ik_arm_pinocchio solves the same targets with Pinocchio's closed-loop IK on the
URDF that posture-figure exports; IKPy solves the first 200 (it is slow) from that URDF here.
Before the peers run, Pinocchio's forward kinematics of every target posture must reproduce
the target frame (to 1e-9), so every solver faces the same problems.

Success everywhere: the palm within 1 mm and 1 degree of the target, recomputed from the
solver's answer, with every arm dof within its limits. Prints every "BENCH ik.arm6d.* ..." line.
"""
import os
import pathlib
import subprocess
import sys
import tempfile
import time
import warnings
import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
TARGETS = 1000
IKPY_TARGETS = 200
ARM = [f"{j}__{k}" for j, n in (("clavicle_r", 2), ("shoulder_r", 3), ("elbow_r", 1),
                                ("wrist_r", 3)) for k in range(n)]
PALM = "hand_r__palm"
SUCCESS_POS, SUCCESS_ORI = 1e-3, np.radians(1.0)


def run(*args):
    proc = subprocess.run([str(a) for a in args], capture_output=True, text=True, check=False)
    if proc.returncode != 0:
        sys.exit(f"{args[0]} failed ({proc.returncode}):\n{proc.stdout}{proc.stderr}")
    return proc.stdout


def angle(a, b):
    """rotation angle between two rotation matrices, radians"""
    return np.arccos(np.clip((np.trace(a.T @ b) - 1) / 2, -1, 1))


def check_targets(model, q_arm, frames):
    """Pinocchio's forward kinematics of each target posture against the target frame"""
    data = model.createData()
    idx = [model.joints[model.getJointId(n)].idx_q for n in ARM]
    fid = model.getFrameId(PALM)
    worst_p = worst_r = 0.0
    for qa, T in zip(q_arm, frames):
        q = pin.neutral(model)
        q[idx] = qa
        pin.framesForwardKinematics(model, data, q)
        M = data.oMf[fid]
        worst_p = max(worst_p, np.linalg.norm(M.translation - T[:3, 3]))
        worst_r = max(worst_r, np.abs(M.rotation - T[:3, :3]).max())
    if worst_p > 1e-9 or worst_r > 1e-9:
        sys.exit(f"ik_arm_bench: Pinocchio's FK of the target postures misses the targets by "
                 f"{worst_p:.3g} m, {worst_r:.3g} in rotation: the URDF is not our figure")
    return worst_p, worst_r


def urdf_path_to(urdf, link):
    """the URDF elements from the root link down to link: [link, joint, link, ..., link]"""
    parent_of = {}
    for j in ET.parse(urdf).getroot().findall("joint"):
        parent_of[j.find("child").attrib["link"]] = (j.attrib["name"],
                                                    j.find("parent").attrib["link"])
    path = [link]
    while path[-1] in parent_of:
        path += parent_of[path[-1]]
    return path[::-1]


def bench_ikpy(urdf, model, frames):
    """IKPy's inverse_kinematics (scipy least_squares, position + full orientation) from zeros"""
    from ikpy.chain import Chain

    warnings.simplefilter("ignore")  # IKPy warns about every fixed link of the URDF
    path = urdf_path_to(urdf, PALM)
    names = [link.name for link in Chain.from_urdf_file(urdf, base_elements=path).links]
    mask = [n in ARM for n in names]
    if sum(mask) != len(ARM):
        sys.exit(f"ik_arm_bench: IKPy's chain has {sum(mask)} of the {len(ARM)} arm joints")
    chain = Chain.from_urdf_file(urdf, base_elements=path, active_links_mask=mask)
    cols = [names.index(n) for n in ARM]
    lo = np.array([chain.links[c].bounds[0] for c in cols])
    hi = np.array([chain.links[c].bounds[1] for c in cols])

    # count the forward kinematics IKPy's residual evaluates (finite differences included)
    fk, evals = chain.forward_kinematics, [0]

    def counted(*a, **k):
        evals[0] += 1
        return fk(*a, **k)

    chain.forward_kinematics = counted
    data = model.createData()
    idx = [model.joints[model.getJointId(n)].idx_q for n in ARM]
    fid = model.getFrameId(PALM)
    us, success, reached, violations, n_evals = [], 0, 0, 0, 0
    for T in frames:
        evals[0] = 0
        t0 = time.perf_counter()
        q_full = chain.inverse_kinematics(target_position=T[:3, 3], target_orientation=T[:3, :3],
                                          orientation_mode="all",
                                          initial_position=np.zeros(len(chain.links)))
        us.append((time.perf_counter() - t0) * 1e6)
        n_evals += evals[0]
        # the success test, with Pinocchio's forward kinematics of IKPy's answer
        qa = np.asarray(q_full)[cols]
        q = pin.neutral(model)
        q[idx] = qa
        pin.framesForwardKinematics(model, data, q)
        M = data.oMf[fid]
        ok = (np.linalg.norm(M.translation - T[:3, 3]) < SUCCESS_POS and
              angle(M.rotation, T[:3, :3]) < SUCCESS_ORI)
        inside = bool(np.all(qa >= lo) and np.all(qa <= hi))
        reached += ok
        success += ok and inside
        violations += ok and not inside
    n = len(frames)
    us = np.sort(us)
    median = np.median(us)
    p95 = us[int(np.ceil(0.95 * n)) - 1]
    return (f"BENCH ik.arm6d.ikpy n={n} success={100 * success / n:.1f} median_us={median:.1f} "
            f"p95_us={p95:.1f} evals={n_evals / n:.1f} restarts=0 limit_violations={violations} "
            f"reached={100 * reached / n:.1f}\n"
            f"ik_arm_bench: IKPy {version('ikpy')} on the first {n} targets only (about 50-100 ms "
            f"a solve): {len(chain.links)} links from world to {PALM}, the 9 arm joints active, "
            f"default least_squares tolerances, from zeros (IKPy nudges the start 1e-3 inside "
            f"the bounds), no restarts; evals counts its forward kinematics\n")


def version(dist):
    from importlib.metadata import version as v
    return v(dist)


def main():
    tool = BUILD / "bin" / "posture-figure"
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        urdf, targets, model_bin = tmp / "human.urdf", tmp / "targets.txt", tmp / "human.bin"
        urdf.write_text(run(tool, "--human", "urdf"))
        model = pin.buildModelFromUrdf(str(urdf))
        model.saveToBinary(str(model_bin))

        ours = run(BUILD / "bench" / "ik_arm", targets, TARGETS)
        print(ours, end="", flush=True)
        table = np.loadtxt(targets, comments="#", ndmin=2)
        if table.shape != (TARGETS, 34):
            sys.exit(f"ik_arm_bench: {targets} has shape {table.shape}")
        q_arm, frames = table[:, :9], table[:, 18:].reshape(-1, 4, 4)
        dp, dr = check_targets(model, q_arm, frames)
        print(f"ik_arm_bench: Pinocchio {pin.__version__}'s forward kinematics reproduces the "
              f"{TARGETS} targets to {dp:.1g} m, {dr:.1g} in rotation", flush=True)

        print(run(BUILD / "bench" / "ik_arm_pinocchio", model_bin, targets), end="", flush=True)
        print(bench_ikpy(str(urdf), model, frames[:IKPY_TARGETS]), end="", flush=True)


if __name__ == "__main__":
    main()
