"""The replay suite: every folder here with recording/ and expect is one test
(posture.pytest_replay); tests/replays/make_replays.py made them."""
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "tools"))

pytest_plugins = ["posture.pytest_replay"]
