"""Shared helpers for the system tests: where the built tools are, how to run them."""
import os
import pathlib
import subprocess

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
