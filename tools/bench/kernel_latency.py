#!/usr/bin/env python3
"""Kernel-to-loop input latency, measured inside the kernel tier's QEMU guest
(tests/guest/README.md): build/rel/guest/guest_evdev latency (tests/guest/guest_evdev.c,
built by make) has a child process write motion frames through uinput, GAP_US apart, while
the parent waits in poll() on the device set's fds as the daemon's loop does; each frame is
timed from the kernel's CLOCK_MONOTONIC stamp of the write (and from the writer's
clock_gettime just before write()) to its INPUT_MOTION being in the set's queue after
input_devs_ready. Median and p99 over N frames after a warm-up of 20; lost counts the frames
the kernel dropped because the reader fell a whole client buffer behind (drops: the
SYN_DROPPEDs).

The guest runs under TCG (software emulation, no KVM here), so its times are not a real
machine's: beside them stands the guest's slowdown, the same two fixed computations timed
on this host and in the guest (alu: xorshift steps in registers; decode: motion frames
through the evdev decoder, the CPU work on the latency's path). tcg_slowdown is the decode
ratio, alu_slowdown the other; host_load is this host's 1-minute load average during the
run (the guest's vCPU is one host thread, which contention on the host delays).

Prints one BENCH line, or "kernel_latency: skipped: WHY" and exits 0 when the tier cannot
run here (no QEMU, no guest kernel, POSTURE_GUEST=skip, the guest program not built).
"""
import io
import os
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
EXE = BUILD / "guest" / "guest_evdev"
N = 2000
GAP_US = 300
sys.path.insert(0, str(ROOT / "tests" / "guest"))
import guest  # noqa: E402


def skip(why):
    print(f"kernel_latency: skipped: {why}")
    sys.exit(0)


def fields(text, tag):
    """the key=value numbers of the first line starting with tag"""
    m = re.search(r"^%s (.*)$" % tag, text, re.M)
    if not m:
        return None
    return {k: float(v) for k, v in re.findall(r"(\w+)=([0-9.]+)", m.group(1))}


def host_calib():
    """the best of three runs of the calibration on this host"""
    best = {}
    for _ in range(3):
        p = subprocess.run([str(EXE), "calib"], capture_output=True, text=True, check=True)
        for k, v in fields(p.stdout, "calib").items():
            best[k] = min(best.get(k, v), v)
    return best


def main():
    why = guest.ready_for(EXE)
    if why:
        skip(why)

    before = host_calib()
    load0 = os.getloadavg()[0]
    out = io.StringIO()
    try:
        status = guest.run(str(EXE), ["latency", str(N), str(GAP_US)], modules=["uinput"],
                           timeout=300, out=out)
    except guest.GuestError as e:
        skip(f"the guest did not run: {e}")
    load1 = os.getloadavg()[0]
    after = host_calib()
    text = out.getvalue()
    lat, gcal = fields(text, "latency"), fields(text, "calib")
    if status != 0 or not lat or not gcal:
        sys.exit(f"kernel_latency: the guest program failed (exit {status}):\n{text}")
    host = {k: min(before[k], after[k]) for k in before}
    tcg = gcal["decode_ns"] / host["decode_ns"]
    alu = gcal["alu_ns"] / host["alu_ns"]
    print(f"BENCH input.kernel_latency median_us={lat['median_us']:.1f} "
          f"p99_us={lat['p99_us']:.1f} n={lat['n']:.0f} lost={lat['lost']:.0f} "
          f"drops={lat['drops']:.0f} gap_us={lat['gap_us']:.0f} "
          f"write_median_us={lat['write_median_us']:.1f} "
          f"write_p99_us={lat['write_p99_us']:.1f} max_us={lat['max_us']:.1f} "
          f"tcg_slowdown={tcg:.1f} alu_slowdown={alu:.1f} "
          f"host_load={max(load0, load1):.1f}")
    print(f"kernel_latency: in the TCG guest, the kernel's stamp to the set's queue takes "
          f"{lat['median_us']:.0f} us (median), {lat['p99_us']:.0f} us (p99); the guest "
          f"decodes {tcg:.1f}x slower than this host (decode {gcal['decode_ns']:.1f} vs "
          f"{host['decode_ns']:.1f} ns a frame), alu {alu:.1f}x")


if __name__ == "__main__":
    main()
