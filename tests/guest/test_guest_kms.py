"""The DRM/KMS sink (src/draw/sink_kms.c) on a real kernel: guest_kms runs in the QEMU guest
with QEMU's standard VGA (the bochs-drm driver), and again with virtio-gpu, sets the card's preferred mode, flips 120
frames and reads each back from the scanout buffer shown, equal to the frame as XRGB8888
(computed in the test program, not by the sink's converter); closing restores the console's
framebuffer on the CRTC; every frame is timed from its render to its flip request, with no
wait (the last flip was in) and a flip request that does not wait for the flip; a connector re-probe in between (the kernel made to probe first)
keeps the screen as it is. Then fbdev emulation on the same card, whose virtual height (no
overallocation) leaves the fbdev sink one buffer: a frame written reads back from /dev/fb0."""
import pytest

from tier import assert_checks, require_built, require_tier, run_program

EXPECTED = ("kms mode set", "kms 120 frames flipped", "kms flip events", "kms render to flip",
            "kms re-probe keeps the screen", "kms crtc restored",
            "fbdev emulation", "fbdev single buffer write", "fbdev read back")


@pytest.mark.parametrize("device, modules", [
    ("-vga std", ["bochs"]),                                     # bochs-drm
    ("-device virtio-gpu-pci", ["virtio_pci", "virtio_gpu"]),    # virtio-gpu
])
def test_kms_sink_flips_frames_that_read_back_exactly(monkeypatch, device, modules):
    require_tier()
    require_built("guest_kms")
    monkeypatch.setenv("POSTURE_GUEST_QEMU_ARGS", device)
    status, lines = run_program("guest_kms", modules, ["120"], timeout=200)
    assert_checks(status, lines, EXPECTED)
    assert any("virtual 1280x800" in ln for ln in lines), "fbdev without overallocation"
