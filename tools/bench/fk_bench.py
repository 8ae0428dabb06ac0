#!/usr/bin/env python3
"""Forward kinematics + centre of mass of the standard human: ours beside Pinocchio.

Both evaluate the same 1000 random postures within the joint limits of the same figure:
ours from the built-in model (build/rel/bench/fk_human), Pinocchio's C++ library from the
URDF that posture-figure exports (build/rel/bench/fk_pinocchio). Prints each tool's
"BENCH ..." lines and the ratio.
"""
import os
import pathlib
import re
import subprocess
import sys
import tempfile

import numpy as np
import pinocchio as pin

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
POSTURES = 1000


def run(*args):
    proc = subprocess.run([str(a) for a in args], capture_output=True, text=True, check=False)
    if proc.returncode != 0:
        sys.exit(f"{args[0]} failed ({proc.returncode}):\n{proc.stderr}")
    return proc.stdout


def main():
    tool = BUILD / "bin" / "posture-figure"
    dofs = [line.split() for line in run(tool, "--human", "dofs").splitlines()
            if line and not line.startswith("#")]
    names = [f"{d[1]}__{d[2]}" for d in dofs]
    lo = np.array([float(d[4]) for d in dofs])
    hi = np.array([float(d[5]) for d in dofs])
    qs = lo + (hi - lo) * np.random.default_rng(1).random((POSTURES, len(dofs)))

    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        (tmp / "human.urdf").write_text(run(tool, "--human", "urdf"))
        model = pin.buildModelFromUrdf(str(tmp / "human.urdf"))
        model.saveToBinary(str(tmp / "human.bin"))
        idx = [model.joints[model.getJointId(n)].idx_q for n in names]
        pin_qs = np.tile(pin.neutral(model), (POSTURES, 1))
        pin_qs[:, idx] = qs
        np.savetxt(tmp / "ours.q", qs, fmt="%.17g")
        np.savetxt(tmp / "pin.q", pin_qs, fmt="%.17g")
        ours = run(BUILD / "bench" / "fk_human", tmp / "ours.q")
        peer = run(BUILD / "bench" / "fk_pinocchio", tmp / "human.bin", tmp / "pin.q")
    print(ours, end="")
    print(peer, end="")
    us = {m.group(1): float(m.group(2))
          for m in re.finditer(r"BENCH (\S+) us=([0-9.]+)", ours + peer)}
    print(f"fk_bench: ours {us['fk.human.posture']:.3f} us (all segment and site frames, "
          f"dof axes, sub-tree centres of mass); Pinocchio {us['fk.human.pinocchio']:.3f} us "
          f"(joints + centre of mass), {us['fk.human.pinocchio_frames']:.3f} us "
          f"(+ every frame)")


if __name__ == "__main__":
    main()
