#!/usr/bin/env python3
"""Rendering: ours beside MuJoCo's, frames per second of render + readback.

Ours: the standard human seated in the vehicle seat with every icon on (frame, translation
arrow, elbow wheel with limits, rotation fans, IK goal icons, balance icons, status and
message lines, pointer), shadows, floor grid, no multisampling (build/rel/bin/render-scene
--bench); also with 4x multisampling for reference. MuJoCo (PyPI mujoco, its OSMesa
backend) on its humanoid, as shipped (4x MSAA, shadows, reflection, skybox) and lite (all
four off), at the same sizes in the same run (peers/render_mujoco.py; kept out of tools/bench/*.py,
which make bench runs one by one). Both run on Mesa's
llvmpipe with the same LP_NUM_THREADS (default: llvmpipe's own, the number of cores).
Median over FRAMES frames after 20 of warm-up.
"""
import os
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
FRAMES = 200
SIZES = [(640, 480), (1280, 720)]


def run(args, env=None):
    proc = subprocess.run([str(a) for a in args], capture_output=True, text=True, check=False,
                          cwd=ROOT, env=env)
    if proc.returncode != 0:
        sys.exit(f"{args[0]} failed ({proc.returncode}):\n{proc.stderr}")
    return proc.stdout


def fps(out, name):
    m = re.search(r"BENCH %s fps=([0-9.]+)" % re.escape(name), out)
    return float(m.group(1)) if m else float("nan")


def main():
    env = dict(os.environ, MUJOCO_GL="osmesa", PYOPENGL_PLATFORM="osmesa")
    threads = env.get("LP_NUM_THREADS", f"default ({os.cpu_count()} cores)")
    print(f"render_bench: llvmpipe threads {threads}, {FRAMES} frames, median")
    tool = BUILD / "bin" / "render-scene"
    peer = ROOT / "tools" / "bench" / "peers" / "render_mujoco.py"
    results = {}
    for w, h in SIZES:
        size = f"{w}x{h}"
        ours = run([tool, "--scene", "seated", "--icons", "--size", size, "--samples", "0",
                    "--bench", FRAMES], env)
        msaa = run([tool, "--scene", "seated", "--icons", "--size", size, "--samples", "4",
                    "--bench", FRAMES], env)
        full = run([sys.executable, peer, w, h, FRAMES, "full"], env)
        lite = run([sys.executable, peer, w, h, FRAMES, "lite"], env)
        print(ours.splitlines()[0])
        print(msaa.splitlines()[0])
        r = {"posture": fps(ours, f"render.{size}.posture"),
             "posture_msaa4": fps(msaa, f"render.{size}.posture"),
             "mujoco": fps(full, f"render.{size}.mujoco"),
             "mujoco_lite": fps(lite, f"render.{size}.mujoco_lite")}
        results[size] = r
        for k, v in r.items():
            print(f"BENCH render.{size}.{k} fps={v:.1f}")
    for size, r in results.items():
        print(f"render_bench {size}: ours {r['posture']:.1f} fps = "
              f"{r['posture'] / r['mujoco']:.2f}x MuJoCo as shipped ({r['mujoco']:.1f}), "
              f"{r['posture'] / r['mujoco_lite']:.2f}x MuJoCo lite ({r['mujoco_lite']:.1f}); "
              f"ours with 4x MSAA {r['posture_msaa4']:.1f} fps")


if __name__ == "__main__":
    main()
