"""The package on a clean Debian 12: make deb's package, installed with
`apt-get install ./posture_*.deb` into a debootstrap'ed minbase bookworm (Debian resolves
its Depends from the archive), has its files in place and its user; that root booted in
QEMU (Debian's kernel, systemd as init, -vga std) starts the enabled postured.service,
which puts the human on the screen through KMS with tty1 in graphics mode, runs on
without a restart, and gives the console back when stopped. The check in the guest is
guest_package.c, run by a unit of the test's (pkgroot.py), not of the package.

POSTURE_DEB=path/to/posture_*.deb tests a package built before instead of building one.
"""
import io
import os
import shutil
import sys
import time

import pytest

from tier import ROOT, assert_checks, program, require_built, require_tier

sys.path.insert(0, str(ROOT / "tests" / "tools"))
import debpkg  # noqa: E402  (after sys.path)
import guest  # noqa: E402
import pkgroot  # noqa: E402


class Tee(io.StringIO):
    """The guest's console, kept for the checks and shown as it comes."""

    def write(self, s):
        sys.stdout.write(s)
        return super().write(s)


def journal(lines):
    """The daemon's journal the guest printed between its markers."""
    if pkgroot.JOURNAL_BEGIN not in lines:
        return "(no journal: the check never ran)"
    i = lines.index(pkgroot.JOURNAL_BEGIN)
    j = lines.index(pkgroot.JOURNAL_END) if pkgroot.JOURNAL_END in lines else len(lines)
    return "\n".join(lines[i + 1:j])


def test_the_package_on_a_clean_debian_shows_the_human(tmp_path):
    require_tier()
    why = pkgroot.missing()
    if why:
        pytest.skip("package tier: " + why)
    require_built("guest_package")
    if not os.environ.get("POSTURE_DEB") and debpkg.deb_tools_missing():
        pytest.skip("package tier: " + debpkg.deb_tools_missing())
    t = [("start", time.monotonic())]
    deb = debpkg.the_deb(tmp_path)
    t.append(("deb", time.monotonic()))
    try:
        pkgroot.pristine()
    except guest.GuestError as e:  # no archive to debootstrap from (offline)
        pytest.skip("package tier: the clean root: %s" % e)
    root = pkgroot.fresh_copy(str(tmp_path / "root"))
    t.append(("clean root", time.monotonic()))
    try:
        out = pkgroot.install(root, deb)
        t.append(("apt-get install", time.monotonic()))
        assert "install ok installed" in out, out[-3000:]
        assert "posture:x:" in out and ":/var/lib/posture:" in out, out[-3000:]
        gone = [f for f in debpkg.FILES if not os.path.lexists(os.path.join(root, f))]
        assert not gone, gone
        assert os.path.islink(os.path.join(
            root, "etc/systemd/system/multi-user.target.wants/postured.service"))
        pkgroot.prepare_boot(root, program("guest_package"))
        img = str(tmp_path / "root.img")
        pkgroot.image(root, img)
    finally:
        shutil.rmtree(root, ignore_errors=True)
    t.append(("image", time.monotonic()))
    console = Tee()
    try:
        status = pkgroot.boot(img, str(tmp_path), console)
    finally:
        os.unlink(img)
    t.append(("boot and checks", time.monotonic()))
    print("times: " + ", ".join("%s %.0f s" % (t[k][0], t[k][1] - t[k - 1][1])
                                for k in range(1, len(t))))
    lines = console.getvalue().splitlines()
    try:
        assert_checks(status, lines, [
            "postured.service active", "postured runs as the user posture",
            "the screen shows the kiosk's picture (KMS)", "tty1 in graphics mode while it runs",
            "postured runs on, never restarted", "postured stops cleanly",
            "the console back after it stops"])
        assert "postured: display: KMS, /dev/dri/card0 Virtual-1" in journal(lines)
    except AssertionError as e:
        raise AssertionError("%s\n-- journalctl -u postured in the guest:\n%s" % (
            e, journal(lines))) from None
