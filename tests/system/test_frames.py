"""The views' pictures off the loop: `--frames DIR` files written by the frame writer, the
counters `status` reports, no pictures while nothing changes, and input starting a frame
at once when the loop is idle."""
import base64
import struct
import time
import zlib

import numpy as np

from daemon import daemon, daemon_factory  # noqa: F401 (fixtures)

VIEW = "add view main width=320 height=240 eye=1.9,1.55,3.1 target=0,0.95,0"


def decode_png(data):
    """An 8-bit RGBA, non-interlaced PNG (what the daemon writes) as an h x w x 4 array."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, ihdr = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        assert zlib.crc32(kind + body) == struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])[0]
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
        pos += 12 + n
    w, h, depth, color, _, _, interlace = ihdr
    assert (depth, color, interlace) == (8, 6, 0), ihdr
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(h, 1 + 4 * w)
    out = np.zeros((h, 4 * w), dtype=np.int32)
    for y in range(h):
        f, line = raw[y, 0], raw[y, 1:].astype(np.int32)
        up = out[y - 1] if y else np.zeros(4 * w, dtype=np.int32)
        if f in (0, 2):
            out[y] = (line + (up if f == 2 else 0)) & 0xFF
            continue
        row = np.zeros(4 * w, dtype=np.int32)
        for x in range(4 * w):  # sub, average, Paeth: each byte needs the one left of it
            a = row[x - 4] if x >= 4 else 0
            b, c = up[x], up[x - 4] if x >= 4 else 0
            if f == 1:
                pred = a
            elif f == 3:
                pred = (a + b) // 2
            else:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else b if pb <= pc else c
            row[x] = (line[x] + pred) & 0xFF
        out[y] = row
    return out.reshape(h, w, 4).astype(np.uint8)


def wait_for(pred, timeout=20.0, what="condition"):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = pred()
        if value:
            return value
        time.sleep(0.05)
    raise AssertionError(f"{what} not met after {timeout} s")


def settled_written(c, quiet=1.0, timeout=30.0):
    """frames_written once it has stayed put for `quiet` seconds (the human has settled)."""
    deadline = time.monotonic() + timeout
    last, since = c.request("status")["frames_written"], time.monotonic()
    while time.monotonic() < deadline:
        time.sleep(0.2)
        now = c.request("status")["frames_written"]
        if now != last:
            last, since = now, time.monotonic()
        elif time.monotonic() - since >= quiet:
            return now
    raise AssertionError("the pictures never stopped changing")


def test_frames_dir_gets_the_views_picture(daemon_factory, tmp_path):
    frames = tmp_path / "frames"
    frames.mkdir()
    d = daemon_factory(frames=frames)
    path = frames / "main.png"
    with d.client() as c:
        c.request("load human as jack")
        c.request(VIEW)
        wait_for(lambda: path.exists(), what="main.png")
        img = decode_png(path.read_bytes())
        assert img.shape == (240, 320, 4)
        assert (img[:, :, 3] == 255).all(), "every pixel opaque"
        assert len(np.unique(img.reshape(-1, 4), axis=0)) > 50, "a picture, not a fill"

        # once settled, the same view drawn now by request: the file is that picture
        # above the status and message lines (which count frames, echo the request)
        settled_written(c)
        c.request("render view main to=now.png")
        now = decode_png((d.state_dir / "now.png").read_bytes())
        img = decode_png(path.read_bytes())
        top = slice(0, 240 * 4 // 5)
        differ = (np.abs(img[top].astype(int) - now[top].astype(int)).max(axis=2) > 8).mean()
        assert differ < 0.001, f"{differ:.2%} of the pixels differ from the view drawn now"

        s = c.request("status")
        assert s["frames_written"] >= 1
        assert s["frames_dropped"] >= 0
        assert isinstance(s["stall_max_us"], int) and s["stall_max_us"] >= 0
        assert isinstance(s["stall_cpu_max_us"], int) and s["stall_cpu_max_us"] >= 0
        assert s["draw_us"] > 0

        # a change is written: a new picture, one more frame written
        before = s["frames_written"]
        c.request("set camera main eye=-1.9,1.55,3.1 target=0,0.95,0")
        wait_for(lambda: c.request("status")["frames_written"] > before, what="a new picture")
        moved = decode_png(path.read_bytes())
        assert (moved != img).any()
    d.stop()
    # the atomic replacement leaves no temporary file behind
    assert sorted(p.name for p in frames.iterdir()) == ["main.png"]


def test_frame_events_carry_the_views_picture(daemon):
    """`subscribe frame`: the PNG is made off the loop and still comes, whole, per change."""
    with daemon.client() as c:
        c.request("load human as jack")
        c.request(VIEW)
        c.subscribe("frame")
        seen = []
        for eye in ("-1.9,1.55,3.1", "0,1.5,3.5"):
            c.request(f"set camera main eye={eye} target=0,0.95,0")
            deadline = time.monotonic() + 20
            while time.monotonic() < deadline:
                ev = c.next_event(timeout=1)
                if ev and ev["event"] == "frame":
                    break
            else:
                raise AssertionError("no frame event after the camera moved")
            assert (ev["view"], ev["width"], ev["height"]) == ("main", 320, 240)
            img = decode_png(base64.b64decode(ev["png"]))
            assert img.shape == (240, 320, 4)
            assert (img[:, :, 3] == 255).all()
            seen.append(img)
            time.sleep(0.2)  # at most 10 frame events a second
            c.pending_events()
        assert (seen[0] != seen[1]).any(), "the second picture shows the moved camera"
        assert c.request("status")["frames_written"] >= 2


def test_no_pictures_while_nothing_changes(daemon_factory, tmp_path):
    frames = tmp_path / "frames"
    frames.mkdir()
    d = daemon_factory(frames=frames)
    with d.client() as c:
        c.request("load human as jack")
        c.request(VIEW)
        written = settled_written(c)
        f0 = c.request("status")["frame"]
        time.sleep(1.0)
        s = c.request("status")
        assert s["frames_written"] == written
        # idle: a slow tick for what waits on time, and a frame for each status request,
        # far from the 60 a second of a loop at work
        assert s["frame"] - f0 < 20, (f0, s["frame"])


def test_input_starts_a_frame_when_idle(daemon_factory):
    # one tick a second: frames counted within a few replies are the ones input started
    d = daemon_factory(fps=1)
    with d.client() as c:
        c.request(VIEW)
        for dx in (3, -3):
            time.sleep(1.2)  # a tick without change: the loop is idle
            f0 = c.request("status")["frame"]  # a frame after this reply (a request came)
            c.request(f"input motion {dx} 0")  # and one at once for the motion
            f1 = c.request("status")["frame"]
            assert f1 - f0 >= 2, (f0, f1)
