"""The kiosk's screen shared by several views: `layout` tiles them on the screen
(--screen here, the framebuffer's size on a kiosk) above one band for the message and
status lines, each view resized to its tile; the pointer is the screen's and moves across
the tiles; the layout is part of the session and survives a kill; `render screen` is what
the framebuffer shows. The tiles are worked out here from the grid's rule."""
import base64
import os
import pathlib

import pytest

from daemon import daemon_factory  # noqa: F401 (fixture)
from test_manip import png_pixels


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


def test_render_screen_composes_the_tiles(daemon_factory):
    """`render screen` is what the framebuffer shows: each view's picture in its tile (the
    middle of each tile compared with the view rendered alone), the gap between them the
    bands' dark blue, the band across the bottom with the kiosk's lines; without a layout,
    the first view."""
    d = daemon_factory(extra=["--screen", "642x300"])
    with d.client() as c:
        c.request("load human as bob")
        c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
        c.request("add view side width=320 height=240 eye=3,1,0.2 target=0,1,0")
        alone = c.request("render screen")
        assert (alone["width"], alone["height"]) == (320, 240)
        c.request("layout front side")
        shot = c.request("render screen")
        assert (shot["width"], shot["height"]) == (642, 300)
        data = base64.b64decode(shot["png"])
        out = pathlib.Path(os.environ.get("POSTURE_BUILD", "build/rel")) / "test-output"
        out.mkdir(parents=True, exist_ok=True)
        (out / "kiosk_screen.png").write_bytes(data)
        w, h, px = png_pixels(data)
        assert all(px[y][320][:3] == (20, 24, 32) and px[y][321][:3] == (20, 24, 32)
                   for y in range(0, 260, 7))
        # the band: dark ground across the whole width, with the status line's light text
        band = [px[y][x][:3] for y in range(260, 300) for x in range(642)]
        assert band.count((20, 24, 32)) > len(band) // 2
        assert any(min(p) > 180 for p in band)
        for name, x0 in (("front", 0), ("side", 322)):
            _, _, view = png_pixels(base64.b64decode(c.request(f"render view {name}")["png"]))
            for y in range(100, 160, 3):
                for x in range(120, 200, 3):
                    assert px[y][x0 + x] == view[y][x], (name, x, y)



def test_frame_files_hold_the_screen_of_a_layout(daemon_factory, tmp_path):
    """with a layout, --frames also gets screen.png: the screen as the framebuffer shows it"""
    import time
    frames = tmp_path / "frames"
    d = daemon_factory(frames=str(frames), extra=["--screen", "642x300"])
    with d.client() as c:
        c.request("add view front width=320 height=240 eye=0,1,3 target=0,1,0")
        c.request("add view side width=320 height=240 eye=3,1,0.2 target=0,1,0")
        c.request("layout front side")
        c.request("load human as bob")
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline and not (frames / "screen.png").exists():
            time.sleep(0.05)
        w, h, px = png_pixels((frames / "screen.png").read_bytes())
        assert (w, h) == (642, 300)
        assert px[150][320][:3] == (20, 24, 32)  # the gap
        assert (frames / "front.png").exists() and (frames / "side.png").exists()
