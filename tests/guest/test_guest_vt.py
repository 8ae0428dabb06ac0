"""The kiosk's VT (src/daemon/vt.c) with the KMS screen, on a real kernel: guest_vt runs in the
QEMU guest with QEMU's standard VGA (bochs-drm, fbcon on tty1). The VT taken (graphics mode,
keyboard off, VT_PROCESS); a switch to tty2 asks first, the KMS sink gives up DRM master (a flip
then fails) and the switch happens; back on tty1 master is taken again and a frame flips and
reads back whole; given back, the modes are as they were. A holder killed with SIGKILL leaves
graphics mode, and `--vt-restore`'s function makes tty1 a text console again."""
from tier import assert_checks, require_built, require_tier, run_program

EXPECTED = ("vt taken", "vt kms flips on tty1", "vt asked to release", "vt kms master dropped",
            "vt kms no flip without master", "vt switched away", "vt back", "vt kms master again",
            "vt kms flips again", "vt 1 shown", "vt given back",
            "vt killed holder leaves graphics", "vt restore runs", "vt restored to text")


def test_vt_switches_give_up_and_take_back_the_screen(monkeypatch):
    require_tier()
    require_built("guest_vt")
    monkeypatch.setenv("POSTURE_GUEST_QEMU_ARGS", "-vga std")
    status, lines = run_program("guest_vt", ["bochs"], timeout=200)
    assert_checks(status, lines, EXPECTED)
