"""The Debian package as the tests take it (tests/tools/test_deb.py, the guest's
tests/guest/test_guest_package.py): POSTURE_DEB=path/to/posture_*.deb, a package built
before, or one built now by make deb from a copy of the tree, as CI builds it."""
import os
import shutil
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

# what the package must hold: the daemon and the tools, the man page, the unit, the udev
# rules, the system user, the CAN modules, the configuration, the figures, the client
FILES = [
    "usr/bin/postured", "usr/bin/posturectl", "usr/bin/posture-figure", "usr/bin/posture-input",
    "usr/bin/posture-replay", "usr/share/man/man8/postured.8.gz",
    "usr/share/man/man1/posturectl.1.gz", "usr/share/man/man1/posture-replay.1.gz",
    "usr/share/man/man1/posture-figure.1.gz", "usr/share/man/man1/posture-input.1.gz",
    "lib/systemd/system/postured.service", "lib/udev/rules.d/60-posture.rules",
    "usr/lib/sysusers.d/posture.conf", "usr/lib/modules-load.d/posture.conf",
    "etc/posture/postured.conf", "usr/share/posture/kiosk.init",
    "usr/share/posture/library/chair.fig", "usr/share/posture/library/table.fig",
    "usr/share/posture/library/vehicle_seat.fig", "usr/share/posture/library/box.fig",
    "usr/lib/python3/dist-packages/posture/__init__.py",
    "usr/lib/python3/dist-packages/posture/client.py",
    "usr/share/doc/posture/copyright",
]


def deb_tools_missing():
    """What make deb needs and this machine lacks, in words; '' when nothing."""
    need = [t for t in ("dpkg-buildpackage", "dh") if not shutil.which(t)]
    return " and ".join(need) + " missing (make deps installs them)" if need else ""


_built = []  # the package this test run built: one build serves every test that wants it


def the_deb(workdir):
    """POSTURE_DEB when it is set, else the posture_*.deb that make deb builds from a copy
    of the tree in workdir (dpkg-buildpackage writes into debian/ and beside the tree),
    once a test run."""
    given = os.environ.get("POSTURE_DEB")
    if given:
        return Path(given).resolve()
    if _built and _built[0].exists():
        return _built[0]
    src = Path(workdir) / "posture"
    shutil.copytree(ROOT, src, symlinks=True, ignore=shutil.ignore_patterns(
        ".git", "build", "build-*", ".venv", "__pycache__", ".pytest_cache"))
    r = subprocess.run(["make", "deb", "DEB_JOBS=%d" % min(os.cpu_count() or 1, 2)],
                       cwd=src, capture_output=True, text=True, timeout=900)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    debs = sorted((src / "build" / "deb").glob("posture_*.deb"))
    assert len(debs) == 1, list((src / "build" / "deb").iterdir())
    _built[:] = [debs[0]]
    return debs[0]
