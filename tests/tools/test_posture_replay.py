"""tools/posture-replay: replay tests pass as committed, and each kind of expectation fails
when the replay does not meet it (a hash, a site, a joint, a margin, a picture, a divergence);
--update rewrites them; a malformed expectations file is refused with file:line."""
import pathlib
import re
import shutil
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
TOOL = ROOT / "tools" / "posture-replay"
SUITE = ROOT / "tests" / "replays"


def run(*tests, update=False):
    argv = [sys.executable, str(TOOL), "run", *(["--update"] if update else []), *map(str, tests)]
    p = subprocess.run(argv, capture_output=True, text=True, timeout=300)
    return p.returncode, p.stdout


@pytest.fixture
def test_copy(tmp_path):
    """A copy of the suite's dial panel test (a joint, a picture, a posture)."""
    dest = tmp_path / "dial_panel"
    shutil.copytree(SUITE / "dial_panel", dest)
    return dest


def edit(test, old, new):
    path = test / "expect"
    text = path.read_text()
    assert re.search(old, text)
    path.write_text(re.sub(old, new, text, count=1))


def test_the_committed_test_passes_with_one_line_and_a_summary(test_copy):
    status, out = run(test_copy)
    assert status == 0, out
    assert re.match(r"PASS dial_panel \(\d+ frames, [\d.]+ s\)\n1 passed, 0 failed\n$", out)


@pytest.mark.parametrize("old, new, said", [
    (r"posture [0-9a-f]{16}", "posture 0123456789abcdef", r"expect:\d+: posture [0-9a-f]{16}, "
                                                          r"expected 0123456789abcdef"),
    (r"(knee_l) (\S+)", r"\1 0.6", r"expect:\d+: joint knee_l is"),
    (r"(picture front front.png)", r"\1\nat end margin human above 5", r"margin .* not above 5"),
])
def test_an_expectation_the_replay_does_not_meet_fails_saying_which(test_copy, old, new, said):
    edit(test_copy, old, new)
    status, out = run(test_copy)
    assert status == 1
    assert re.search(r"FAIL dial_panel: .*" + said, out), out
    assert out.endswith("0 passed, 1 failed\n")


def test_a_picture_unlike_its_golden_one_fails(test_copy):
    # the golden picture of another session
    shutil.copyfile(SUITE / "snapping" / "front.png", test_copy / "front.png")
    status, out = run(test_copy)
    assert status == 1 and "view front differs from front.png by" in out, out


def test_a_site_off_by_a_millimetre_fails(tmp_path):
    dest = tmp_path / "hand"
    shutil.copytree(SUITE / "fig_5_9_move_hand", dest)
    text = (dest / "expect").read_text()
    m = re.search(r"site human hand_r.palm (\S+)", text)
    moved = text.replace(m[1], repr(float(m[1]) + 0.001), 1)
    (dest / "expect").write_text(moved)
    status, out = run(dest)
    assert status == 1 and "site hand_r.palm at" in out, out


def test_a_recording_that_diverges_fails(test_copy):
    frames = test_copy / "recording" / "frames"
    log = frames.read_text().splitlines()
    i = next(k for k, ln in enumerate(log) if ln.startswith("fig 0 "))
    log[i] = "fig 0 0000000000000000"
    p = next(k for k, ln in enumerate(log) if k > i and ln.startswith("posture "))
    log[p] = re.sub(r"[0-9a-f]{16}$", "0000000000000001", log[p])
    frames.write_text("\n".join(log) + "\n")
    status, out = run(test_copy)
    assert status == 1 and "diverged from its recording" in out, out


def test_update_rewrites_what_was_measured(test_copy):
    edit(test_copy, r"posture [0-9a-f]{16}", "posture 0123456789abcdef")
    edit(test_copy, r"(knee_l) (\S+)", r"\1 0.6")
    status, out = run(test_copy, update=True)
    assert status == 0 and "updated" in out, out
    assert run(test_copy)[0] == 0
    assert "0123456789abcdef" not in (test_copy / "expect").read_text()


@pytest.mark.parametrize("text, said", [
    ("posture-replay 2\nat end posture 0123456789abcdef\n", r"expect:1: the first line"),
    ("posture-replay 1\nat end posture xyz\n", r"expect:2: posture HASH"),
    ("posture-replay 1\nat noon posture 0123456789abcdef\n", r"expect:2: the point"),
    ("posture-replay 1\nat end joint human\n", r"expect:2: joint takes"),
    ("posture-replay 1\n# nothing\n", r"expect: no expectations"),
])
def test_a_malformed_expectations_file_is_refused_with_file_and_line(test_copy, text, said):
    (test_copy / "expect").write_text(text)
    status, out = run(test_copy)
    assert status == 1 and re.search(said, out), out
