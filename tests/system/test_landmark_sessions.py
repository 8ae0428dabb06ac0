"""What a user kept before every human carried its landmark sites still loads as it was.

tests/sessions/landmarks holds a session file and two state directories written by the
daemon of before (tests/sessions/landmarks/README.md says how): a journal left by kill -9,
and a snapshot left by a clean stop. Their human jack has a hand held on each of two
sites (kept then as site indices, which the landmarks moved), a site moved on its segment
and a constraint between two sites; after loading, each is the site it was named.
"""
import shutil

import pytest

from daemon import ROOT, daemon_factory  # noqa: F401  (the fixture)

KEPT = ROOT / "tests" / "sessions" / "landmarks"


def behave_line(text):
    return next(line for line in text.splitlines() if line.startswith("behave jack "))


def check_jack(c, state_dir, root):
    """jack as kept: the hands' sites (through a session written now), the moved site,
    the constraint, the root; and the landmarks every human now has."""
    c.request("save session now.session")
    text = (state_dir / "now.session").read_text()
    assert behave_line(text).endswith(" hand_l=head.vertex hand_r=T5.chest")
    assert "\nsite jack hand_r.palm 0,-0.059999999999999998,0.01,0,0,0,1\n" in text
    assert f"\nroot jack {root} " in text
    look = next(line for line in text.splitlines() if line.startswith("constraint look "))
    assert " effector=head.between_eyes " in look and " goalsite=hand_r.palm " in look
    params = c.request("get behavior jack")["parameters"]
    assert params["hand_l"] == params["hand_r"] == "site"
    assert c.request("get site jack clavicle_r.acromion")["position"][1] > 1.2


@pytest.mark.parametrize("kept,root", [("killed", "toes_r.toe"), ("stopped", "toes_l.toe")])
def test_a_state_directory_of_before_recovers(daemon_factory, kept, root):  # noqa: F811
    d = daemon_factory(start=False)
    for f in (KEPT / kept).iterdir():
        shutil.copy(f, d.state_dir / f.name)
    d.start()
    with d.client() as c:
        assert [f["name"] for f in c.request("list figures")["figures"]] == ["jack"]
        check_jack(c, d.state_dir, root)


def test_a_session_file_of_before_loads(daemon_factory):  # noqa: F811
    d = daemon_factory()
    shutil.copy(KEPT / "saved.session", d.state_dir / "saved.session")
    with d.client() as c:
        c.request("load session saved.session")
        check_jack(c, d.state_dir, "toes_r.toe")
