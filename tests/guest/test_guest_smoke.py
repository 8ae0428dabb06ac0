"""The kernel test tier's smoke test: uinput/evdev, vcan/CAN_RAW, uhid/hidraw
and a dummy_hcd USB HID gadget, checked in a QEMU guest on Debian's kernel.

Select it with `pytest tests/guest`.  It skips, saying why, when QEMU or the
guest kernel is unavailable; POSTURE_GUEST=skip skips it on purpose.  The
first run downloads Debian's kernel (about 70 MB) into build/guest/.
"""

import shutil
import subprocess

import pytest

from tier import HERE, assert_checks, require_tier, run_program

MODULES = ["uinput", "vcan", "can_raw", "uhid", "usb_f_hid"]
EXPECTED = ("uinput device", "evdev EVIOCGRAB", "evdev EVIOCSCLOCKID",
            "evdev read back", "CAN loopback", "vcan0 up again",
            "hidraw read back", "hid-input evdev agrees",
            "usb gadget report")


def test_guest_smoke(tmp_path):
    require_tier()
    cc = shutil.which("cc")
    if cc is None:
        pytest.skip("kernel tier: no C compiler")
    exe = tmp_path / "smoke"
    subprocess.run([cc, "-std=c11", "-Wall", "-Wextra", "-Werror", "-O1",
                    "-o", str(exe), str(HERE / "smoke.c")],
                   check=True)
    status, lines = run_program(exe, MODULES, timeout=180)
    assert_checks(status, lines, EXPECTED)
    assert "smoke: 0 failures" in lines
