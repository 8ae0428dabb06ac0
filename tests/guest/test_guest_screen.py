"""The real daemon on the machine's screen: postured runs in the QEMU guest with
QEMU's standard VGA (bochs-drm) and `--display auto --vt /dev/tty1 --init tools/kiosk.init`:
auto takes KMS, the frames it writes are what the CRTC shows (the kiosk's picture, not the
console's framebuffer), tty1 is in graphics mode while it runs, and after SIGTERM it exits 0
with tty1 in text mode and the console's framebuffer back on the CRTC. While it runs,
status's flip_us times the frames from the loop to their flip requests."""
from tier import ROOT, assert_checks, require_built, require_tier, run_program

from test_guest_kiosk import KEYBOARD_DATA, MEMORY, POSTURED

FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf"


def test_the_daemon_shows_the_kiosk_on_the_screen_and_gives_the_console_back(monkeypatch):
    require_tier()
    require_built("guest_screen")
    monkeypatch.setenv("POSTURE_GUEST_QEMU_ARGS", "-vga std")
    status, lines = run_program(
        "guest_screen", ["bochs"], ["/usr/local/bin/postured", "/guest/kiosk.init"],
        files=["%s:/guest/kiosk.init" % (ROOT / "tools" / "kiosk.init"), "%s:%s" % (FONT, FONT),
               *KEYBOARD_DATA],
        exes=[POSTURED], timeout=240, memory=MEMORY)
    assert_checks(status, lines, [
        "the console shows on a CRTC", "frames written to the screen",
        "the screen shows the kiosk's picture (KMS)", "status reports render to flip",
        "tty1 in graphics mode while it runs",
        "postured stops cleanly on SIGTERM", "the console back after it stops"])
    assert any("postured: display: KMS, /dev/dri/card0 Virtual-1" in ln for ln in lines)
