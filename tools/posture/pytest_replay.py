"""A pytest plugin: every folder holding recording/ and expect under the collected paths is
one test, run as `posture-replay run` runs it (posture.replay). Enable it with
``-p posture.pytest_replay`` and tools/ on the path, as `make test` does:
``PYTHONPATH=tools python -m pytest -p posture.pytest_replay tests/replays``."""
import pytest

from posture.replay import run_test


def pytest_collect_file(parent, file_path):
    if file_path.name == "expect" and (file_path.parent / "recording").is_dir():
        return ReplayFile.from_parent(parent, path=file_path)
    return None


class ReplayFile(pytest.File):
    def collect(self):
        yield ReplayItem.from_parent(self, name=self.path.parent.name)


class ReplayFailure(Exception):
    pass


class ReplayItem(pytest.Item):
    def runtest(self):
        result = run_test(self.path.parent)
        if not result.passed:
            raise ReplayFailure("\n".join(result.failures))

    def repr_failure(self, excinfo, style=None):
        if isinstance(excinfo.value, ReplayFailure):
            return "replay test %s failed:\n%s" % (self.name, excinfo.value)
        return super().repr_failure(excinfo, style)

    def reportinfo(self):
        return self.path, 0, "replay: %s" % self.name
