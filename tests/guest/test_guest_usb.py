"""The USB backend against the guest's kernel: a configfs HID gadget (a mouse
and a keyboard) on dummy_hcd, opened through libusb with usbhid set aside,
reports compared with what the kernel's own evdev nodes said for them, the
driver given back on close, an unplug mid-press, and a re-plug picked up by
libusb's hot-plug callback (guest_usb.c says how), and one picked up by a
rescan where no udevd runs; last, a descriptor our parser refuses: boot
protocol on a boot mouse, skipped elsewhere; and a hi-res wheel, whose
Resolution Multiplier feature we must write as usbhid writes it.

It skips, saying why, when the kernel tier cannot run or the program was not
built (make all builds it into $POSTURE_BUILD/guest).
"""

import io
import os
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import guest  # noqa: E402

EXPECTED = ("gadget 1d6b:0104 bound", "the kernel's meaning of 8 reports",
            "opened usb:1-1:0", "detach:", "usb reports: all 8 reports",
            "re-attach:", "unplug mid-press:", "hot-plug:", "no udevd:",
            "boot fallback: the refused", "boot fallback: the non-boot",
            "boot fallback: boot reports", "multiplier: the feature report",
            "multiplier: 1/8 + 7/8")


@pytest.fixture(scope="module")
def tier():
    if os.environ.get("POSTURE_GUEST") == "skip":
        pytest.skip("kernel tier: POSTURE_GUEST=skip")
    ok, why = guest.check()
    if not ok and guest.fetchable():
        try:
            guest.fetch()
        except guest.GuestError as e:
            pytest.skip("kernel tier: %s" % e)
        ok, why = guest.check()
    if not ok:
        pytest.skip("kernel tier: %s" % why)


def test_guest_usb(tier):
    build = os.environ.get("POSTURE_BUILD", os.path.join("build", "rel"))
    exe = os.path.join(build, "guest", "guest_usb")
    if not os.access(exe, os.X_OK):
        pytest.skip("%s is not built (make all)" % exe)
    out = io.StringIO()
    try:
        status = guest.run(os.path.abspath(exe), modules=["usb_f_hid"],
                           timeout=180, out=out)
    except guest.GuestError as e:
        pytest.fail("the guest did not run: %s\n%s" % (e, out.getvalue()))
    text = out.getvalue()
    print(text)
    lines = text.splitlines()
    failed = [ln for ln in lines if ln.startswith("FAIL ")]
    assert not failed, "\n".join(failed)
    passed = [ln for ln in lines if ln.startswith("ok ")]
    for what in EXPECTED:
        assert any(what in ln for ln in passed), "no 'ok %s' line" % what
    assert "guest_usb: 0 failures" in lines
    assert status == 0
