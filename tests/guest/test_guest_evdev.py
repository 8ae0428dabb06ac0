"""uinput devices replay evemu recordings into the evdev backend (grab, SYN_DROPPED, unplug
mid-drag), on Debian's kernel in the QEMU guest (tests/guest/README.md).

build/rel/guest/guest_evdev (tests/guest/guest_evdev.c, built by make) runs in the guest once
for the whole module: it makes a uinput device from each recording of tests/input/evdev (written
by libevemu, not by us), opens it through the device set and replays the recording's events.
The references are outside our code: the recording itself (the kernel must pass its records
unchanged, and the backend must give what decoding the recording's bytes offline gives), a
second plain reader of the same node (the grab), the kernel's own key state (EVIOCGKEY after a
real SYN_DROPPED) and the kernel's refusal of a second grab. It skips, saying why, when the
tier cannot run; POSTURE_GUEST=skip skips it on purpose.
"""

import pytest

from tier import ROOT, require_tier, run_program


@pytest.fixture(scope="module")
def run():
    """the guest's exit status and output lines (one boot for every test here)"""
    require_tier()
    return run_program("guest_evdev", ["uinput"], ["check", "/guest/evdev"],
                       files=["%s:/guest/evdev" % (ROOT / "tests" / "input" / "evdev")])


def passed(lines, what):
    failed = [ln for ln in lines if ln.startswith("FAIL %s" % what)]
    assert not failed, "\n".join(failed)
    return [ln for ln in lines if ln.startswith("ok ") and what in ln]


def test_probe_real_nodes(run):
    _, lines = run
    for rec in ("mouse", "keyboard", "tablet", "tablet-v1.0"):
        assert passed(lines, "(%s.evemu)" % rec), "evdev_dev_probe of %s" % rec
    assert passed(lines, "probe /dev/null refused")
    assert passed(lines, "probe of a missing node refused")


@pytest.mark.parametrize("rec", ["mouse", "keyboard", "tablet", "tablet-v1.0"])
def test_replay_through_the_kernel(run, rec):
    _, lines = run
    ok = passed(lines, "replay %s.evemu:" % rec)
    assert any("passed its" in ln for ln in ok), "no ok line for the replay of " + rec
    assert any("description read back" in ln for ln in ok), "no ok line for the description"


def test_auto_picks_mouse_and_keyboard(run):
    _, lines = run
    assert passed(lines, "auto:")


def test_grab(run):
    _, lines = run
    for what in ("grab held:", "ungrab:", "grab taken again:", "close: the grab is gone",
                 "reopen: the grab is taken again"):
        assert passed(lines, what), what


def test_grab_held_by_another_process(run):
    _, lines = run
    ok = passed(lines, "evdev_dev_open with grab on a node another process grabbed")
    assert ok and "another reader holds the grab" in ok[0]
    assert passed(lines, "the set's open with grab skips it")
    assert passed(lines, "after the other process ended the grab is ours")


def test_syn_dropped_resync(run):
    _, lines = run
    assert passed(lines, "SYN_DROPPED from a real overflow")


def test_syn_dropped_resync_after_the_waiting_records(run):
    _, lines = run
    assert passed(lines, "SYN_DROPPED with a long tail")


def test_read_cap_splits_a_frame(run):
    _, lines = run
    assert passed(lines, "read cap:")


def test_unplug_mid_drag(run):
    _, lines = run
    ok = passed(lines, "unplug mid-drag:")
    assert ok and "Posture Test 3-Button" in ok[0] and "gone (No such device)" in ok[0]


def test_no_failures(run):
    status, lines = run
    assert "guest_evdev: 0 failures" in lines
    assert status == 0
