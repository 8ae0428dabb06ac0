"""REBA and OWAS (through tools/posture-assess) against a peer we did not write:
ergonomics-metrics 0.4.3 (rs9000/ergonomics, MIT), fed the same angle sets, 1,500 random
postures each.

The peer scores from angles and flags (RebaScore.set_body / set_arms, OwasScore.set_body_params);
its angle conventions, read from its source: flexion positive, the knee as the inner angle
(180 = straight) in OWAS, the flags (twisted, raised, abducted) as 0/1. Where a method leaves a
threshold open, the peer is given our decision (its flag inputs are fed from our derivation's
adjustments), or, where it takes an angle, the angle shifted so that its implementer's
threshold falls on ours; the comparison then tests the bands, the code logic and the tables.

Where the peer deviates from the published method, the paper wins. Each deviation found is
counted by kind, and the test asserts that every disagreement is one of these kinds:
  research human-factors §2.4 (known before): REBA neck band 1 only 10-20 deg (paper 0-20);
    REBA trunk band 1 only 0-1 deg (paper: upright); the load never enters the score (the
    peer computes load_score and drops it; nor has it coupling, activity or shock);
  §3.3: OWAS load digit fixed at 1; the contested cell back 4, arms 1, legs 3, load 2
    (peer 3, majority 2);
  found reading the peer's source: REBA trunk extension beyond 20 deg scored 2 (its
    `elif trunk_angle <= 20` takes every extension; paper 3); REBA knees beyond 60 deg add 2
    when seated (paper: not for sitting); OWAS back extension beyond 20 deg read straight
    (`trunk_angle < 20`; the slides: bent forward or backward); OWAS "both knees bent" checked
    after sitting and kneeling, so a seated or kneeling posture with both knees beyond 85 deg
    scores 4; OWAS one-legged stance bent when either knee is, the raised leg's too; and its
    compute_score asserts back < 4 and arms < 3, so it cannot score those codes at all (its
    table is then read directly at our code).
"""
import json
import os
import pathlib
import subprocess
import sys
import types
from collections import Counter

import numpy as np
import pytest

# the peer's utils module draws poses with matplotlib; scoring never touches it
sys.modules.setdefault("ergonomics.utils", types.ModuleType("ergonomics.utils"))
from ergonomics.owas import OwasScore  # noqa: E402
from ergonomics.reba import RebaScore  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
TOOL = BUILD / "bin" / "posture-assess"
N = 1500
UPRIGHT = 5  # assess_config upright (trunk and neck "upright" / 0 within this)
KNEE_BENT_PEER = 85  # the peer's OWAS knee: inner angle < 95 deg


def run_tool(lines, *args):
    text = "".join(json.dumps(x) + "\n" for x in lines)
    proc = subprocess.run([str(TOOL), *args], input=text, capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stderr
    out = [json.loads(x) for x in proc.stdout.splitlines()]
    assert len(out) == len(lines)
    return out


def random_posture(rng):
    u = rng.uniform
    a = {"trunk_flexion": u(-40, 90), "trunk_side_bend": u(-40, 40), "trunk_twist": u(-40, 40),
         "neck_flexion": u(-30, 50), "neck_side_bend": u(-30, 30), "neck_twist": u(-40, 40),
         "hip_trunk_angle": u(60, 180)}
    for s in "lr":
        a |= {f"upper_arm_flexion_{s}": u(-50, 150), f"upper_arm_abduction_{s}": u(0, 90),
              f"upper_arm_rotation_{s}": u(-90, 90), f"shoulder_elevation_{s}": u(0, 30),
              f"elbow_flexion_{s}": u(0, 150), f"wrist_flexion_{s}": u(-60, 60),
              f"wrist_deviation_{s}": u(-30, 30), f"wrist_twist_fraction_{s}": u(0, 1),
              f"elbow_above_shoulder_{s}": u(-0.4, 0.2), f"knee_flexion_{s}": u(0, 120),
              f"hip_flexion_{s}": u(0, 60)}
    stance = rng.choice(["both", "both", "one", "kneel", "seated"])
    share = u(0.3, 0.7)
    a |= {"weight_share_l": share, "weight_share_r": 1 - share, "foot_on_floor_l": 1,
          "foot_on_floor_r": 1, "kneeling_l": 0, "kneeling_r": 0, "seated": 0}
    if stance == "one":
        a |= {"foot_on_floor_r": 0, "weight_share_l": 1.0, "weight_share_r": 0.0}
    elif stance == "kneel":
        a["kneeling_r"] = 1
    elif stance == "seated":
        a["seated"] = 1
    opts = {"side": "right", "load": float(u(0, 25)),
            "coupling": str(rng.choice(["good", "fair", "poor", "unacceptable"])),
            "activity": int(rng.integers(0, 4)), "shock": bool(rng.random() < 0.2)}
    if rng.random() < 0.4:
        # nothing the peer leaves out: under 5 kg, a good coupling, no activity, no shock
        opts |= {"load": float(u(0, 4.9)), "coupling": "good", "activity": 0, "shock": False}
    return a, opts


@pytest.fixture(scope="module")
def postures():
    rng = np.random.default_rng(20240525)
    return [random_posture(rng) for _ in range(N)]


def adjusted(part, word):
    """whether our derivation adjusted this part for a reason containing word"""
    return int(any(x["value"] > 0 and word in x["reason"] for x in part["adjustments"]))


def test_reba_against_peer(postures):
    ours = run_tool([{"id": i, "angles": a, "options": o} for i, (a, o) in enumerate(postures)],
                    "reba")
    kinds = Counter()
    exact = 0
    for (a, o), res in zip(postures, ours):
        d = res["reba"]
        p = d["parts"]
        peer = RebaScore()
        legs_angle = p["legs"]["angle"]
        peer.set_body(np.array([
            a["neck_flexion"], int(p["neck"]["score"] > p["neck"]["base"]),
            a["trunk_flexion"], int(p["trunk"]["score"] > p["trunk"]["base"]),
            int(p["legs"]["base"] == 2), legs_angle, 0]))
        peer.set_arms(np.array([
            a["upper_arm_flexion_r"], adjusted(p["upper_arm"], "raised"),
            int(adjusted(p["upper_arm"], "abducted") or adjusted(p["upper_arm"], "rotated")),
            0, a["elbow_flexion_r"], a["wrist_flexion_r"], int(p["wrist"]["score"] > p["wrist"]["base"])]))
        pa, (pn, pt, pl) = peer.compute_score_a()
        pb, (pu, plo, pw) = peer.compute_score_b()
        pc, _ = peer.compute_score_c(pa, pb)
        mine = {k: p[k]["score"] for k in ("neck", "trunk", "legs", "upper_arm", "lower_arm", "wrist")}
        theirs = {"neck": pn, "trunk": pt, "legs": pl, "upper_arm": pu, "lower_arm": plo, "wrist": pw}
        # the peer's tables at our indices: every cell equal (no deviation is allowed here)
        assert peer.table_a[mine["neck"] - 1][mine["trunk"] - 1][mine["legs"] - 1] == d["tables"]["A"]
        assert peer.table_b[mine["upper_arm"] - 1][mine["lower_arm"] - 1][mine["wrist"] - 1] == d["tables"]["B"]
        ic = d["lookups"]["C"]["index"]
        assert peer.compute_score_c(ic["score_a"], ic["score_b"])[0] == d["tables"]["C"]
        # the bands: each disagreement is a known deviation of the peer
        found = []
        t, n = a["trunk_flexion"], a["neck_flexion"]
        for k in mine:
            if mine[k] == theirs[k]:
                continue
            if k == "neck" and -UPRIGHT <= n < 10 and theirs[k] == mine[k] + 1:
                found.append("neck band 1 only 10-20 deg")
            elif k == "trunk" and abs(t) <= UPRIGHT and not 0 <= t <= 1 and theirs[k] == mine[k] + 1:
                found.append("trunk band 1 only 0-1 deg")
            elif k == "trunk" and t <= -20 and theirs[k] == mine[k] - 1:
                found.append("trunk extension beyond 20 deg scored 2")
            elif k == "legs" and a["seated"] and legs_angle > 60 and theirs[k] == mine[k] + 2:
                found.append("knees beyond 60 deg add 2 when seated")
            else:
                pytest.fail(f"unexplained REBA {k}: ours {mine[k]}, peer {theirs[k]} for {a} {o}")
        addons = (d["parts"]["load"]["score"] or d["parts"]["coupling"]["score"]
                  or d["parts"]["activity"]["score"])
        if not found and not addons:
            assert pc == d["score"]
        if not found and addons and pc != d["score"]:
            found.append("load, coupling, activity not in the score")
        kinds.update(found)
        exact += not found and pc == d["score"]
    print("REBA deviations by kind:", dict(kinds), "exact agreement:", exact)
    # the generator reaches every kind, and agreement is the rule where none applies
    assert set(kinds) == {"neck band 1 only 10-20 deg", "trunk band 1 only 0-1 deg",
                          "trunk extension beyond 20 deg scored 2",
                          "knees beyond 60 deg add 2 when seated",
                          "load, coupling, activity not in the score"}
    assert exact >= 150


def test_owas_against_peer(postures):
    ours = run_tool([{"id": i, "angles": a, "options": {"load": o["load"]}}
                     for i, (a, o) in enumerate(postures)],
                    "--set", f"knee_bent={KNEE_BENT_PEER}", "owas")
    kinds = Counter()
    exact = 0
    for (a, o), res in zip(postures, ours):
        d = res["owas"]
        code = [int(c) for c in d["code"]]
        peer = OwasScore()
        # the peer's side angle threshold is 30 deg, ours 20: shifted onto ours
        side = max(abs(a["trunk_side_bend"]), abs(a["trunk_twist"])) + 10
        seated = a["seated"]
        peer.set_body_params(np.array([
            a["trunk_flexion"], side, a["elbow_above_shoulder_l"], a["elbow_above_shoulder_r"],
            90 if seated else a["hip_flexion_l"], 90 if seated else a["hip_flexion_r"],
            180 - a["knee_flexion_l"], 180 - a["knee_flexion_r"],
            0.05 if a["kneeling_l"] else 0.4, 0.05 if a["kneeling_r"] else 0.4,
            0.2 if a["foot_on_floor_r"] == 0 else 0.0, 0.0]))
        # the peer's table at our code: equal but for the contested cell (research §3.3)
        cell = int(peer.table[code[0] - 1][code[1] - 1][code[2] - 1][code[3] - 1])
        found = []
        if cell != d["score"]:
            assert code == [4, 1, 3, 2] and cell == 3 and d["score"] == 2
            found.append("contested cell 4132")
        try:
            pscore, pcode = peer.compute_score()
            pcode = [int(x) for x in pcode]
        except AssertionError:
            assert code[0] == 4 or code[1] == 3
            found.append("peer cannot score back 4 or arms 3")
            pcode = None
        if pcode is not None:
            bent = [a[f"knee_flexion_{s}"] > KNEE_BENT_PEER for s in "lr"]
            if pcode[0] != code[0]:
                assert a["trunk_flexion"] < -20 and pcode[0] == code[0] - 1
                found.append("back extension read straight")
            if pcode[2] != code[2]:
                if (seated or a["kneeling_r"]) and all(bent) and pcode[2] == 4:
                    found.append("seated or kneeling with both knees bent scored 4")
                elif code[2] == 3 and pcode[2] == 5 and bent[1] and not bent[0]:
                    found.append("one-legged stance bent by the raised leg")
                else:
                    pytest.fail(f"unexplained OWAS legs: ours {code}, peer {pcode} for {a}")
            assert pcode[1] == code[1]
            if code[3] != 1:
                found.append("load digit fixed at 1")
            if not found:
                assert pscore == d["score"]
        kinds.update(found)
        exact += not found
    print("OWAS deviations by kind:", dict(kinds), "exact agreement:", exact)
    assert set(kinds) <= {"contested cell 4132", "peer cannot score back 4 or arms 3",
                          "back extension read straight",
                          "seated or kneeling with both knees bent scored 4",
                          "one-legged stance bent by the raised leg", "load digit fixed at 1"}
    assert {"peer cannot score back 4 or arms 3", "back extension read straight",
            "seated or kneeling with both knees bent scored 4",
            "one-legged stance bent by the raised leg", "load digit fixed at 1"} <= set(kinds)
    assert exact >= 200


def test_tool_refuses_bad_lines_and_keeps_going():
    text = ('{"id": 1, "angles": {"upper_arm_flexion_r": 50, "shoulder_elevation_r": 14.2}}\n'
            '{"id": 2, "angles": {"no_such_angle": 1}}\n'
            'not json\n'
            '{"id": 4, "options": {"coupling": "sticky"}}\n'
            '{"id": 5, "angles": {"trunk_flexion": 30}, "options": {"load": 12}}\n')
    proc = subprocess.run([str(TOOL), "rula", "owas"], input=text, capture_output=True,
                          text=True, timeout=60)
    assert proc.returncode == 1
    out = [json.loads(x) for x in proc.stdout.splitlines()]
    assert len(out) == 5
    assert out[1] == {"id": 2, "error": "unknown angle 'no_such_angle'"}
    assert "not JSON" in out[2]["error"]
    assert "coupling" in out[3]["error"]
    assert "line 2" in proc.stderr and "line 4" in proc.stderr
    ua = out[0]["rula"]["parts"]["upper_arm"]
    assert (ua["band"], ua["base"], ua["score"]) == ("45-90 deg flexion", 3, 4)
    assert ua["adjustments"] == [{"value": 1, "reason": "shoulder raised: clavicle elevation 14.2 > 10 deg"}]
    assert out[4]["owas"]["code"] == "2122" and out[4]["owas"]["score"] == 2
    # a threshold set on the command line, and one refused
    proc = subprocess.run([str(TOOL), "--set", "owas_back=35", "owas"], input=text.splitlines()[4],
                          capture_output=True, text=True, timeout=60)
    assert json.loads(proc.stdout)["owas"]["code"] == "1122"
    proc = subprocess.run([str(TOOL), "--set", "owas_back=95"], input="", capture_output=True,
                          text=True, timeout=60)
    assert proc.returncode == 2 and "0..90" in proc.stderr
