"""The Debian package (make deb): built from a copy of the tree as CI builds it, its
files, lintian without errors, and a real install (dpkg -i, maintainer scripts and all)
into a throw-away root: an overlay of this Debian 12 machine's / in a mount namespace
of its own, so the machine itself is left as it was.

POSTURE_DEB=path/to/posture_*.deb tests a package built before instead of building one.
"""
import os
import shutil
import subprocess
import textwrap

import pytest

from debpkg import FILES, the_deb

pytestmark = pytest.mark.skipif(
    not shutil.which("dpkg-buildpackage") or not shutil.which("dh")
    or not shutil.which("lintian"),
    reason="dpkg-buildpackage, debhelper or lintian missing (make deps installs them)")


@pytest.fixture(scope="module")
def deb(tmp_path_factory):
    return the_deb(tmp_path_factory.mktemp("debbuild"))


def test_package_holds_the_service_and_its_files(deb):
    listing = subprocess.run(["dpkg-deb", "-c", str(deb)], capture_output=True, text=True,
                             check=True).stdout
    names = {line.split()[5].lstrip("./") for line in listing.splitlines()}
    missing = [f for f in FILES if f not in names]
    assert not missing, missing
    ctl = subprocess.run(["dpkg-deb", "-f", str(deb), "Depends"], capture_output=True,
                         text=True, check=True).stdout
    for dep in ("python3", "libosmesa6", "fonts-dejavu-core", "systemd-sysusers"):
        assert dep in ctl, ctl
    # the unit as installed: ExecStart is the packaged daemon; the maintainer scripts
    # create the user and enable and start the service
    x = deb.parent / "x"
    subprocess.run(["dpkg-deb", "-R", str(deb), str(x)], check=True)
    unit = (x / "lib/systemd/system/postured.service").read_text()
    assert "ExecStart=/usr/bin/postured --config /etc/posture/postured.conf" in unit
    postinst = (x / "DEBIAN/postinst").read_text()
    assert "systemd-sysusers" in postinst and "posture.conf" in postinst
    assert "deb-systemd-helper enable 'postured.service'" in postinst
    assert "etc/posture/postured.conf" in (x / "DEBIAN/conffiles").read_text()
    conf = (x / "etc/posture/postured.conf").read_text()
    for line in ("init = /usr/share/posture/kiosk.init",
                 "library = /usr/share/posture/library", "display = auto", "vt = stdin",
                 "state-dir = /var/lib/posture", "socket = /run/posture/postured.sock"):
        assert line in conf.splitlines(), line


def test_lintian_finds_no_errors(deb):
    r = subprocess.run(["lintian", "--no-tag-display-limit", str(deb)],
                       capture_output=True, text=True, timeout=300)
    errors = [line for line in r.stdout.splitlines() if line.startswith("E:")]
    assert not errors, r.stdout
    print(r.stdout)


def test_unit_exposure_score(deb, tmp_path):
    """systemd-analyze security on the packaged unit: 1.4 when this was written (8.0
    before the hardening); fails if a change loses much of it"""
    if not shutil.which("systemd-analyze"):
        pytest.skip("systemd-analyze missing")
    subprocess.run(["dpkg-deb", "-x", str(deb), str(tmp_path)], check=True)
    r = subprocess.run(["systemd-analyze", "security", "--offline=true",
                        str(tmp_path / "lib/systemd/system/postured.service")],
                       capture_output=True, text=True)
    line = [x for x in r.stdout.splitlines() if "Overall exposure level" in x]
    assert line, r.stdout + r.stderr
    score = float(line[0].split(":")[1].split()[0])
    assert score <= 2.0, line[0]


# run inside the namespace: an overlay of / as the new root, dpkg -i, the checks, and the
# installed daemon run as the installed user with the installed configuration
INSTALL = textwrap.dedent("""\
    set -eu
    T=$1; DEB=$2
    m=$T/root
    mkdir -p $T/up $T/work $m
    mount -t overlay overlay -o lowerdir=/,upperdir=$T/up,workdir=$T/work $m || exit 42
    for d in dev proc sys; do mount --rbind /$d $m/$d; done
    mount -t tmpfs tmpfs $m/tmp
    mount -t tmpfs tmpfs $m/run
    cp "$DEB" $m/tmp/posture.deb
    ! chroot $m getent passwd posture >/dev/null || { echo "posture user exists before"; exit 3; }
    chroot $m env DEBIAN_FRONTEND=noninteractive dpkg -i /tmp/posture.deb
    chroot $m dpkg-query -W -f='${Status}\\n' posture
    chroot $m getent passwd posture
    test -L $m/etc/systemd/system/multi-user.target.wants/postured.service
    chroot $m /usr/bin/python3 -c 'import posture; print("client", posture.__file__)'
    chroot $m posturectl --help >/dev/null
    # the unit as systemd reads it, with its binary, user and man page in place
    if command -v systemd-analyze >/dev/null; then
        chroot $m systemd-analyze verify /lib/systemd/system/postured.service
        echo "unit verified"
    fi
    # the installed daemon as the installed user with the installed configuration; the
    # framebuffer a file (the machine has none), the state in /tmp
    mkdir -p $m/tmp/st $m/tmp/rt
    truncate -s $((640*480*4)) $m/tmp/fb
    chroot $m chown posture:posture /tmp/st /tmp/rt /tmp/fb
    chroot $m runuser -u posture -- postured --config /etc/posture/postured.conf \\
        --state-dir /tmp/st --socket /tmp/rt/s.sock --fb file:/tmp/fb:640x480 --vt none --input none \\
        --hotplug none > $T/postured.log 2>&1 &
    pid=$!
    for i in $(seq 100); do [ -S $m/tmp/rt/s.sock ] && break; sleep 0.1; done
    sleep 1
    chroot $m posturectl --socket /tmp/rt/s.sock list figures > $T/figures || true
    kill -TERM $pid; wait $pid || true
    cp $m/tmp/fb $T/fb
    ls $m/tmp/st > $T/state.ls
    """)


def test_install_into_a_throwaway_root(deb, tmp_path):
    if os.geteuid() != 0 or not shutil.which("unshare"):
        pytest.skip("a real install needs root and unshare (a mount namespace of its own)")
    if subprocess.run(["dpkg-query", "-W", "posture"], capture_output=True).returncode == 0:
        pytest.skip("posture is installed on this machine: the overlay would not be clean")
    probe = subprocess.run(["unshare", "-m", "true"], capture_output=True, text=True)
    if probe.returncode:
        pytest.skip("no mount namespace here: " + probe.stderr.strip())
    script = tmp_path / "install.sh"
    script.write_text(INSTALL)
    r = subprocess.run(["unshare", "-m", "--propagation", "private", "bash", str(script),
                        str(tmp_path), str(deb)], capture_output=True, text=True, timeout=300)
    if r.returncode == 42:
        pytest.skip("no overlay mount of / here: " + r.stderr.strip()[-300:])
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    assert "install ok installed" in r.stdout
    assert "posture:" in r.stdout and "/var/lib/posture" in r.stdout
    assert "/usr/lib/python3/dist-packages/posture/__init__.py" in r.stdout
    if shutil.which("systemd-analyze"):
        assert "unit verified" in r.stdout
    log = (tmp_path / "postured.log").read_text()
    # the first start loaded the kiosk's init from /usr/share/posture (the human as jack)
    assert "listening on /tmp/rt/s.sock" in log, log
    assert "journal" in (tmp_path / "state.ls").read_text(), log
    assert '"name":"jack","source":"human"' in (tmp_path / "figures").read_text(), log
    # and drew the view on the (file) framebuffer: more than a cleared screen
    fb = (tmp_path / "fb").read_bytes()
    colours = {fb[i:i + 4] for i in range(0, len(fb), 4 * 7)}
    assert len(colours) > 50, (len(colours), log)
