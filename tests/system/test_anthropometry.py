"""The human measured as ANSUR II measured people (get anthropometry, posture-figure measures)
and built from measures (posture-figure --measure), against the data itself.

The landmark offsets and the mean ratios a build uses come from ANSUR II by
tools/ansur2_landmarks.py; here that script's numbers are compared with the built figures.
"""
import csv
import pathlib
import subprocess
import sys

import numpy as np
import pytest

from conftest import FIGURES, ROOT, run_tool
from daemon import daemon, daemon_factory  # noqa: F401 (fixtures)

DATA = ROOT / "data" / "ansur2"
MEASURES = ("stature acromialheight wristheight trochanterionheight kneeheightmidpatella "
            "lateralmalleolusheight sittingheight eyeheightsitting acromionradialelength "
            "radialestylionlength handlength footlength buttockkneelength kneeheightsitting "
            "poplitealheight biacromialbreadth hipbreadth span thumbtipreach weightkg").split()


def script_output():
    """tools/ansur2_landmarks.py's numbers: {sex: {name: value}} (offsets and ratios together)"""
    out = subprocess.run([sys.executable, str(ROOT / "tools" / "ansur2_landmarks.py")],
                         capture_output=True, text=True, check=True, timeout=120).stdout
    values, sex = {}, None
    for line in out.splitlines():
        if not line.startswith(" "):
            sex = line.split()[0].rstrip(",")
            values.setdefault(sex, {})
            continue
        name, v = line.split()
        values[sex][name] = float(v)
    return values


def subjects(sex):
    """The subjects of one file, each {measure: value} (weightkg in kg)"""
    with open(DATA / f"ANSUR_II_{sex.upper()}_Public.csv", encoding="latin-1", newline="") as f:
        rows = [{k: float(r[k]) for k in MEASURES} for r in csv.DictReader(f)]
    for r in rows:
        r["weightkg"] /= 10
    return rows


def measure_args(sex, measures):
    args = ["--human", "--sex", sex]
    for k, v in measures.items():
        args += ["--measure", f"{k}={v!r}"]
    return args


def measured(*args):
    """posture-figure ... measures -> {name: value}"""
    lines = run_tool(*args, "measures").splitlines()
    return {k: float(v) for k, v in (line.split() for line in lines)}


def sites(*args):
    """posture-figure ... sites -> {site: (x, y, z)} in the built posture"""
    out = {}
    for line in run_tool(*args, "sites").splitlines()[1:]:
        f = line.split()
        out[f[0]] = tuple(float(v) for v in f[1:4])
    return out


@pytest.mark.parametrize("sex", ["male", "female"])
def test_landmark_offsets_are_the_datas(sex):
    """Today's figure (no measures) carries its landmarks at the offsets the script derives
    from ANSUR II (the C tables hold them to 4 decimals of stature)."""
    want = script_output()[sex]
    s = sites("--human", "--sex", sex)
    h = s["head.vertex"][1]

    def x(site):
        return s[site][0]

    def y(site):
        return s[site][1]

    def z(site):
        return s[site][2]

    # the right side's landmarks (x < 0): offsets outwards are -x
    got = {
        "acromion_y": y("clavicle_r.acromion") - y("upperarm_r.origin"),
        "acromion_x": x("upperarm_r.origin") - x("clavicle_r.acromion"),
        "stylion_z": z("forearm_r.stylion") - z("hand_r.origin"),
        "seat": y("pelvis.root") - y("pelvis.ischial_tuberosity_r"),
        "midpatella_y": y("thigh_r.midpatella") - y("shank_r.origin"),
        "suprapatella": z("thigh_r.suprapatella") - z("shank_r.origin"),
        "popliteal": z("shank_r.origin") - z("thigh_r.popliteal"),
        "buttock": z("pelvis.root") - z("pelvis.buttock_r"),
        "shoulder_blade": z("upperarm_r.origin") - z("clavicle_r.shoulder_blade"),
        "trochanterion_x": -x("thigh_r.trochanterion"),
        "tibiale_y": y("shank_r.tibiale") - y("shank_r.origin"),
        "iliocristale_y": y("pelvis.iliocristale_r") - y("pelvis.root"),
        "iliocristale_x": -x("pelvis.iliocristale_r"),
        "malleolus_x": x("foot_r.origin") - x("shank_r.lateral_malleolus"),
        "tragion_y": h - y("head.tragion_r"),
        "tragion_x": -x("head.tragion_r"),
    }
    assert set(got) <= set(want)
    for k, v in got.items():
        assert abs(v - want[k] * h) < 0.5e-4 * h, (k, v / h, want[k])


@pytest.mark.parametrize("sex", ["male", "female"])
def test_posture_figure_predicts_what_is_not_given_as_the_daemon_does(daemon, sex):  # noqa: F811
    """posture-figure --measure makes the manikin `load human` makes from the same measures:
    the others are the population's conditional expectation, equal to numpy's regression on
    the subjects; the given ones are met."""
    d = subjects(sex)
    given = {"stature": 1700.0, "weightkg": 70.0, "sittingheight": 890.0}
    got = measured(*measure_args(sex, given))
    with daemon.client() as c:
        c.request("load human as m sex=%s stature=1.7 weightkg=70 sittingheight=890" % sex)
        want = c.request("get anthropometry m")["measures"]
    X = np.array([[1.0] + [s[g] for g in given] for s in d])
    x = np.array([1.0] + list(given.values()))
    for k in MEASURES:
        assert got[k] == pytest.approx(want[k], abs=1e-6), k
        if k in given:
            assert got[k] == pytest.approx(given[k], abs=2.0 if k != "weightkg" else 1e-9), k
        else:
            coef, *_ = np.linalg.lstsq(X, np.array([s[k] for s in d]), rcond=None)
            assert got[k] == pytest.approx(float(x @ coef), abs=1e-6), k


def test_get_anthropometry_measures_without_moving_the_figure(daemon, tmp_path):  # noqa: F811
    """The daemon's measures are posture-figure's for the same figure, the figure's posture
    and the posture hash do not change, a figure built from measures (written by
    posture-figure, loaded as a figure file) gives its measures back, and a landmark moved on
    its segment is measured where it is."""
    subject = subjects("female")[100]
    fig = run_tool(*measure_args("female", subject), "write")
    (daemon.state_dir / "jane.fig").write_text(fig)
    with daemon.client() as c:
        c.request("load human as jack")
        c.request("set joint jack knee_l 40deg")
        c.request("set joint jack shoulder_r 30deg 10deg 0")
        before = (c.request("get posture jack"), c.request("status")["posture"])
        got = c.request("get anthropometry jack")["measures"]
        assert list(got) == MEASURES
        assert (c.request("get posture jack"), c.request("status")["posture"]) == before
        want = measured("--human")
        for k in MEASURES:
            assert got[k] == pytest.approx(want[k], abs=1e-9), k
        c.request("load figure jane.fig as jane")
        got = c.request("get anthropometry jane")["measures"]
        for k in MEASURES:
            assert got[k] == pytest.approx(subject[k], abs=2.0 if k != "weightkg" else 1e-9), k
        # only figures with the human's landmarks are measured; the daemon carries on
        (daemon.state_dir / "chair.fig").write_text((FIGURES / "chair.fig").read_text())
        c.request("load figure chair.fig as chair")
        reply = c.request_reply("get anthropometry chair")
        assert reply["error"]["code"] == "bad-argument" and "landmarks" in reply["error"]["message"]
        assert c.request_reply("get anthropometry nobody")["error"]["code"] == "not-found"
        assert c.request("get anthropometry jack")["measures"]["stature"] == pytest.approx(1750)
        # the figure's own landmarks are measured: the acromion moved up 10 mm on its segment
        s = sites("--human")
        local = [a - o for a, o in zip(s["clavicle_r.acromion"], s["clavicle_r.origin"])]
        c.request("set site jack clavicle_r.acromion %r %r %r" % (local[0], local[1] + 0.01,
                                                                   local[2]))
        got = c.request("get anthropometry jack")["measures"]
        assert got["acromialheight"] == pytest.approx(want["acromialheight"] + 10, abs=1e-9)
        assert got["stature"] == pytest.approx(want["stature"], abs=1e-9)


def test_posture_figure_refuses_what_no_body_meets(tmp_path):
    """A set of measures the body cannot meet is refused with the measures named; a bad
    --measure word is refused before anything is built."""
    subject = subjects("male")[0]
    subject["sittingheight"] -= 250
    del subject["eyeheightsitting"]
    exe = pathlib.Path(run_tool.__globals__["BUILD"]) / "bin" / "posture-figure"
    p = subprocess.run([str(exe), *measure_args("male", subject), "measures"], capture_output=True,
                       text=True, timeout=60)
    assert p.returncode != 0 and "sittingheight" in p.stderr and not p.stdout
    for bad in ("height=1700", "stature", "stature=tall", "=3"):
        p = subprocess.run([str(exe), "--measure", bad, "measures"], capture_output=True, text=True,
                           timeout=60)
        assert p.returncode != 0 and "--measure" in p.stderr and not p.stdout, bad
