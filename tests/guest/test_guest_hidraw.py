"""The hidraw backend against the kernel: uhid devices made from a hid-recorder recording,
opened through hidapi by the device set, checked report by report against the kernel's own
hid-input evdev node, then destroyed mid-press; and a mouse with hi-res wheels, whose Resolution
Multipliers the backend must write (the fake answers GET_REPORT and SET_REPORT) and whose wheel
events must agree with hid-input's REL_WHEEL_HI_RES (tests/guest/guest_hidraw.c says what is
checked).

Select it with `pytest tests/guest`.  It skips, saying why, when QEMU or the guest kernel is
unavailable (POSTURE_GUEST=skip skips it on purpose) or the guest program was not built
(`make all` builds $(BUILD)/rel/guest/guest_hidraw).
"""

from tier import ROOT, assert_checks, require_built, require_tier, run_program

HID = ROOT / "tests" / "input" / "hid"

# the checks the program must pass: (what the line says)
EXPECTED = (
    "uhid mouse 'QEMU QEMU USB Mouse'",
    "uhid keyboard 'QEMU QEMU USB Keyboard'",
    "enumeration: 3 hidapi entries, 2 nodes",
    "opened the mouse",
    "opened the keyboard",
    "mouse recorded report",
    "keyboard recorded report",
    "mouse extra report",
    "keyboard extra report",
    "both readers stopped and joined",
    "the rescan opened both again",
    "mouse held report",
    "mouse gone mid-press: BTN_LEFT released, the device removed",
    "its place is free; the keyboard is still open",
    "keyboard after report",
    "keyboard gone: removed, nothing to release",
    "hi-res: the backend read feature report 0 and wrote it back with both multipliers",
    "hi-res mouse hi-res report",
    "hi-res mouse gone: removed",
)


def test_guest_hidraw_agrees_with_hid_input():
    require_tier()
    require_built("guest_hidraw")
    files = {"two.hid": "hidtools_two.hid", "mouse.hid": "hidtools_mouse.hid",
             "hires.rdesc": "hires_wheel.rdesc"}
    status, lines = run_program(
        "guest_hidraw", ["uhid"], ["/guest/" + name for name in files],
        files=["%s:/guest/%s" % (HID / src, name) for name, src in files.items()])
    assert_checks(status, lines, EXPECTED)
    passed = [ln for ln in lines if ln.startswith("ok ")]
    # every report of both recordings was compared: 4 in the two-device one, 3 in the mouse's
    assert sum("recorded report" in ln for ln in passed) == 7
    # the line that says the mouse went away blames the device and counts the release
    assert any("device fault: gone" in ln and "1 key(s) and button(s) released" in ln
               for ln in lines)
    # the hi-res wheel: 15 in 1/120 a count (multiplier 8), a detent after 120, pan -30
    assert any("hi-res report: 00 00 00 00 00 05 00" in ln and "2/8/1 2/11/75" in ln
               for ln in lines)
    assert sum("hi-res mouse hi-res report" in ln for ln in passed) == 7
    assert "guest_hidraw: 38 checks, 0 failures" in lines
