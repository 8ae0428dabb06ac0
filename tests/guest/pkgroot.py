"""A clean Debian 12 root with the posture package installed as a site installs it,
booted in the kernel tier's QEMU guest with systemd as init (test_guest_package.py).

- pristine(): debootstrap --variant=minbase bookworm with systemd, udev and kmod, made
  once and cached under build/debroot/<key>/ (key: every input of the debootstrap);
  fresh_copy() copies it for one run, so the cached root stays clean.
- install(): apt-get install ./posture_*.deb in a chroot (a mount namespace of its own;
  a policy-rc.d lets nothing start there); apt's .debs are kept in build/debroot/archives
  so later runs fetch nothing.
- prepare_boot(): what the boot needs besides the package: the kernel's modules the
  machine loads, and the test's own check unit (never the package's business).
- boot(): an ext4 image of the root (mkfs.ext4 -d), a busybox initramfs that loads
  virtio, ext4 and bochs and switch_roots to /sbin/init, and QEMU with -vga std.

Root is needed (debootstrap, chroot, mount namespaces, file owners in the image).
"""
import fcntl
import hashlib
import os
import shutil
import subprocess
import time

import guest

ROOT = os.path.dirname(os.path.dirname(guest.HERE))
CACHE = os.environ.get("POSTURE_DEBROOT_CACHE", os.path.join(ROOT, "build", "debroot"))
MIRROR = os.environ.get("POSTURE_DEBIAN_MIRROR", "http://deb.debian.org/debian")
SUITE = "bookworm"
# the minimum that boots with systemd as init, udev for the devices, kmod for modprobe
INCLUDE = ["systemd", "systemd-sysv", "udev", "kmod"]
DEBROOT_VERSION = "1"  # bump when what is done to the pristine root changes
# loaded by the initramfs: the disk, its file system, and the screen (bochs-drm); the
# root gets these and evdev (udev loads it for the keyboard) with their modules.dep
BOOT_MODULES = ["virtio_pci", "virtio_blk", "ext4", "bochs"]
ROOT_MODULES = BOOT_MODULES + ["evdev"]
MEMORY = 2048  # MiB: llvmpipe, OSMesa's renderer, and LLVM
JOURNAL_BEGIN = "@@POSTURE-JOURNAL-BEGIN@@"
JOURNAL_END = "@@POSTURE-JOURNAL-END@@"


def missing():
    """Why the package's boot cannot run here, in words; '' when it can."""
    if os.geteuid() != 0:
        return "debootstrap, chroot and the image's file owners need root"
    for tool, pkg in (("debootstrap", "debootstrap"), ("mkfs.ext4", "e2fsprogs"),
                      ("unshare", "util-linux"), ("chroot", "coreutils")):
        if not shutil.which(tool):
            return "%s not found (Debian package %s)" % (tool, pkg)
    probe = subprocess.run(["unshare", "-m", "true"], capture_output=True, text=True)
    if probe.returncode:
        return "no mount namespace here: " + probe.stderr.strip()
    return ""


def _run(cmd, timeout=900, **kw):
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       timeout=timeout, **kw)
    if p.returncode:
        raise guest.GuestError("command failed (%d): %s\n%s" % (
            p.returncode, " ".join(cmd), p.stdout[-4000:]))
    return p.stdout


# ------------------------------------------------------------ the clean root

def _key():
    return hashlib.sha256("|".join([DEBROOT_VERSION, SUITE, "minbase", MIRROR,
                                    ",".join(INCLUDE)]).encode()).hexdigest()[:16]


def pristine():
    """The cached clean root (debootstrap'ed once per key); its path."""
    d = os.path.join(CACHE, _key())
    root = os.path.join(d, "root")
    if os.path.exists(os.path.join(d, "ready")):
        return root
    os.makedirs(CACHE, exist_ok=True)
    with open(os.path.join(CACHE, ".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # parallel runs wait for one debootstrap
        if not os.path.exists(os.path.join(d, "ready")):
            _debootstrap(d)
    return root


def _debootstrap(d):
    t0 = time.monotonic()
    tmp = d + ".tmp"
    shutil.rmtree(tmp, ignore_errors=True)
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(tmp)
    guest.log("debootstrap %s (minbase + %s) from %s" % (SUITE, ",".join(INCLUDE), MIRROR))
    _run(["debootstrap", "--variant=minbase", "--include=" + ",".join(INCLUDE), SUITE,
          os.path.join(tmp, "root"), MIRROR], timeout=1800)
    # the package lists apt resolves Depends from; debootstrap's .debs are not kept
    _in_root(os.path.join(tmp, "root"), "chroot $R apt-get update -qq")
    archives = os.path.join(tmp, "root", "var/cache/apt/archives")
    for f in os.listdir(archives):
        if f.endswith(".deb"):
            os.unlink(os.path.join(archives, f))
    os.rename(tmp, d)
    with open(os.path.join(d, "ready"), "w") as f:
        f.write("%s %s %s\n" % (SUITE, MIRROR, ",".join(INCLUDE)))
    guest.log("clean root made in %.0f s" % (time.monotonic() - t0))


def fresh_copy(dest):
    """A copy of the clean root at dest (which must not exist) for one run."""
    _run(["cp", "-a", "--reflink=auto", pristine(), dest])
    return dest


# the chroot's mounts, in a mount namespace of its own so that nothing outlives the call;
# apt's downloads go to the shared archive cache
MOUNTS = """set -eu
R=$1
mount -t proc proc $R/proc
mount --rbind /dev $R/dev
mount -t tmpfs tmpfs $R/run
mount -t tmpfs tmpfs $R/tmp
mkdir -p "$ARCHIVES/partial" $R/var/cache/apt/archives
mount --bind "$ARCHIVES" $R/var/cache/apt/archives
"""


def _in_root(root, script, *args, timeout=900):
    archives = os.path.join(CACHE, "archives")
    os.makedirs(archives, exist_ok=True)
    env = dict(os.environ, ARCHIVES=archives, DEBIAN_FRONTEND="noninteractive",
               LC_ALL="C.UTF-8", PATH="/usr/sbin:/usr/bin:/sbin:/bin")
    return _run(["unshare", "-m", "--propagation", "private", "sh", "-c", MOUNTS + script,
                 "sh", root, *args], timeout=timeout, env=env)


# ------------------------------------------------------------ the package

INSTALL = """
cp "$2" $R/tmp/
deb=/tmp/$(basename "$2")
# what a site's chroot or image build does: no service starts in there
printf '#!/bin/sh\\nexit 101\\n' > $R/usr/sbin/policy-rc.d
chmod 755 $R/usr/sbin/policy-rc.d
# the lists may be older than the archive (a version gone): refresh them once
chroot $R apt-get install -y -q "$deb" ||
    { chroot $R apt-get update -qq && chroot $R apt-get install -y -q "$deb"; }
rm $R/usr/sbin/policy-rc.d
chroot $R dpkg-query -W -f='${Status}\\n' posture
chroot $R getent passwd posture
"""


def install(root, deb):
    """apt-get install ./posture_*.deb in the root; the output (apt's, then the package's
    status line and the posture user's passwd line)."""
    return _in_root(root, INSTALL, os.path.abspath(deb))


# ------------------------------------------------------------ the boot

CHECK_UNIT = """[Unit]
Description=posture package test: the human on the screen
# only ordered, never Wants=/Requires=: the package's enabling must start postured, and
# the check's systemctl stop of it must not stop the check
After=postured.service
# the image is thrown away: no unit's stop is waited for
SuccessAction=poweroff-force
FailureAction=poweroff-force

[Service]
Type=oneshot
ExecStart=/usr/local/sbin/posture-check-run
StandardOutput=tty
StandardError=tty

[Install]
WantedBy=multi-user.target
"""

CHECK_RUN = """#!/bin/sh
# the checks' lines, the daemon's journal, then the status for the host (guest.py's marker)
/usr/local/sbin/posture-check
rc=$?
echo "%s"
journalctl -b -u postured --no-pager -o short-monotonic
echo "%s"
echo "%s $rc"
""" % (JOURNAL_BEGIN, JOURNAL_END, guest.EXIT_MARKER)


def _modules_to_load(root):
    """ROOT_MODULES and what the root's modules-load.d files ask for (the package's CAN)."""
    names = list(ROOT_MODULES)
    for d in ("usr/lib/modules-load.d", "etc/modules-load.d"):
        p = os.path.join(root, d)
        for f in sorted(os.listdir(p)) if os.path.isdir(p) else ():
            with open(os.path.join(p, f)) as fh:
                names += [ln.strip() for ln in fh
                          if ln.strip() and not ln.lstrip().startswith(("#", ";"))]
    return names


def prepare_boot(root, check_program):
    """Puts into the root what a real machine has besides the package: the kernel's
    modules it loads (as linux-image would, cut down) and the test's check unit, enabled;
    the serial getty is masked so that nothing else holds the console."""
    kver, _, mods_dir, _ = guest.fetch()
    _, files = guest.resolve_modules(mods_dir, _modules_to_load(root))
    mroot = os.path.join(root, "usr/lib/modules", kver)
    for rel in files:
        os.makedirs(os.path.dirname(os.path.join(mroot, rel)), exist_ok=True)
        shutil.copy2(os.path.join(mods_dir, rel), os.path.join(mroot, rel))
    for f in ("modules.builtin", "modules.order", "modules.builtin.modinfo"):
        if os.path.exists(os.path.join(mods_dir, f)):
            shutil.copy2(os.path.join(mods_dir, f), mroot)
    _run(["chroot", root, "depmod", kver])
    sbin = os.path.join(root, "usr/local/sbin")
    shutil.copy2(check_program, os.path.join(sbin, "posture-check"))
    with open(os.path.join(sbin, "posture-check-run"), "w") as f:
        f.write(CHECK_RUN)
    os.chmod(os.path.join(sbin, "posture-check-run"), 0o755)
    etc = os.path.join(root, "etc/systemd/system")
    with open(os.path.join(etc, "posture-check.service"), "w") as f:
        f.write(CHECK_UNIT)
    wants = os.path.join(etc, "multi-user.target.wants")
    os.makedirs(wants, exist_ok=True)
    os.symlink("/etc/systemd/system/posture-check.service",
               os.path.join(wants, "posture-check.service"))
    os.symlink("/dev/null", os.path.join(etc, "serial-getty@ttyS0.service"))


INIT = r"""#!/bin/sh
/bin/busybox --install -s
mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs devtmpfs /dev
for m in $(cat /modules); do
    modprobe "$m" || echo "guest: modprobe $m failed"
done
mkdir -p /newroot
i=0
while [ ! -b /dev/vda ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
mount -t ext4 -o rw /dev/vda /newroot || { echo "guest: cannot mount /dev/vda"; poweroff -f; }
echo "@@POSTURE-GUEST-READY@@ $(cut -d' ' -f1 /proc/uptime)"
for d in dev proc sys; do mount --move /$d /newroot/$d; done
exec switch_root /newroot /sbin/init
"""


def _initramfs(path):
    kver, _, mods_dir, bb = guest.fetch()
    order, files = guest.resolve_modules(mods_dir, BOOT_MODULES)
    c = guest.Cpio()
    for d in ("/bin", "/sbin", "/usr/bin", "/usr/sbin", "/proc", "/sys", "/dev"):
        c.mkdir(d)
    c.host_file("/bin/busybox", bb, 0o755)
    c.symlink("/bin/sh", "busybox")
    c.file("/init", INIT.encode(), 0o755)
    c.file("/modules", ("\n".join(order) + "\n").encode())
    guest.add_modules(c, kver, mods_dir, files)
    with open(path, "wb") as f:
        f.write(c.finish(level=1))


def image(root, path):
    """An ext4 image of the root at path, with room for the state the daemon writes."""
    used = int(_run(["du", "-sxm", root]).split()[0])
    _run(["mkfs.ext4", "-q", "-F", "-L", "posture", "-d", root, path,
          "%dM" % (used * 5 // 4 + 256)])


def boot(img, workdir, out, timeout=240):
    """Boots the image with systemd as init; the check's exit status (GuestError when the
    guest never reports one)."""
    kver, vmlinuz, _, _ = guest.fetch()
    t0 = time.monotonic()
    initrd = os.path.join(workdir, "initrd.cpio.gz")
    _initramfs(initrd)
    # two vCPUs: TCG runs them on two host threads, and llvmpipe renders on both
    cmd = guest.qemu_command(vmlinuz, initrd, MEMORY,
                             "rw systemd.firstboot=off systemd.show_status=error", smp=2)
    cmd += ["-vga", "std", "-drive", "file=%s,format=raw,if=virtio,cache=unsafe" % img]
    return guest.boot(cmd, timeout, out, time.monotonic() - t0)
