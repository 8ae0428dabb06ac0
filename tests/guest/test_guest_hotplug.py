"""Hot-plug against the real kernel: a mouse arriving while the device set runs is opened
by the rescan the monitor's uevent asks for; unplugged mid-press, its button is released
and its place freed (tests/guest/guest_hotplug.c)."""
from tier import assert_checks, require_tier, run_program


def test_a_mouse_arrives_is_opened_then_leaves_mid_press():
    require_tier()
    status, lines = run_program("guest_hotplug", ["uinput"])
    assert_checks(status, lines, [
        "its arrival seen by the monitor", "the rescan opened the new mouse and nothing else",
        "INPUT_ADDED queued for it", "the press comes through",
        "a removal is not an arrival", "the held button released as an event",
        "INPUT_REMOVED queued", "its place is free again"])
