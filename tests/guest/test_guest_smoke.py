"""The kernel test tier's smoke test: uinput/evdev, vcan/CAN_RAW, uhid/hidraw
and a dummy_hcd USB HID gadget, checked in a QEMU guest on Debian's kernel.

Select it with `pytest tests/guest`.  It skips, saying why, when QEMU or the
guest kernel is unavailable; POSTURE_GUEST=skip skips it on purpose.  The
first run downloads Debian's kernel (about 70 MB) into build/guest/.
"""

import os
import shutil
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import guest  # noqa: E402
from tier import require_tier  # noqa: E402

MODULES = "uinput,vcan,can_raw,uhid,usb_f_hid"
EXPECTED = ("uinput device", "evdev EVIOCGRAB", "evdev EVIOCSCLOCKID",
            "evdev read back", "CAN loopback", "vcan0 up again",
            "hidraw read back", "hid-input evdev agrees",
            "usb gadget report")


@pytest.fixture(scope="module")
def tier():
    require_tier()


def test_guest_smoke(tier, tmp_path):
    cc = shutil.which("cc")
    if cc is None:
        pytest.skip("kernel tier: no C compiler")
    exe = tmp_path / "smoke"
    subprocess.run([cc, "-std=c11", "-Wall", "-Wextra", "-Werror", "-O1",
                    "-o", str(exe), os.path.join(HERE, "smoke.c")],
                   check=True)
    p = subprocess.run([sys.executable, os.path.join(HERE, "guest.py"),
                        "run", "--modules", MODULES, "--timeout", "180",
                        str(exe)],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True)
    print(p.stdout)
    assert p.returncode != 125, "the guest did not run:\n" + p.stdout
    lines = p.stdout.splitlines()
    failed = [ln for ln in lines if ln.startswith("FAIL ")]
    assert not failed, "\n".join(failed)
    passed = [ln for ln in lines if ln.startswith("ok ")]
    for what in EXPECTED:
        assert any(what in ln for ln in passed), "no 'ok %s' line" % what
    assert "smoke: 0 failures" in lines
    assert p.returncode == 0
