"""tests/input/hid: the committed .expect files and hid-tools recordings are
what hid-tools says today.

tests/test_hid.c checks our HID decoder against the .expect files, which
make_expect.py writes by asking hid-tools (an independent decoder) for the
field values of a set of reports, and reads two recordings hid-tools'
own writer made. Here the script runs again into a temporary folder and
every file must come out the same, so the C test never checks against
stale or hand-edited answers.
"""
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "input" / "hid"
SCRIPT = DATA / "make_expect.py"

pytest.importorskip("hidtools")


@pytest.fixture(scope="module")
def fresh(tmp_path_factory):
    out = tmp_path_factory.mktemp("hid")
    subprocess.run([sys.executable, str(SCRIPT), str(out)], check=True, capture_output=True)
    return out


def committed():
    return sorted(p.name for p in DATA.iterdir() if p.suffix in (".expect", ".hid"))


def test_every_descriptor_has_its_expect_file():
    rdesc = {p.stem for p in DATA.glob("*.rdesc")}
    expect = {p.stem for p in DATA.glob("*.expect")}
    assert rdesc == expect


@pytest.mark.parametrize("name", committed())
def test_committed_file_is_what_hidtools_says(fresh, name):
    new = (fresh / name).read_text()
    old = (DATA / name).read_text()
    assert new == old, f"{name} differs from what hid-tools gives now: run {SCRIPT.name}"


def test_hidtools_reads_its_recording_back():
    """the recordings parse with hid-tools' own descriptor reader"""
    from hidtools.hid import ReportDescriptor

    for name in ("hidtools_mouse.hid", "hidtools_two.hid"):
        lines = (DATA / name).read_text().splitlines()
        rdescs = [line for line in lines if line.startswith("R: ")]
        assert rdescs
        for line in rdescs:
            fields = line.split()[1:]
            size, data = int(fields[0]), [int(x, 16) for x in fields[1:]]
            assert size == len(data)
            assert ReportDescriptor.from_bytes(data).input_reports
