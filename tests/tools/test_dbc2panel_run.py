"""tools/dbc2panel runs as the README shows it, `tools/dbc2panel FILE.dbc`, with the system's
python3 first on PATH (not the virtualenv's): the script finds cantools in the tree's .venv
(made by `make deps`) by itself, and says what to do when there is none."""
import os
import shutil
import subprocess

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DBC2PANEL = os.path.join(ROOT, "tools", "dbc2panel")
CAN_DIR = os.path.join(ROOT, "tests", "input", "can")


def system_path():
    """PATH as a shell outside any virtualenv has it: without this tree's .venv/bin or
    $VIRTUAL_ENV/bin"""
    venvs = {os.path.realpath(os.path.join(ROOT, ".venv", "bin"))}
    if os.environ.get("VIRTUAL_ENV"):
        venvs.add(os.path.realpath(os.path.join(os.environ["VIRTUAL_ENV"], "bin")))
    dirs = [d for d in os.environ.get("PATH", "/usr/bin:/bin").split(os.pathsep)
            if d and os.path.realpath(d) not in venvs]
    return os.pathsep.join(dirs)


def system_env():
    env = {k: v for k, v in os.environ.items() if k not in ("VIRTUAL_ENV", "PYTHONPATH",
                                                           "PYTHONHOME")}
    env["PATH"] = system_path()
    return env


def has_cantools(python):
    return subprocess.run([python, "-c", "import cantools"], capture_output=True).returncode == 0


def test_runs_as_the_readme_shows_from_any_folder(tmp_path):
    python3 = shutil.which("python3", path=system_path())
    assert python3, "no python3 on PATH"
    r = subprocess.run([DBC2PANEL, os.path.join(CAN_DIR, "mux.dbc")], capture_output=True,
                       text=True, env=system_env(), cwd=tmp_path, timeout=120)
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""
    with open(os.path.join(CAN_DIR, "mux.map")) as f:
        assert r.stdout == f.read()


def test_without_cantools_it_says_how_to_get_it(tmp_path):
    """a copy of the script in a tree with no .venv, run by a python3 without cantools"""
    python3 = shutil.which("python3", path=system_path())
    if has_cantools(python3):
        pytest.skip(f"{python3} has cantools: nothing to find")
    (tmp_path / "tools").mkdir()
    script = tmp_path / "tools" / "dbc2panel"
    shutil.copy(DBC2PANEL, script)
    r = subprocess.run([str(script), os.path.join(CAN_DIR, "mux.dbc")], capture_output=True,
                       text=True, env=system_env(), timeout=120)
    assert r.returncode == 1
    assert r.stdout == ""
    assert r.stderr == ("dbc2panel: cantools is not installed: `make deps` in the source tree "
                        "puts it in .venv, or `pip install cantools`\n")
