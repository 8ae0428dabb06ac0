#!/usr/bin/env python3
"""Finished render to flip request on a real kernel's DRM, measured inside the kernel tier's
QEMU guest (tests/guest/README.md) on its two KMS drivers: bochs-drm (-vga std) and
virtio-gpu. build/rel/guest/guest_kms bench (tests/guest/guest_kms.c) hands 1280x720 frames to
a frame writer at 60 Hz for SECONDS, as the daemon's loop hands them, and its thread writes
them to the KMS sink (src/draw/sink_kms.c), which times each frame from the handing over to
drmModePageFlip returning: the median and p99 of that, and the medians of its parts (queue:
until the writer's thread took it; wait: the previous flip's event; copy: the conversion into
the back buffer; ioctl: the flip request). frames counts the flip requests made, dropped the
frames a newer one replaced before the writer took them.

The guest runs under TCG (software emulation), so its copy is several times a real CPU's
(display.kms_copy, from display_bench, is this host's figure for the same conversion).

Prints one BENCH line per device, or "kms_flip_bench: skipped: WHY" and exits 0 when the tier
cannot run here (no QEMU, no guest kernel, POSTURE_GUEST=skip, the guest program not built).
"""
import io
import os
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
EXE = BUILD / "guest" / "guest_kms"
SECONDS = 5
W, H = 1280, 720
DEVICES = (("bochs", "-vga std", ["bochs"]),
           ("virtio-gpu", "-device virtio-gpu-pci", ["virtio_pci", "virtio_gpu"]))
sys.path.insert(0, str(ROOT / "tests" / "guest"))
import guest  # noqa: E402


def skip(why):
    print(f"kms_flip_bench: skipped: {why}")
    sys.exit(0)


def measure(qemu_args, modules):
    """the guest's kms_flip line as numbers (and its desc), or exits with the output"""
    os.environ["POSTURE_GUEST_QEMU_ARGS"] = qemu_args
    out = io.StringIO()
    try:
        status = guest.run(str(EXE), ["bench", str(SECONDS), str(W), str(H)], modules=modules,
                           timeout=240, out=out)
    except guest.GuestError as e:
        skip(f"the guest did not run: {e}")
    text = out.getvalue()
    m = re.search(r"^kms_flip (.*) desc=(.*)$", text, re.M)
    if status != 0 or not m:
        sys.exit(f"kms_flip_bench: the guest program failed (exit {status}):\n{text}")
    got = {k: v for k, v in re.findall(r"(\w+)=(\S+)", m.group(1))}
    got["desc"] = m.group(2).strip()
    return got


def main():
    why = guest.ready_for(EXE)
    if why:
        skip(why)
    for name, qemu_args, modules in DEVICES:
        r = measure(qemu_args, modules)
        print(f"BENCH display.kms_render_to_flip device={name} median_us={r['median_us']} "
              f"p99_us={r['p99_us']} queue_us={r['queue_us']} wait_us={r['wait_us']} "
              f"copy_us={r['copy_us']} ioctl_us={r['ioctl_us']} frames={r['frames']} "
              f"dropped={r['dropped']} size={r['size']} mode={r['mode']} "
              f"hz=60 seconds={SECONDS} host_load={os.getloadavg()[0]:.1f}", flush=True)


if __name__ == "__main__":
    main()
