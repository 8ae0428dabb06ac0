"""The kiosk's keyboard end to end: keys typed over the socket as a keyboard
gives them (`input key` lines, a US layout) reach the edit line when no mode takes them;
Enter runs the line as a command, journaled like a client's; Tab completes; the
change-view key, undo and redo; a value typed during a manipulation. Pictures of the edit
line go to the test output."""
import pytest

from daemon import daemon, daemon_factory, write_picture  # noqa: F401 (fixtures)
from kiosk_keys import press, type_text


def names(c):
    return [f["name"] for f in c.request("list figures")["figures"]]


def test_a_typed_line_runs_and_is_journaled(daemon):
    with daemon.client() as c:
        c.request("add view front width=480 height=240 eye=0,1,3 target=0,1,0")
        type_text(c, "load human as bob")
        assert c.request("get kiosk")["line"] == "load human as bob"
        write_picture(c, "front", "kiosk_edit_line.png")
        press(c, "KEY_ENTER")
        assert names(c) == ["bob"]
        assert c.request("get kiosk")["line"] == ""
        # a refused line says why on the message line, and changes nothing
        type_text(c, "set joint bob knee_l 500deg", enter=True)
        c.request("get kiosk")
        write_picture(c, "front", "kiosk_refused.png")
    daemon.kill9()
    daemon.start()
    with daemon.client() as c:
        assert names(c) == ["bob"]


def test_tab_completes_verbs_objects_and_names(daemon):
    with daemon.client() as c:
        c.request("load human as bob")
        type_text(c, "manip")
        press(c, "KEY_TAB")
        assert c.request("get kiosk")["line"] == "manipulate "
        type_text(c, "fi")
        press(c, "KEY_TAB")
        type_text(c, "b")
        press(c, "KEY_TAB")
        assert c.request("get kiosk")["line"] == "manipulate figure bob "
        press(c, "KEY_ESC")
        type_text(c, "get site bob hand_r.pa")
        press(c, "KEY_TAB")
        assert c.request("get kiosk")["line"] == "get site bob hand_r.palm "


def test_the_change_view_key_undo_and_redo(daemon):
    with daemon.client() as c:
        c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
        c.request("load human as bob")
        press(c, "KEY_V")  # at the edit line V is a letter
        assert c.request("get kiosk")["line"] == "v"
        press(c, "KEY_ESC")
        press(c, "KEY_F2")  # change view: a left drag sweeps the camera
        c.request("input pointer front 160 120")
        c.request("input button left down")
        c.request("input motion 40 0")
        c.request("input button left up")
        press(c, "KEY_ESC")
        eye = c.request("list views")["views"][0]["eye"]
        assert eye[0] > 0.5, eye
        assert c.request("get kiosk")["line"] == ""
        # Ctrl+Z takes the last change back (the sweep), Ctrl+Y does it again
        press(c, "KEY_LEFTCTRL", "KEY_Z")
        assert c.request("list views")["views"][0]["eye"] == pytest.approx([0, 1, 3], abs=1e-12)
        press(c, "KEY_LEFTCTRL", "KEY_Y")
        assert c.request("list views")["views"][0]["eye"] == pytest.approx(eye, abs=1e-12)
        press(c, "KEY_LEFTCTRL", "KEY_Z")
        press(c, "KEY_LEFTCTRL", "KEY_Z")  # and the figure
        assert names(c) == []


def test_a_value_typed_during_a_drag_moves_g_exactly(daemon):
    with daemon.client() as c:
        c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
        c.request("load human as bob")
        c.request("manipulate figure bob")
        g0 = c.request("get manip")["position"]
        c.request("input button left down")  # x, the active axis
        type_text(c, "12.5cm")
        kiosk = c.request("get kiosk")
        assert kiosk["value"] is True and kiosk["line"] == "12.5cm"
        write_picture(c, "front", "kiosk_value.png")
        press(c, "KEY_ENTER")
        g = c.request("get manip")["position"]
        assert g[0] - g0[0] == pytest.approx(0.125, abs=1e-12)
        assert g[1:] == pytest.approx(g0[1:], abs=1e-12)
        # ESC drops a value being typed, and the mode stays; the next ESC ends it
        type_text(c, "3")
        press(c, "KEY_ESC")
        assert c.request("get manip")["mode"] == "figure"
        assert c.request("get manip")["position"] == g
        c.request("input button left up")
        press(c, "KEY_ESC")
        assert c.request("get manip")["mode"] == "none"
        c.request("undo")  # the drag with its typed value was one step
        root = c.request("show figure bob")["root"]
        assert c.request(f"get site bob {root}")["position"] == pytest.approx(g0, abs=1e-12)


def test_the_configured_layout_types_its_own_characters(daemon):
    """`set kiosk keymap=de`: the German keyboard's keys (xkb-data symbols/de: Y and Z
    swapped, AD11 ü); the edit line holds UTF-8, drawn a '?' a character (the font is ASCII)"""
    with daemon.client() as c:
        c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
        assert c.request("set kiosk keymap=de")["keymap"] == "de"
        press(c, "KEY_LEFTBRACE")
        press(c, "KEY_Y")
        k = c.request("get kiosk")
        assert k["line"] == "\u00fcz" and k["cursor"] == 3  # bytes: ü is two
        write_picture(c, "front", "kiosk_de.png")
        press(c, "KEY_ESC")
        assert c.request("set kiosk keymap=us")["keymap"] == "us"
