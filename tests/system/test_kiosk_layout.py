"""The kiosk's screen shared by several views (issue 14): `layout` tiles them on the screen
(--screen here, the framebuffer's size on a kiosk) above the message band, each resized to
its tile; the pointer is the screen's and moves across the tiles; the layout is part of the
session and survives a kill. The tiles are worked out here from the grid's rule."""
import pytest

from daemon import daemon_factory  # noqa: F401 (fixture)


def test_layout_tiles_the_views_and_the_pointer_crosses_them(daemon_factory):
    d = daemon_factory(extra=["--screen", "1282x760"])
    with d.client() as c:
        for name in ("front", "side", "top"):
            c.request(f"add view {name} width=320 height=240 eye=0,1,3 target=0,1,0")
        reply = c.request("layout front side")
        # 1282 - 2 px gap = 2 x 640; 760 - 40 px band = 720 high
        assert reply["screen"] == [1282, 760]
        assert reply["tiles"] == [{"view": "front", "x": 0, "y": 0, "width": 640, "height": 720},
                                  {"view": "side", "x": 642, "y": 0, "width": 640, "height": 720}]
        sizes = {v["name"]: (v["width"], v["height"]) for v in c.request("list views")["views"]}
        assert sizes == {"front": (640, 720), "side": (640, 720), "top": (320, 240)}
        # the pointer from the screen's top left: 700 px right is 58 px into side
        c.request("input motion 700 10")
        assert c.request("get kiosk")["pointer"] == {"view": "side", "x": 58.0, "y": 10.0}
        c.request("input motion -680 5")  # back into front, at 20 px
        assert c.request("get kiosk")["pointer"] == {"view": "front", "x": 20.0, "y": 15.0}
        c.request("input motion 621 0")  # 641: the gap; the views keep the last pixel
        assert c.request("get kiosk")["pointer"]["view"] == "front"
        three = c.request("layout front side top")["tiles"]
        assert [(t["x"], t["y"], t["width"], t["height"]) for t in three] == [
            (0, 0, 640, 359), (642, 0, 640, 359), (0, 361, 640, 359)]
        for bad in ("layout front front", "layout nowhere", "layout"):
            assert not c.request_reply(bad)["ok"], bad
    d.kill9()
    d.start()
    with d.client() as c:
        assert c.request("get layout")["views"] == ["front", "side", "top"]
        c.request("delete view side")
        assert c.request("get layout")["views"] == ["front", "top"]
        assert c.request("layout off")["tiles"] == []
        assert c.request("get layout")["views"] == []
