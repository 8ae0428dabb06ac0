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

from tier import BUILD, assert_checks, require_built, require_tier, run_program

EXPECTED = ("gadget 1d6b:0104 bound", "the kernel's meaning of 8 reports",
            "opened usb:1-1:0", "detach:", "usb reports: all 8 reports",
            "re-attach:", "record: posture-input record usb:", "unplug mid-press:", "hot-plug:", "no udevd:",
            "boot fallback: the refused", "boot fallback: the non-boot",
            "boot fallback: boot reports", "multiplier: the feature report",
            "multiplier: 1/8 + 7/8")


def test_guest_usb():
    require_tier()
    require_built("guest_usb")
    status, lines = run_program("guest_usb", ["usb_f_hid"], timeout=180,
                                exes=[BUILD / "bin" / "posture-input"])
    assert_checks(status, lines, EXPECTED)
    assert "guest_usb: 0 failures" in lines
