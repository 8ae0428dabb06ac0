"""Golden transcripts of kiosk sessions: tests/kiosk/*.txt give what a person
did (`<` lines: socket lines, `type TEXT` typed on a US keyboard, `key NAME` pressed and
released, `chord A B` held together) and what the journal must hold for it (`>` lines: the
command records `C LINE`, `*` at the end of a line matching any rest, and the step marks
`B`, `E`, `A`; posture records are the solver's and not compared)."""

import pytest

from daemon import ROOT, daemon_factory, journal_records  # noqa: F401 (fixture)
from kiosk_keys import press, type_text

TRANSCRIPTS = sorted((ROOT / "tests" / "kiosk").glob("*.txt"))


def parse(path):
    steps, expected = [], []
    for n, line in enumerate(path.read_text().splitlines(), 1):
        if line.startswith("< "):
            steps.append((n, line[2:]))
        elif line.startswith("> "):
            expected.append(line[2:])
        elif line.strip() and not line.startswith("#"):
            raise AssertionError(f"{path.name}:{n}: not a transcript line: {line!r}")
    return steps, expected


def journaled(state_dir):
    """the journal's command records and step marks, in order"""
    out = []
    for _, kind, body in journal_records(state_dir):
        if kind == "C":
            out.append(f"C {body}")
        elif kind in "BEA":
            out.append(kind)
    return out


def matches(got, want):
    if want.endswith("*"):
        return got.startswith(want[:-1])
    return got == want


@pytest.mark.parametrize("path", TRANSCRIPTS, ids=[p.stem for p in TRANSCRIPTS])
def test_kiosk_transcript(daemon_factory, path):
    steps, expected = parse(path)
    d = daemon_factory()
    with d.client() as c:
        for n, step in steps:
            if step.startswith("type "):
                type_text(c, step[5:])
            elif step.startswith("key "):
                press(c, step[4:])
            elif step.startswith("chord "):
                press(c, *step[6:].split())
            else:
                reply = c.request_reply(step)
                assert reply["ok"], f"{path.name}:{n}: {step}: {reply}"
        c.request("status")  # every event taken in before the journal is read
    got = journaled(d.state_dir)
    assert len(got) == len(expected) and all(map(matches, got, expected)), (
        f"{path.name}: the journal holds\n  " + "\n  ".join(got) +
        "\nnot\n  " + "\n  ".join(expected))
