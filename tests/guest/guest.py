#!/usr/bin/env python3
"""Run a test binary inside a QEMU guest booted on Debian's own kernel.

The build machine has no uinput, uhid, USB or CAN in its kernel.  Debian's
stock kernel has all of them as modules, so this module boots that kernel
under QEMU (TCG, no KVM needed) with a tiny busybox initramfs that loads the
requested modules, runs one binary and powers off.

Usage:
    python3 tests/guest/guest.py check
    python3 tests/guest/guest.py fetch
    python3 tests/guest/guest.py run [--modules m1,m2] [--timeout S]
                                     [--file SRC[:DEST]] [--exe PATH]
                                     BINARY [ARGS...]

Everything fetched (Debian packages through apt, unpacked with dpkg-deb,
never installed) lives in build/guest/ (override with POSTURE_GUEST_CACHE).
Standard library only.
"""

import argparse
import fcntl
import gzip
import hashlib
import io
import os
import re
import selectors
import shlex
import shutil
import stat
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
CACHE = os.environ.get("POSTURE_GUEST_CACHE",
                       os.path.join(ROOT, "build", "guest"))
QEMU = os.environ.get("POSTURE_GUEST_QEMU", "qemu-system-x86_64")
KERNEL_META = "linux-image-amd64"
BUSYBOX_PKG = "busybox-static"
EXIT_MARKER = "@@POSTURE-GUEST-EXIT@@"
READY_MARKER = "@@POSTURE-GUEST-READY@@"
_ANSI = re.compile(r"\x1b(\[[0-9;?]*[A-Za-z]|[@-Z\\-_c])")
_FIRMWARE = re.compile(r"^(SeaBIOS|Booting from|iPXE|\s*$)")
_POWEROFF = re.compile(r"reboot: (Power down|Restarting)")
LAYOUT_VERSION = "3"   # bump when the base image layout changes

# Modules that a requested module needs at run time but that modules.dep
# cannot know about, because without udev nothing loads them on demand.
IMPLIED = {
    "uinput": ["evdev"],
    "uhid": ["hid_generic", "evdev"],
    "usbhid": ["hid_generic", "evdev"],
    "usb_f_hid": ["libcomposite", "dummy_hcd", "usbhid", "hid_generic",
                  "evdev"],
    "libcomposite": ["dummy_hcd"],
    "vcan": ["can_raw"],
    "can_raw": ["can"],
    # the crc32c the mount of an ext4 file system asks the crypto API for
    "ext4": ["crc32c_generic"],
}


class GuestError(Exception):
    """The tier cannot run, with a reason meant for people."""


def log(msg):
    print("guest: " + msg, file=sys.stderr, flush=True)


# ---------------------------------------------------------------- fetching

def _run(cmd, cwd=None):
    p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        raise GuestError("command failed (%d): %s\n%s" %
                         (p.returncode, " ".join(cmd), p.stdout.strip()))
    return p.stdout


def _apt_download(pkg, dest):
    """Download one Debian package into dest; return the .deb path."""
    os.makedirs(dest, exist_ok=True)
    if shutil.which("apt-get") is None:
        raise GuestError("apt-get is missing: cannot fetch %s" % pkg)
    try:
        _run(["apt-get", "download", pkg], cwd=dest)
    except GuestError:
        # The package lists may be stale or empty: refresh them once.
        if os.geteuid() != 0:
            raise
        log("apt-get download %s failed; running apt-get update" % pkg)
        _run(["apt-get", "update"])
        _run(["apt-get", "download", pkg], cwd=dest)
    name = pkg.split("=")[0]
    debs = [f for f in os.listdir(dest)
            if f.startswith(name + "_") and f.endswith(".deb")]
    if not debs:
        raise GuestError("apt-get download %s left no .deb" % pkg)
    debs.sort(key=lambda f: os.path.getmtime(os.path.join(dest, f)))
    return os.path.join(dest, debs[-1])


def _deb_depends(deb):
    return _run(["dpkg-deb", "-f", deb, "Depends"]).strip()


def _kernel_dir():
    return os.path.join(CACHE, "kernel")


def _stamp():
    return os.path.join(CACHE, "ready")


def fetched():
    """Return (kernel_release, vmlinuz, modules_dir, busybox) or None."""
    try:
        with open(_stamp()) as f:
            lines = f.read().split()
    except OSError:
        return None
    if len(lines) != 2 or lines[0] != LAYOUT_VERSION:
        return None
    kver = lines[1]
    kd = _kernel_dir()
    vmlinuz = os.path.join(kd, "boot", "vmlinuz-" + kver)
    mods = os.path.join(kd, "lib", "modules", kver)
    bb = os.path.join(CACHE, "busybox", "bin", "busybox")
    for p in (vmlinuz, os.path.join(mods, "modules.dep"), bb):
        if not os.path.exists(p):
            return None
    return kver, vmlinuz, mods, bb


def fetch():
    """Fetch and unpack the kernel, its modules and busybox (once)."""
    have = fetched()
    if have:
        return have
    os.makedirs(CACHE, exist_ok=True)
    with open(os.path.join(CACHE, ".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)   # parallel test runs wait here
        have = fetched()
        return have if have else _fetch()


def _fetch():
    if shutil.which("dpkg-deb") is None:
        raise GuestError("dpkg-deb is missing: cannot unpack Debian packages")
    t0 = time.monotonic()
    debs = os.path.join(CACHE, "debs")
    log("fetching %s (Debian kernel) into %s" % (KERNEL_META, CACHE))
    meta = _apt_download(KERNEL_META, debs)
    m = re.search(r"(linux-image-[0-9][^\s,|()]*-amd64)", _deb_depends(meta))
    if not m:
        raise GuestError("cannot find the versioned kernel in the Depends "
                         "of %s" % os.path.basename(meta))
    versioned = m.group(1)
    kver = versioned[len("linux-image-"):]
    log("fetching %s" % versioned)
    image = _apt_download(versioned, debs)
    kd = _kernel_dir()
    shutil.rmtree(kd, ignore_errors=True)
    log("unpacking %s" % os.path.basename(image))
    _run(["dpkg-deb", "-x", image, kd])
    bbdir = os.path.join(CACHE, "busybox")
    log("fetching %s" % BUSYBOX_PKG)
    bbdeb = _apt_download(BUSYBOX_PKG, debs)
    shutil.rmtree(bbdir, ignore_errors=True)
    _run(["dpkg-deb", "-x", bbdeb, bbdir])
    bb = os.path.join(bbdir, "bin", "busybox")
    # The package ships no modules.dep (depmod runs at install time);
    # busybox's depmod writes one into the unpacked tree.
    log("generating modules.dep")
    _run([bb, "depmod", "-b", kd, kver])
    for f in os.listdir(debs):  # keep the cache small: drop the .debs
        os.unlink(os.path.join(debs, f))
    with open(_stamp(), "w") as f:
        f.write("%s %s\n" % (LAYOUT_VERSION, kver))
    log("fetched in %.1f s" % (time.monotonic() - t0))
    return fetched()


def fetchable():
    """True when the kernel is missing but apt can fetch it here."""
    return (fetched() is None and shutil.which("apt-get") is not None and
            shutil.which("dpkg-deb") is not None)


def check():
    """Return (ok, reason) saying whether the tier can run here now."""
    if sys.platform != "linux" or os.uname().machine != "x86_64":
        return False, "the kernel tier needs an x86_64 Linux host"
    if shutil.which(QEMU) is None:
        return False, ("%s not found (Debian package qemu-system-x86)" % QEMU)
    have = fetched()
    if have is None:
        if not fetchable():
            return False, ("the guest kernel is not fetched and apt-get/"
                           "dpkg-deb are missing to fetch it")
        return False, ("the guest kernel is not fetched yet (about 70 MB; "
                       "run: python3 tests/guest/guest.py fetch)")
    return True, "%s, kernel %s in %s" % (shutil.which(QEMU), have[0], CACHE)


def ready_for(exe):
    """For a benchmark that runs exe in the guest: None when it can run now (the kernel
    fetched first if it can be), else why not."""
    if os.environ.get("POSTURE_GUEST") == "skip":
        return "POSTURE_GUEST=skip"
    if not os.path.exists(exe):
        return "%s is not built (make all builds it)" % exe
    ok, why = check()
    if not ok and shutil.which(QEMU) and fetchable():
        try:
            fetch()
        except GuestError as e:
            return str(e)
        ok, why = check()
    return None if ok else why


# ------------------------------------------------------------- cpio (newc)

class Cpio:
    """A minimal writer of the newc cpio format used by initramfs."""

    def __init__(self):
        self.buf = io.BytesIO()
        self.ino = 1000
        self.dirs = set()

    def _entry(self, name, mode, data=b"", nlink=1):
        name = name.lstrip("/")
        self.ino += 1
        hdr = "070701" + "".join("%08X" % v for v in (
            self.ino, mode, 0, 0, nlink, 0, len(data), 0, 0, 0, 0,
            len(name) + 1, 0))
        self.buf.write(hdr.encode() + name.encode() + b"\0")
        self._pad()
        self.buf.write(data)
        self._pad()

    def _pad(self):
        n = (-self.buf.tell()) % 4
        self.buf.write(b"\0" * n)

    def mkdir(self, path, mode=0o755):
        path = "/" + path.strip("/")
        parts = path.strip("/").split("/")
        for i in range(1, len(parts) + 1):
            d = "/" + "/".join(parts[:i])
            if d not in self.dirs:
                self.dirs.add(d)
                self._entry(d, stat.S_IFDIR | (mode if i == len(parts)
                                                else 0o755), nlink=2)

    def file(self, path, data, mode=0o644):
        self.mkdir(os.path.dirname(path) or "/")
        self._entry(path, stat.S_IFREG | mode, data)

    def host_file(self, path, src, mode=None):
        with open(src, "rb") as f:
            data = f.read()
        if mode is None:
            mode = os.stat(src).st_mode & 0o777
        self.file(path, data, mode)

    def symlink(self, path, target):
        self.mkdir(os.path.dirname(path) or "/")
        self._entry(path, stat.S_IFLNK | 0o777, target.encode())

    def finish(self, level=1):
        self._entry("TRAILER!!!", 0)
        return gzip.compress(self.buf.getvalue(), compresslevel=level,
                             mtime=0)


# ------------------------------------------------------------ the initramfs

INIT = r"""#!/bin/sh
/bin/busybox --install -s
export PATH=/usr/local/bin:/guest/bin:/sbin:/bin:/usr/sbin:/usr/bin
mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs devtmpfs /dev 2>/dev/null
mkdir -p /dev/pts /dev/shm /run /tmp /var/tmp
mount -t devpts devpts /dev/pts
mount -t tmpfs tmpfs /tmp
mount -t tmpfs tmpfs /run
mount -t tmpfs tmpfs /dev/shm
ip link set lo up 2>/dev/null
for m in $(cat /guest/modules); do
    modprobe "$m" || echo "guest: modprobe $m failed"
done
grep -q configfs /proc/filesystems &&
    mount -t configfs configfs /sys/kernel/config 2>/dev/null
grep -q debugfs /proc/filesystems &&
    mount -t debugfs debugfs /sys/kernel/debug 2>/dev/null
echo "@@POSTURE-GUEST-READY@@ $(cut -d' ' -f1 /proc/uptime)"
cd /guest
. /guest/cmd
rc=$?
echo "@@POSTURE-GUEST-EXIT@@ $rc"
sync
poweroff -f
"""


def resolve_modules(mods_dir, names):
    """Expand module names with IMPLIED and modules.dep; return the list
    of names to load (in order) and the set of .ko relative paths."""
    deps = {}
    byname = {}
    with open(os.path.join(mods_dir, "modules.dep")) as f:
        for line in f:
            if ":" not in line:
                continue
            ko, rest = line.split(":", 1)
            deps[ko] = rest.split()
            byname[_modname(ko)] = ko
    builtin = set()
    try:
        with open(os.path.join(mods_dir, "modules.builtin")) as f:
            builtin = {_modname(x.strip()) for x in f if x.strip()}
    except OSError:
        pass
    order, seen, files = [], set(), set()

    def add(name):
        name = name.replace("-", "_")
        if name in seen:
            return
        seen.add(name)
        if name in builtin:
            return
        ko = byname.get(name)
        if ko is None:
            raise GuestError("no kernel module named %r in %s" %
                             (name, mods_dir))
        for d in deps[ko]:
            files.add(d)
        files.add(ko)
        order.append(name)
        for extra in IMPLIED.get(name, []):
            add(extra)

    for n in names:
        add(n)
    return order, files


def _modname(path):
    base = os.path.basename(path)
    for ext in (".ko.xz", ".ko.zst", ".ko.gz", ".ko"):
        if base.endswith(ext):
            base = base[: -len(ext)]
    return base.replace("-", "_")


def add_modules(c, kver, mods_dir, files):
    """Put the module files (relative paths, from resolve_modules) into the cpio c, with
    a modules.dep and modules.alias restricted to them."""
    mroot = "/lib/modules/" + kver
    for rel in sorted(files):
        c.host_file(mroot + "/" + rel, os.path.join(mods_dir, rel), 0o644)
    # A modules.dep (and aliases) restricted to the files we carry, so
    # that busybox modprobe and the kernel's on-demand loading both work.
    dep_lines = []
    with open(os.path.join(mods_dir, "modules.dep")) as f:
        for line in f:
            if line.split(":", 1)[0] in files:
                dep_lines.append(line)
    c.file(mroot + "/modules.dep", "".join(dep_lines).encode())
    names = {_modname(x) for x in files}
    alias_lines = []
    try:
        with open(os.path.join(mods_dir, "modules.alias")) as f:
            for line in f:
                p = line.split()
                if len(p) == 3 and p[2].replace("-", "_") in names:
                    alias_lines.append(line)
    except OSError:
        pass
    c.file(mroot + "/modules.alias", "".join(alias_lines).encode())
    for extra in ("modules.builtin", "modules.order"):
        src = os.path.join(mods_dir, extra)
        if os.path.exists(src):
            c.host_file(mroot + "/" + extra, src, 0o644)


def _base_image(kver, mods_dir, bb, modules):
    """The cached part: busybox, /init, the modules.  Keyed on its inputs."""
    order, files = resolve_modules(mods_dir, modules)
    key = hashlib.sha256(("%s|%s|%s|%s" % (
        LAYOUT_VERSION, kver, INIT, " ".join(sorted(files) + order))
    ).encode()).hexdigest()[:16]
    path = os.path.join(CACHE, "initrd", "base-%s.cpio.gz" % key)
    if os.path.exists(path):
        return path
    c = Cpio()
    for d in ("/bin", "/sbin", "/usr/bin", "/usr/sbin", "/proc", "/sys",
              "/dev", "/tmp", "/run", "/etc", "/root", "/guest",
              "/lib/modules/" + kver):
        c.mkdir(d)
    c.host_file("/bin/busybox", bb, 0o755)
    c.symlink("/bin/sh", "busybox")
    c.file("/init", INIT.encode(), 0o755)
    c.file("/etc/passwd", b"root:x:0:0:root:/root:/bin/sh\n")
    c.file("/etc/group", b"root:x:0:\ninput:x:101:\n")
    c.file("/guest/modules", ("\n".join(order) + "\n").encode())
    add_modules(c, kver, mods_dir, files)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    tmp = path + ".tmp%d" % os.getpid()
    with open(tmp, "wb") as f:
        f.write(c.finish(level=6))
    os.replace(tmp, path)
    return path


def _libraries(exe):
    """Absolute paths of the shared libraries (and loader) exe needs."""
    p = subprocess.run(["ldd", exe], stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True)
    out = p.stdout
    if "not a dynamic executable" in out or "statically linked" in out:
        return []
    if p.returncode != 0:
        raise GuestError("ldd %s failed: %s" % (exe, out.strip()))
    libs = []
    for line in out.splitlines():
        line = line.strip()
        if "=> not found" in line:
            raise GuestError("%s: library %s not found on this machine" %
                             (exe, line.split()[0]))
        m = re.match(r"(?:\S+\s+=>\s+)?(/\S+)\s+\(0x", line)
        if m:
            libs.append(m.group(1))
    return libs


def _run_image(binary, args, files, exes, env):
    """The per-run part: the binary, its libraries, extra files, command."""
    c = Cpio()
    for d in ("/guest", "/guest/bin"):
        c.mkdir(d)
    libs = set()
    placed = {}
    name = os.path.basename(binary)
    placed["/guest/bin/" + name] = binary
    for e in exes:
        placed["/usr/local/bin/" + os.path.basename(e)] = e
    for dest, src in placed.items():
        c.host_file(dest, src, 0o755)
        libs.update(_libraries(src))
    for src, dest in files:
        if os.path.isdir(src):
            for dirpath, _, fnames in os.walk(src):
                for fn in fnames:
                    s = os.path.join(dirpath, fn)
                    c.host_file(dest + "/" + os.path.relpath(s, src), s)
        else:
            c.host_file(dest, src)
    done = set()
    for lib in sorted(libs):
        # The guest has no usrmerge symlinks: the real file goes under its
        # resolved name, and the name ldd printed (what the loader and the
        # ELF interpreter ask for) is a symlink to it when that differs.
        # Once, not twice: postured's OSMesa and LLVM are about 200 MB.
        real = os.path.realpath(lib)
        if real not in done:
            done.add(real)
            c.host_file(real, real, 0o755)
        if lib not in done:
            done.add(lib)
            c.symlink(lib, real)
    cmd = []
    for k, v in env:
        cmd.append("export %s=%s" % (k, shlex.quote(v)))
    cmd.append(" ".join(shlex.quote(a) for a in
                        ["/guest/bin/" + name] + list(args)))
    c.file("/guest/cmd", ("\n".join(cmd) + "\n").encode())
    return c.finish(level=1)


# ------------------------------------------------------------------ running

def run(binary, args=(), modules=(), timeout=120.0, files=(), exes=(),
        env=(), out=None, memory=512, append=""):
    """Boot the guest, run binary with args, return its exit status.

    The guest's console is streamed to out (default: sys.stdout).
    Raises GuestError when the guest cannot be set up or does not finish.
    """
    out = out or sys.stdout
    if shutil.which(QEMU) is None:
        raise GuestError("%s not found: install Debian's qemu-system-x86" %
                         QEMU)
    if not os.path.isfile(binary) or not os.access(binary, os.X_OK):
        raise GuestError("%s is not an executable file" % binary)
    kver, vmlinuz, mods_dir, bb = fetch()
    t0 = time.monotonic()
    base = _base_image(kver, mods_dir, bb, list(modules))
    extra = _run_image(binary, args, files, exes, env)
    os.makedirs(os.path.join(CACHE, "initrd"), exist_ok=True)
    fd, initrd = tempfile.mkstemp(prefix="run-", suffix=".cpio.gz",
                                  dir=os.path.join(CACHE, "initrd"))
    try:
        with os.fdopen(fd, "wb") as f:
            with open(base, "rb") as b:
                shutil.copyfileobj(b, f)
            f.write(extra)   # the kernel unpacks concatenated archives
        t_pack = time.monotonic() - t0
        return boot(qemu_command(vmlinuz, initrd, memory, append), timeout, out, t_pack)
    finally:
        os.unlink(initrd)


def qemu_command(vmlinuz, initrd, memory=512, append="", smp=1):
    """The QEMU command line of a guest: serial console on stdio, no reboot (a panic
    ends QEMU), and POSTURE_GUEST_QEMU_ARGS (e.g. -vga std) at the end."""
    # -cpu max: the project's binaries are built for x86-64-v2 (SSE4.2,
    # POPCNT), which TCG's default qemu64 CPU lacks
    cmd = [QEMU, "-accel", "tcg", "-cpu", "max", "-m", str(memory), "-smp", str(smp),
           "-nographic", "-no-reboot", "-nodefaults", "-serial", "stdio",
           "-kernel", vmlinuz, "-initrd", initrd,
           "-append", ("console=ttyS0 quiet panic=-1 oops=panic "
                       "loglevel=3 tsc=reliable " + append).strip()]
    return cmd + shlex.split(os.environ.get("POSTURE_GUEST_QEMU_ARGS", ""))


def boot(cmd, timeout, out, t_pack=0.0):
    """Run the QEMU command cmd, streaming its console to out, until the guest prints
    EXIT_MARKER and powers off; return the status the marker gives (GuestError when
    it never comes, with the panic and the last console lines)."""
    t0 = time.monotonic()
    try:
        p = subprocess.Popen(cmd, stdin=subprocess.DEVNULL,
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    except OSError as e:
        raise GuestError("cannot start %s: %s" % (cmd[0], e))
    sel = selectors.DefaultSelector()
    sel.register(p.stdout, selectors.EVENT_READ)
    pending = b""
    status = None
    tail = []
    panic = []
    ready_at = None
    timed_out = False
    try:
        while True:
            left = timeout - (time.monotonic() - t0)
            if left <= 0:
                timed_out = True
                break
            if not sel.select(timeout=min(left, 1.0)):
                continue
            chunk = os.read(p.stdout.fileno(), 65536)
            if not chunk:
                break
            pending += chunk
            while b"\n" in pending:
                raw, pending = pending.split(b"\n", 1)
                line = _ANSI.sub("", raw.decode("utf-8", "replace"))
                line = line.replace("\r", "")
                tail = (tail + [line])[-30:]
                for key in ("Kernel panic", "BUG:", "Oops:"):
                    if key in line:
                        panic.append(line[line.index(key):].strip())
                        break
                if READY_MARKER in line:
                    ready_at = time.monotonic() - t0
                    continue
                if ready_at is None and _FIRMWARE.match(line):
                    continue
                if EXIT_MARKER in line:
                    # Output without a final newline shares this line.
                    before, _, after = line.partition(EXIT_MARKER)
                    try:
                        status = int(after.split()[0])
                    except (IndexError, ValueError):
                        status = 255
                    if before:
                        out.write(before + "\n")
                    continue
                if status is not None and _POWEROFF.search(line):
                    continue
                out.write(line + "\n")
                out.flush()
    finally:
        if p.poll() is None:
            p.kill()
        p.wait()
        sel.close()
    wall = time.monotonic() - t0
    if pending:
        out.write(pending.decode("utf-8", "replace") + "\n")
    crash = ("; the kernel said: " + " | ".join(panic[:3])) if panic else ""
    if timed_out:
        raise GuestError("guest timed out after %.0f s%s%s" %
                         (timeout, crash, _tail_note(tail, status is None)))
    if status is None:
        why = "the guest stopped without reporting an exit status"
        if ready_at is None:
            why = "the guest did not boot to /init (qemu exit %d)" % \
                p.returncode
        raise GuestError(why + crash + _tail_note(tail, True))
    if panic:
        log("warning: the kernel reported: " + " | ".join(panic[:3]))
    log("exit %d; packed %.2f s, boot %s s, total %.1f s in the guest" % (
        status, t_pack, "%.1f" % ready_at if ready_at else "?", wall))
    return status


def _tail_note(tail, show):
    if not show or not tail:
        return ""
    return "; last console lines:\n  " + "\n  ".join(tail[-15:])


# ---------------------------------------------------------------------- CLI

def main(argv=None):
    ap = argparse.ArgumentParser(
        prog="guest.py",
        description="Run a binary in a QEMU guest on Debian's kernel.")
    sub = ap.add_subparsers(dest="cmd", required=True)
    c = sub.add_parser("check", help="say whether the tier can run here")
    c.add_argument("--fetch", action="store_true",
                   help="fetch the kernel first when it is missing")
    sub.add_parser("fetch", help="fetch the kernel, modules and busybox")
    r = sub.add_parser("run", help="run BINARY [ARGS...] in the guest")
    r.add_argument("--modules", default="",
                   help="comma-separated kernel modules to load")
    r.add_argument("--timeout", type=float, default=120.0)
    r.add_argument("--memory", type=int, default=512, help="MiB")
    r.add_argument("--file", action="append", default=[],
                   metavar="SRC[:DEST]",
                   help="copy a host file or folder in (default DEST "
                        "/guest/<name>)")
    r.add_argument("--exe", action="append", default=[], metavar="PATH",
                   help="copy a host executable with its libraries to "
                        "/usr/local/bin")
    r.add_argument("--env", action="append", default=[], metavar="K=V")
    r.add_argument("--append", default="", help="extra kernel arguments")
    r.add_argument("binary")
    r.add_argument("args", nargs=argparse.REMAINDER)
    a = ap.parse_args(argv)

    if a.cmd == "check":
        ok, why = check()
        if not ok and a.fetch and shutil.which(QEMU) and fetchable():
            try:
                fetch()
            except GuestError as e:
                print("skip: fetching the guest kernel failed: %s" % e)
                return 1
            ok, why = check()
        print(("ok: " if ok else "skip: ") + why)
        return 0 if ok else 1
    try:
        if a.cmd == "fetch":
            kver, vmlinuz, _, _ = fetch()
            print("ok: kernel %s (%s)" % (kver, vmlinuz))
            return 0
        files = []
        for spec in a.file:
            src, _, dest = spec.partition(":")
            files.append((os.path.abspath(src),
                          dest or "/guest/" + os.path.basename(src)))
        env = [tuple(e.split("=", 1)) for e in a.env]
        mods = [m for m in a.modules.split(",") if m]
        exes = [shutil.which(e) or e for e in a.exe]
        return run(os.path.abspath(a.binary), a.args, mods, a.timeout,
                   files, exes, env, memory=a.memory, append=a.append)
    except GuestError as e:
        log("error: %s" % e)
        return 125


if __name__ == "__main__":
    sys.exit(main())
