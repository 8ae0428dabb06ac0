"""Shared helpers for the system tests: where the built tools are, how to run them."""
import os
import pathlib
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
FIGURES = ROOT / "src" / "figure" / "library"


def run_tool(*args, stdin=None):
    """Runs posture-figure and returns its stdout; fails the test on a non-zero exit."""
    exe = BUILD / "bin" / "posture-figure"
    proc = subprocess.run([str(exe), *map(str, args)], input=stdin, capture_output=True,
                          text=True, timeout=120)
    if proc.returncode != 0:
        pytest.fail(f"posture-figure {' '.join(map(str, args))} exited {proc.returncode}:\n"
                    f"{proc.stderr}")
    return proc.stdout


@pytest.fixture
def tool():
    return run_tool


# the figures the export and kinematics tests take through the peers
FIGURE_ARGS = {
    "human-male": ["--human"],
    "human-female": ["--human", "--sex", "female"],
    "table": ["--figure", FIGURES / "table.fig"],
    "chair": ["--figure", FIGURES / "chair.fig"],
    "vehicle-seat": ["--figure", FIGURES / "vehicle_seat.fig"],
}


def read_dofs(args):
    """posture-figure dofs -> [(urdf joint name, lower, upper)] in dof order"""
    dofs = []
    for line in run_tool(*args, "dofs").splitlines():
        if line.startswith("#") or not line.strip():
            continue
        idx, joint, k, kind, lo, hi, init = line.split()
        dofs.append((f"{joint}__{k}", float(lo), float(hi)))
    return dofs


def read_sites(text):
    """posture-figure sites -> list (per posture) of {site: (p, R)}"""
    postures, cur = [], None
    for line in text.splitlines():
        if line.startswith("posture "):
            cur = {}
            postures.append(cur)
            continue
        f = line.split()
        vals = np.array([float(v) for v in f[1:]])
        cur[f[0]] = (vals[:3], vals[3:].reshape(3, 3))
    return postures


def random_postures(dofs, n, seed):
    """n postures drawn uniformly within the limits"""
    rng = np.random.default_rng(seed)
    lo = np.array([d[1] for d in dofs])
    hi = np.array([d[2] for d in dofs])
    return lo + (hi - lo) * rng.random((n, len(dofs)))


def read_segments(text):
    """posture-figure segments -> list (per posture) of {segment: 4x4 frame}"""
    postures = []
    for line in text.splitlines():
        if line.startswith("posture "):
            postures.append({})
            continue
        f = line.split()
        v = np.array([float(x) for x in f[5:]])
        frame = np.eye(4)
        frame[:3, 3] = v[:3]
        frame[:3, :3] = v[3:].reshape(3, 3)
        postures[-1][f[0]] = frame
    return postures


def quat_matrix(q):
    """the rotation matrix of a quaternion (x, y, z, w), normalised first"""
    q = np.asarray(q, dtype=float)
    x, y, z, w = q / np.linalg.norm(q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
