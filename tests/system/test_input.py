"""Input over the socket (`input ...`) and the decoded stream (`subscribe input`) against
the real daemon: each line becomes the event a device would give, in order, with the
kernel's codes; bad lines change nothing."""
import re
from fractions import Fraction

import pytest

from conftest import ROOT

from daemon import daemon, daemon_factory, snapshot  # noqa: F401 (fixtures)


def kernel_codes():
    """KEY_* and BTN_* numbers from the kernel's own header, the independent reference."""
    text = open("/usr/include/linux/input-event-codes.h").read()
    codes = {}
    for name, value in re.findall(r"#define\s+((?:KEY|BTN)_\w+)\s+(0x[0-9a-fA-F]+|\d+)\b", text):
        codes.setdefault(name, int(value, 0))
    return codes


def input_events(client, n, timeout=5):
    """the next n input events that are not frame ends, and the frame ends seen on the way"""
    got, frames = [], 0
    for ev in client.events(timeout=timeout):
        assert ev["event"] == "input", ev
        if ev["kind"] == "frame":
            frames += 1
            continue
        got.append(ev)
        if len(got) == n:
            break
    return got, frames


def test_each_line_becomes_the_event_a_device_gives(daemon):
    codes = kernel_codes()
    with daemon.client() as c:
        c.request("add view front width=320 height=240 eye=0,1.2,3 target=0,1,0")
        assert c.subscribe("input") == {}
        # Shift+Z: at the kiosk's edit line a "Z" typed, nothing changed (Ctrl+Z would undo)
        lines = ["input motion 3 -2", "input button left down", "input motion 0.5 0.25",
                 "input button left up", "input key KEY_LEFTSHIFT down", "input key KEY_Z down",
                 "input key KEY_Z up", "input key KEY_LEFTSHIFT up", "input wheel -2",
                 "input pointer front 160.5 12", "input button side down"]
        for line in lines:
            assert c.request(line) == {"queued": True}, line
        evs, frames = input_events(c, len(lines))
        assert frames >= len(lines) - 1  # one frame end after each injected event
        assert [e["kind"] for e in evs] == ["motion", "button", "motion", "button", "key", "key",
                                            "key", "key", "wheel", "pointer", "button"]
        assert all(e["device"] == "socket" for e in evs)
        assert (evs[0]["dx"], evs[0]["dy"]) == (3, -2)
        assert (evs[2]["dx"], evs[2]["dy"]) == (0.5, 0.25)
        assert (evs[1]["code"], evs[1]["value"]) == (codes["BTN_LEFT"], 1)
        assert (evs[3]["code"], evs[3]["value"]) == (codes["BTN_LEFT"], 0)
        assert [(e["code"], e["value"]) for e in evs[4:8]] == [
            (codes["KEY_LEFTSHIFT"], 1), (codes["KEY_Z"], 1), (codes["KEY_Z"], 0),
            (codes["KEY_LEFTSHIFT"], 0)]
        assert evs[4]["name"] == "KEY_LEFTSHIFT" and evs[5]["name"] == "KEY_Z"
        assert evs[8]["axis"] == "vertical" and evs[8]["detents"] == -2 and evs[8]["hires"] == -240
        assert evs[9]["view"] == "front" and (evs[9]["x"], evs[9]["y"]) == (160.5, 12)
        assert evs[10]["code"] == codes["BTN_SIDE"]
        # times come from the daemon's monotonic clock, in order
        times = [e["t_us"] for e in evs]
        assert times == sorted(times) and times[0] > 0


def test_motion_in_pixels_keeps_the_fractions_and_the_raw_counts(daemon):
    """Motion is flat: pixels = counts * gain * 1000 / DPI (1000 for the socket), whole
    pixels out, the fractions kept; the raw counts stay beside them."""
    with daemon.client() as c:
        assert c.request("set input gain=2.5") == {"grab": False, "gain": 2.5, "held": 60}
        assert c.subscribe("input") == {}
        moves = [(3, -2), (0.3, 0.3), (0.3, -0.1), (0.3, 0.1), (-1, 0)]
        for dx, dy in moves:
            assert c.request(f"input motion {dx} {dy}") == {"queued": True}
        evs, _ = input_events(c, len(moves))
        assert [(e["dx"], e["dy"]) for e in evs] == [(dx, dy) for dx, dy in moves]
        # the rule in exact arithmetic: the carried fraction plus the new motion,
        # truncated toward zero (so small back-and-forth motion does not jitter)
        k = Fraction(5, 2)
        for axis, got in (("dx", [e["px"] for e in evs]), ("dy", [e["py"] for e in evs])):
            rem, want, given, total = Fraction(0), [], 0, Fraction(0)
            for e in evs:
                rem += k * Fraction(str(e[axis]))
                whole = int(rem)  # toward zero
                rem -= whole
                want.append(whole)
                given += whole
                total += k * Fraction(str(e[axis]))
                assert abs(given - total) < 1  # never a pixel or more from the exact sum
            assert got == want, axis


def test_kernel_key_names_are_taken_with_the_kernels_numbers(daemon):
    """Every KEY_ name of the header goes through as the header's number, but those the
    installed libevdev does not know yet (it lags the kernel's headers by a few new keys:
    with libevdev 1.13 and Linux 6.1's header, KEY_LINK_PHONE and a handful more); those
    are refused by name, and they are few."""
    codes = {n: v for n, v in kernel_codes().items()
             if n.startswith("KEY_") and v < 0x2ff and n != "KEY_RESERVED"}
    with daemon.client() as c:
        c.subscribe("input")
        taken, refused = [], []
        for name in sorted(codes):
            reply = c.request_reply(f"input key {name} down")
            if reply["ok"]:
                taken.append(name)
            else:
                assert reply["error"]["code"] == "bad-argument" and name in reply["error"]["message"]
                refused.append(name)
        evs, _ = input_events(c, len(taken), timeout=10)
        assert [e["code"] for e in evs] == [codes[n] for n in taken]
        assert len(refused) <= 0.03 * len(codes), refused
        assert "KEY_A" in taken and "KEY_LEFTCTRL" in taken and "KEY_ESC" in taken


@pytest.mark.parametrize("line,code", [
    ("input key KEY_NOSUCHKEY down", "bad-argument"),
    ("input key BTN_LEFT down", "bad-argument"),
    ("input button left maybe", "bad-argument"),
    ("input motion nan 0", "bad-number"),
    ("input motion 1 99999999", "bad-number"),
    ("input pointer nowhere 1 1", "not-found"),
    ("input pointer front 1 241", "bad-argument"),
    ("input wheel 0.5", "bad-number"),
    ("input valuator dial 1", "not-found"),
    ("input motion 1", "arity"),
])
def test_bad_lines_queue_nothing_and_change_nothing(daemon, line, code):
    with daemon.client() as c, daemon.client() as watcher:
        c.request("add view front width=320 height=240 eye=0,1.2,3 target=0,1,0")
        c.request("load human as jack")
        watcher.subscribe("input")
        before = snapshot(c)
        reply = c.request_reply(line)
        assert reply["ok"] is False and reply["error"]["code"] == code, reply
        assert snapshot(c) == before
        assert watcher.next_event(timeout=0.3) is None
        # and the connection still works
        assert c.request("input motion 1 1") == {"queued": True}
        assert watcher.next_event(timeout=5)["kind"] == "motion"


PANEL = ROOT / "tests" / "input" / "panel.map"


def test_valuators_by_the_panel_maps_names(daemon_factory):
    d = daemon_factory(extra=("--panel", str(PANEL)))
    with d.client() as c:
        c.subscribe("input")
        c.request("input valuator backrest -12.5")
        c.request("input valuator seat_height 40")
        evs, _ = input_events(c, 2)
        # the map's lines in order: seat_height 0, backrest 1
        assert [(e["valuator"], e["name"], e["value"], e["stale"]) for e in evs] == [
            (1, "backrest", -12.5, False), (0, "seat_height", 40, False)]


def test_a_bad_panel_map_stops_the_start_with_its_line(daemon_factory, tmp_path):
    bad = tmp_path / "bad.map"
    bad.write_text("axis 181 0-1le+ seat_height\naxis 9999 0 dial\n")
    d = daemon_factory(start=False, extra=("--panel", str(bad)))
    with pytest.raises(Exception):
        d.start(timeout=5)
    assert "bad.map:2" in d.log()
