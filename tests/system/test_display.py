"""--display: the kiosk's screen. On a machine without a screen (no /dev/dri/card*,
no /dev/fb0, as here) `auto` says why it has neither and the daemon does not start; a KMS
spec names the card it could not open. (The KMS sink itself is tested against a real kernel in
the QEMU guest: tests/guest/test_guest_kms.py.)"""
import os
import subprocess

import pytest

from daemon import POSTURED


def start(tmp_path, spec):
    return subprocess.run([str(POSTURED), "--socket", str(tmp_path / "sock"), "--state-dir",
                           str(tmp_path / "state"), "--input", "none", "--display", spec],
                          capture_output=True, text=True, timeout=60)


@pytest.mark.skipif(os.path.exists("/dev/dri/card0") or os.path.exists("/dev/fb0"),
                    reason="this machine has a screen")
def test_auto_without_a_screen_says_why(tmp_path):
    p = start(tmp_path, "auto")
    assert p.returncode == 1
    assert "no KMS (/dev/dri/card0: No such file or directory)" in p.stderr
    assert "no fbdev (fb /dev/fb0: open: No such file or directory)" in p.stderr


def test_a_kms_spec_names_its_card(tmp_path):
    p = start(tmp_path, "kms:/nonexistent/card7:HDMI-A-1:1280x720")
    assert p.returncode == 1 and "/nonexistent/card7: No such file or directory" in p.stderr
    p = start(tmp_path, "kms::HDMI-A-1:1280by720")
    assert p.returncode == 1 and "mode '1280by720' is not WxH or WxH@HZ" in p.stderr
