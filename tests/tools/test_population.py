"""The population module (through tools/posture-population) against independent references:
numpy's least-squares regressions fitted on every ANSUR II subject, numpy's percentiles of the
data, scipy's chi-square quantiles and Mahalanobis distances computed here from the raw data.

The built-in population's statistics are themselves checked: regenerating them from the
committed CSV files gives the committed C source byte for byte."""
import csv
import os
import pathlib
import subprocess

import numpy as np
import pytest
from scipy import stats

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
TOOL = BUILD / "bin" / "posture-population"
DATA = ROOT / "data" / "ansur2"
FILES = {"male": DATA / "ANSUR_II_MALE_Public.csv", "female": DATA / "ANSUR_II_FEMALE_Public.csv"}

# the 20 measures a manikin is built from (src/figure/measures.h), in its order
MEASURES = ["stature", "acromialheight", "wristheight", "trochanterionheight",
            "kneeheightmidpatella", "lateralmalleolusheight", "sittingheight", "eyeheightsitting",
            "acromionradialelength", "radialestylionlength", "handlength", "footlength",
            "buttockkneelength", "kneeheightsitting", "poplitealheight", "biacromialbreadth",
            "hipbreadth", "span", "thumbtipreach", "weightkg"]
# ten of them given, the other ten predicted
TEN = ["stature", "weightkg", "sittingheight", "acromialheight", "kneeheightsitting",
       "buttockkneelength", "span", "footlength", "handlength", "biacromialbreadth"]


def tool(*args, stdin=None, ok=True):
    proc = subprocess.run([str(TOOL), *map(str, args)], input=stdin, capture_output=True,
                          text=True, timeout=300)
    if ok:
        assert proc.returncode == 0, proc.stderr
    return proc


def table(text):
    """CSV text -> (header, float rows)"""
    lines = text.strip().splitlines()
    return lines[0].split(","), np.array([[float(v) for v in ln.split(",")] for ln in lines[1:]])


_data = {}


def subjects(sex):
    """every subject of the sex: {column: values}, weightkg in kg"""
    if sex not in _data:
        with open(FILES[sex], encoding="latin-1", newline="") as f:
            rows = list(csv.reader(f))
        head = rows[0]
        cols = {}
        for j, name in enumerate(head[1:94], start=1):
            v = np.array([float(r[j]) for r in rows[1:] if r])
            cols[name] = v / 10 if name == "weightkg" else v
        _data[sex] = cols
    return _data[sex]


def test_built_in_statistics_regenerate_from_the_committed_data():
    out = subprocess.run([str(ROOT / "tools" / "ansur2-stats")], capture_output=True, text=True,
                         check=True, timeout=120).stdout
    committed = (ROOT / "src" / "figure" / "ansur2_data.c").read_text()
    assert out == committed, "src/figure/ansur2_data.c is not what tools/ansur2-stats makes"


def test_built_in_moments_match_numpy():
    """means and covariances of the built-in population against numpy's of the raw data"""
    for sex in ("male", "female"):
        d = subjects(sex)
        lines = tool("--sex", sex, "stats").stdout.strip().splitlines()[1:]
        assert len(lines) == 93
        for line in lines:
            name, n, mean, sd = line.split(",")
            x = d[name]
            assert int(n) == len(x)
            assert float(mean) == pytest.approx(x.mean(), rel=1e-13)
            assert float(sd) == pytest.approx(x.std(ddof=1), rel=1e-12)


def predictions(sex, given):
    """the module's conditional expectations for every subject, from their given measures"""
    d = subjects(sex)
    lines = "\n".join(",".join(repr(float(d[g][i])) for g in given) for i in range(len(d["stature"])))
    head, rows = table(tool("--sex", sex, "predict", ",".join(given), stdin=lines + "\n").stdout)
    return {name: rows[:, j] for j, name in enumerate(head)}


def regression(d, given, target):
    """numpy's least-squares fit of target on the given measures (with intercept): the
    fitted values for every subject"""
    X = np.column_stack([np.ones(len(d[target]))] + [d[g] for g in given])
    coef, *_ = np.linalg.lstsq(X, d[target], rcond=None)
    return X @ coef


def rms_table(given):
    out = []
    for sex in ("female", "male"):
        d, pred = subjects(sex), predictions(sex, given)
        for g in given:  # the given ones are met
            assert np.max(np.abs(pred[g] - d[g])) <= 1e-9
        for m in MEASURES:
            if m in given:
                continue
            fitted = regression(d, given, m)
            # on its own data the population's conditional expectation is that regression
            assert np.allclose(pred[m], fitted, rtol=1e-9, atol=1e-7), (sex, m)
            ours = np.sqrt(np.mean((pred[m] - d[m]) ** 2))
            ref = np.sqrt(np.mean((fitted - d[m]) ** 2))
            out.append((sex, m, ours, ref))
    return out


def print_table(title, rows):
    print(f"\n{title}\n| sex | measure | RMS error (mm; weightkg kg) | numpy regression | ratio |")
    for sex, m, ours, ref in rows:
        print(f"| {sex} | {m} | {ours:.2f} | {ref:.2f} | {ours / ref:.4f} |")


@pytest.mark.parametrize("given", [["stature", "weightkg"], TEN], ids=["stature+weight", "ten"])
def test_prediction_no_worse_than_a_regression_on_every_subject(given):
    rows = rms_table(given)
    print_table(f"given {', '.join(given)}", rows)
    for sex, m, ours, ref in rows:
        assert ours <= 1.1 * ref, f"{sex} {m}: RMS {ours:.2f} vs regression {ref:.2f}"


@pytest.mark.parametrize("sex", ["female", "male"])
def test_percentile_stature_is_the_datas_order_statistic(sex):
    st = subjects(sex)["stature"]
    for p in (0, 1, 5, 10, 25, 50, 75, 90, 95, 99, 100, 2.5, 97.5):
        head, rows = table(tool("--sex", sex, "percentile", p).stdout)
        assert rows[0, head.index("stature")] == pytest.approx(np.percentile(st, p), abs=1e-9)
    # the data's README: female P5 1525 mm, male P95 1870 mm
    p, want = (5, 1525) if sex == "female" else (95, 1870)
    head, rows = table(tool("--sex", sex, "percentile", p).stdout)
    assert rows[0, head.index("stature")] == want


def test_percentile_manikin_is_the_conditional_median_given_stature():
    """the rest of a percentile manikin: numpy's regression on stature, at that stature"""
    d = subjects("female")
    head, rows = table(tool("--sex", "female", "percentile", 5).stdout)
    s = rows[0, head.index("stature")]
    for m in ("weightkg", "sittingheight", "span", "footlength"):
        slope, icept = np.polyfit(d["stature"], d[m], 1)
        assert rows[0, head.index(m)] == pytest.approx(icept + slope * s, rel=1e-9)
    # its distance is |z| of that stature
    z = (s - d["stature"].mean()) / d["stature"].std(ddof=1)
    assert rows[0, -1] == pytest.approx(abs(z), rel=1e-9)


def mahalanobis(d, names, x):
    X = np.column_stack([d[n] for n in names])
    mu, S = X.mean(0), np.atleast_2d(np.cov(X.T))
    diff = x - mu
    return np.sqrt(diff @ np.linalg.solve(S, diff))


@pytest.mark.parametrize("names,coverage,n", [
    (["stature", "weightkg"], 90, 8),
    (["stature", "weightkg"], 95, 16),
    (["stature", "weightkg", "sittingheight"], 90, 14),
    (["stature", "weightkg", "sittingheight", "span", "buttockkneelength"], 99, 16),
    (["stature"], 90, 2),
])
@pytest.mark.parametrize("sex", ["female", "male"])
def test_family_on_the_coverage_ellipsoid(sex, names, coverage, n):
    d = subjects(sex)
    head, rows = table(tool("--sex", sex, "family", ",".join(names), coverage, n).stdout)
    assert rows.shape[0] == n + 1
    idx = [head.index(m) for m in names]
    radius = np.sqrt(stats.chi2.ppf(coverage / 100, len(names)))
    # the centre is the mean; each boundary manikin at the chi-square radius, by numpy's reckoning
    assert mahalanobis(d, names, rows[0, idx]) == pytest.approx(0, abs=1e-9)
    for r in rows[1:]:
        assert mahalanobis(d, names, r[idx]) == pytest.approx(radius, rel=1e-9)
        assert r[-1] == pytest.approx(radius, rel=1e-9)
    # the rest of each is the regression on the chosen measures at that point
    others = [m for m in MEASURES if m not in names]
    X = np.column_stack([np.ones(len(d["stature"]))] + [d[m] for m in names])
    for m in others[:4]:
        coef, *_ = np.linalg.lstsq(X, d[m], rcond=None)
        for r in rows:
            assert r[head.index(m)] == pytest.approx(coef[0] + r[idx] @ coef[1:], rel=1e-9)


def test_two_measure_family_is_eight_points_at_45_degrees():
    """k = 2, n = 8: the axis ends and the diagonals of the standardised principal axes"""
    d = subjects("male")
    names = ["stature", "weightkg"]
    head, rows = table(tool("--sex", "male", "family", ",".join(names), 90, 8).stdout)
    X = np.column_stack([d[m] for m in names])
    mu, sd = X.mean(0), X.std(0, ddof=1)
    lam, V = np.linalg.eigh(np.corrcoef(X.T))
    order = np.argsort(lam)[::-1]
    lam, V = lam[order], V[:, order]
    z = (rows[1:, [head.index(m) for m in names]] - mu) / sd
    pcs = (z @ V) / np.sqrt(lam)  # the points in whitened principal components
    angles = np.sort((np.degrees(np.arctan2(pcs[:, 1], pcs[:, 0])) + 1e-6) % 360)
    assert np.allclose(angles, np.arange(0, 360, 45), atol=1e-5)
    assert np.allclose(np.hypot(pcs[:, 0], pcs[:, 1]), np.sqrt(stats.chi2.ppf(0.9, 2)), rtol=1e-9)
    # first the two ends of the first principal axis
    assert abs(pcs[0, 1]) < 1e-9 and abs(pcs[1, 1]) < 1e-9 and pcs[0, 0] * pcs[1, 0] < 0


def test_chi2_quantile_against_scipy():
    for k in (1, 2, 3, 4, 5, 7, 10, 20, 50, 93):
        for p in (0.001, 0.05, 0.5, 0.8, 0.9, 0.95, 0.99, 0.999):
            ours = float(tool("chi2", p, k).stdout)
            assert ours == pytest.approx(stats.chi2.ppf(p, k), rel=1e-11), (p, k)


BAD = [
    ("Gender,stature\n", "no people"),
    ("stature,weightkg\n1600,600\n", ":1: no sex column"),
    ("Gender,age\nFemale,30\n", ":1: no column is one of ANSUR II's measured dimensions"),
    ("Gender,stature\nFemale,1600\nFemale,\n", ":3: stature is empty"),
    ("Gender,stature\nFemale,1600\nFemale,16OO\n", ":3: stature '16OO' is not a number"),
    ("Gender,stature\nFemale,-1600\n", ":2: stature -1600 is outside"),
    ("Gender,stature\nFemale,160\n", ":2: stature 160 is outside"),
    ("Gender,weightkg\nFemale,65\n", ":2: weightkg 65 is outside"),
    ("Gender,stature\nWoman,1600\n", ":2: sex 'Woman' is neither Male nor Female"),
    ("Gender,stature\n,1600\n", ":2: no sex"),
    ("Gender,stature\nFemale,1600,3\n", ":2: 3 fields where the header has 2"),
    ("Gender,stature,Stature\n", ":1: the column Stature appears twice"),
    ("Gender,stature\n\"Female,1600\n", ":2: a quoted field does not close on its line"),
]


@pytest.mark.parametrize("text,why", BAD, ids=[b[1] for b in BAD])
def test_bad_population_files_refused_with_file_and_line(tmp_path, text, why):
    path = tmp_path / "people.csv"
    path.write_text(text)
    proc = tool("--population", path, "check", ok=False)
    assert proc.returncode == 1 and proc.stdout == ""
    assert f"{path}" in proc.stderr and why in proc.stderr, proc.stderr


def test_a_sex_needs_thirty_people(tmp_path):
    rng = np.random.default_rng(7)
    rows = ["Gender,stature"] + [f"Female,{v:.0f}" for v in rng.normal(1630, 64, 30)]
    ok = tmp_path / "ok.csv"
    ok.write_text("\n".join(rows) + "\n")
    assert tool("--population", ok, "check").stdout.startswith("men 0\nwomen 30\n")
    few = tmp_path / "few.csv"
    few.write_text("\n".join(rows + ["Male,1750"] * 29) + "\n")
    proc = tool("--population", few, "check", ok=False)
    assert proc.returncode == 1 and "29 men: a sex needs at least 30 people" in proc.stderr


def test_ansur_layout_subset_latin1_utf8_and_quotes(tmp_path):
    """a file with a few of ANSUR's columns (any order, quoted, a BOM, latin-1 text in an
    ignored column) gives the moments numpy gives"""
    d = subjects("female")
    n = 200
    lines = ["\ufeffName,\"Weightkg\",sex,stature"]
    for i in range(n):
        lines.append(f"\"Zoë, {i}\",{d['weightkg'][i] * 10:.0f},F,\"{d['stature'][i]:.0f}\"")
    path = tmp_path / "subset.csv"
    path.write_bytes(("\r\n".join(lines) + "\r\n").encode("utf-8"))
    out = tool("--population", path, "--sex", "female", "stats").stdout.strip().splitlines()
    got = {ln.split(",")[0]: [float(v) for v in ln.split(",")[1:]] for ln in out[1:]}
    assert set(got) == {"stature", "weightkg"}
    for m in ("stature", "weightkg"):
        assert got[m][1] == pytest.approx(d[m][:n].mean(), rel=1e-12)
        assert got[m][2] == pytest.approx(d[m][:n].std(ddof=1), rel=1e-12)
    assert tool("--population", path, "check").stdout.splitlines()[-1] == "ignored Name"
    # the same as latin-1
    path.write_bytes(("\r\n".join(lines[:1] + lines[1:]) + "\r\n").encode("latin-1",
                                                                          errors="replace"))
    assert tool("--population", path, "check").stdout.startswith("men 0\nwomen 200\n")
