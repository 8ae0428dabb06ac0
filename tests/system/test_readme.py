"""The README as a newcomer reads it: its picture is what `make run` shows today.

docs/kiosk.png is drawn by tools/readme-picture (the daemon started as the Makefile's
`run` target starts it, the menu opened by a right click on the background); this test
draws it again and compares.
"""
import os
import subprocess

import numpy as np

from conftest import BUILD, ROOT
from posture.replay import read_png

PICTURE = ROOT / "docs" / "kiosk.png"
# the status line's frame count, frame rate and times differ from run to run: the last
# band (VIEW_LINE_PX rows) is compared only over the view's name at its left
STATUS_ROWS, NAME_COLUMNS = 20, 48
# On this machine two drawings are the same to the bit outside those numbers. A channel
# off by more than 24 counts in more than 200 pixels is another picture: the right elbow
# turned 5 degrees changes 857 such pixels, the message line's "right" written "left"
# 773, the pointer 10 pixels to the right 34 000; the margin is for the few edge pixels
# another CPU's llvmpipe may draw otherwise.
COUNTS, PIXELS = 24, 200


def pixels(path):
    w, h, ch, data = read_png(path)
    return np.frombuffer(data, np.uint8).reshape(h, w, ch)[:, :, :3].astype(int)


def differing_pixels(a, b):
    """pixels with a channel off by more than COUNTS, the status line's numbers left out"""
    off = np.abs(a - b).max(axis=2) > COUNTS
    off[-STATUS_ROWS:, NAME_COLUMNS:] = False
    return int(off.sum())


def test_the_readme_picture_is_what_make_run_shows_now():
    out = BUILD / "test-output" / "readme" / "kiosk.png"
    env = dict(os.environ, POSTURE_BUILD=str(BUILD))
    p = subprocess.run([str(ROOT / "tools" / "readme-picture"), "--out", str(out)], env=env,
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stdout + p.stderr
    new, committed = pixels(out), pixels(PICTURE)
    how = (f"run tools/readme-picture to draw docs/kiosk.png again, look at it, and commit "
           f"it (this run's picture: {out})")
    assert new.shape == committed.shape, f"docs/kiosk.png is {committed.shape}, the daemon " \
        f"draws {new.shape}: {how}"
    n = differing_pixels(new, committed)
    assert n <= PIXELS, f"docs/kiosk.png is not what the daemon draws now ({n} pixels " \
        f"differ): {how}"
