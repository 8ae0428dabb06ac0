"""What every test of the kernel tier shares: the skip rules and running one of the
guest programs make builds (tests/guest/guest_*.c -> $POSTURE_BUILD/guest/)."""
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parents[1]
BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
sys.path.insert(0, str(HERE))
import guest  # noqa: E402


def require_tier():
    """Skips the calling test, saying why, when the guest cannot boot here (fetching the
    kernel first when QEMU and apt are there)."""
    if os.environ.get("POSTURE_GUEST") == "skip":
        pytest.skip("kernel tier: POSTURE_GUEST=skip")
    ok, why = guest.check()
    # fetch the kernel (70 MB) only when QEMU is there to boot it
    if not ok and shutil.which(guest.QEMU) and guest.fetchable():
        try:
            guest.fetch()
        except guest.GuestError as e:
            pytest.skip("kernel tier: %s" % e)
        ok, why = guest.check()
    if not ok:
        pytest.skip("kernel tier: %s" % why)


def program(name):
    """$POSTURE_BUILD/guest/NAME: where make builds the guest program NAME."""
    return BUILD / "guest" / name


def require_built(name):
    """Skips the calling test when make has not built the guest program NAME."""
    if not program(name).exists():
        pytest.skip("kernel tier: %s is not built (make all)" % program(name))


def run_program(name, modules, args=(), files=(), exes=(), timeout=240, memory=512, env=()):
    """Runs the guest program NAME ($POSTURE_BUILD/guest/NAME; a pathlib.Path is run as
    it is) in the guest; returns (exit status, output lines). files are SRC[:DEST] and
    exes host programs, as guest.py run takes them; memory is the guest's, in MiB (the
    daemon's OSMesa and LLVM need 2048); env holds K=V words for the program. A harness
    failure (exit 125) fails the test with the guest's output."""
    exe = name if isinstance(name, pathlib.Path) else program(name)
    assert exe.exists(), "%s is not built (make all builds it)" % exe
    cmd = [sys.executable, str(HERE / "guest.py"), "run", "--modules", ",".join(modules),
           "--timeout", str(timeout), "--memory", str(memory)]
    for f in files:
        cmd += ["--file", str(f)]
    for x in exes:
        cmd += ["--exe", str(x)]
    for kv in env:
        cmd += ["--env", kv]
    cmd += [str(exe), *map(str, args)]
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       timeout=timeout + 60)
    print(p.stdout)
    assert p.returncode != 125, "the guest did not run:\n" + p.stdout
    return p.returncode, p.stdout.splitlines()


def assert_checks(status, lines, expected):
    """The guest program's one-line checks: no FAIL, every expected 'ok' there."""
    failed = [ln for ln in lines if ln.startswith("FAIL ")]
    assert not failed, "\n".join(failed)
    passed = [ln for ln in lines if ln.startswith("ok ")]
    for what in expected:
        assert any(what in ln for ln in passed), "no 'ok %s' line" % what
    assert status == 0
