"""The pop-up menu of commands: a mouse button on the background with no mode
opens it at the pointer; typing filters it, the keys and the pointer move its highlight;
a choice goes on as the command typed, its missing arguments asked for; ESC closes it and
nothing changes. A button on a figure opens nothing."""
from daemon import daemon, daemon_factory, write_picture  # noqa: F401 (fixtures)
from kiosk_keys import press, type_text


def kiosk(c):
    return c.request("get kiosk")


def test_the_menu_opens_on_the_background_filters_and_its_choice_asks_the_rest(daemon):
    with daemon.client() as c:
        c.request("add view front width=640 height=480 eye=0,1,3 target=0,1,0")
        c.request("load human as bob")
        assert c.request("pick front 20 20")["hit"] is None  # the sky: background
        c.request("input pointer front 20 20")
        c.request("input button right down")
        c.request("input button right up")
        menu = kiosk(c)["menu"]
        assert menu is not None and menu["filter"] == ""
        write_picture(c, "front", "kiosk_menu.png")
        type_text(c, "manipulate j")
        menu = kiosk(c)["menu"]
        assert menu["filter"] == "manipulate j" and menu["highlighted"] == "manipulate joint"
        write_picture(c, "front", "kiosk_menu_filtered.png")
        press(c, "KEY_ENTER")
        k = kiosk(c)
        assert k["menu"] is None
        assert k["prompt"] == {"line": "manipulate joint", "question": "select a figure"}
        type_text(c, "bob", enter=True)
        type_text(c, "knee_l", enter=True)
        assert c.request("get manip")["mode"] == "joint"


def test_esc_closes_it_and_a_figure_under_the_pointer_opens_nothing(daemon):
    with daemon.client() as c:
        c.request("add view front width=640 height=480 eye=0,1,3 target=0,1,0")
        c.request("load human as bob")
        before = c.request("get posture bob")
        c.request("input pointer front 20 20")
        c.request("input button left down")
        c.request("input button left up")
        assert kiosk(c)["menu"] is not None
        press(c, "KEY_DOWN")
        press(c, "KEY_ESC")
        assert kiosk(c)["menu"] is None and kiosk(c)["prompt"] is None
        assert c.request("get posture bob") == before
        # the middle of the figure: a click there is no menu
        hit = None
        for y in range(150, 350, 10):
            if c.request(f"pick front 320 {y}")["hit"]:
                hit = y
                break
        assert hit is not None
        c.request(f"input pointer front 320 {hit}")
        c.request("input button left down")
        c.request("input button left up")
        assert kiosk(c)["menu"] is None
