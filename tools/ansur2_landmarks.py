#!/usr/bin/env python3
"""Derives the built-in human's landmark offsets from ANSUR II (data/ansur2/*.csv), and each
measure's mean ratio to stature (what a build from measures takes for one not given).

Each offset is the mean over a sex's subjects of one relation between their measures, divided
by the subject's stature; src/figure/human_dims.c holds the printed values (to 4 decimals) and
cites this script. Run from the repository root:

    python3 tools/ansur2_landmarks.py

Relations (mm; H stature). Joint centres are where human.h puts them: the knee's at the lateral
femoral epicondyle's height, the hip's at the trochanterion's, the wrist's at the stylion's.
  acromion above the shoulder joint   acromionradialelength/H - de Leva's upper arm/H
  stylion ahead of the wrist axis     wristcircumference / (2 pi) (half the wrist's thickness)
  acromion lateral of the shoulder    biacromialbreadth/2 + arm - span/2, arm = shoulder joint to
                                      dactylion, hanging
  seat below the hip joint            sittingheight - (stature - trochanterionheight)
  midpatella above the knee joint     kneeheightmidpatella - lateralfemoralepicondyleheight
  suprapatella ahead of the knee      kneeheightsitting - lateralfemoralepicondyleheight
  popliteal behind the knee           lateralfemoralepicondyleheight - poplitealheight
  buttock behind the hip joint        buttockkneelength - thigh - suprapatella offset
  shoulder blades behind the joint    thumbtipreach - (shoulder joint - pinch point), the pinch
                                      point 0.6 handlength below the wrist (an assumption)
  trochanterion from the midline      hipbreadth / 2
  tibiale above the knee joint        tibialheight - lateralfemoralepicondyleheight
  iliocristale above the hip joint    iliocristaleheight - trochanterionheight; bicristalbreadth/2
  lateral malleolus from the axis     bimalleolarbreadth / 2
  tragion below the vertex            tragiontopofhead; headbreadth / 2
"""
import csv
import math
import pathlib

DATA = pathlib.Path(__file__).resolve().parent.parent / "data" / "ansur2"
# de Leva (1996) Table 4: upper arm (shoulder to elbow joint centre) and the reference stature, m
DE_LEVA_UPPER_ARM = {"male": 0.2817 / 1.741, "female": 0.2751 / 1.735}
PINCH = 0.6  # pinch point (thumb tip on index finger) below the wrist, fraction of handlength


def read(sex):
    path = DATA / f"ANSUR_II_{sex.upper()}_Public.csv"
    with open(path, encoding="latin-1", newline="") as f:
        return [{k: float(v) for k, v in row.items() if k.islower() and k != "subjectid"}
                for row in csv.DictReader(f)]


def offsets(sex):
    rows = read(sex)
    acc = {}

    def add(name, value_mm, h):
        acc.setdefault(name, []).append(value_mm / h)

    a_y = sum(r["acromionradialelength"] / r["stature"] for r in rows) / len(rows) - \
        DE_LEVA_UPPER_ARM[sex]
    s_z = sum(r["wristcircumference"] / (2 * math.pi) / r["stature"] for r in rows) / len(rows)
    for r in rows:
        h = r["stature"]
        gh = r["acromialheight"] - a_y * h
        dactylion = r["wristheight"] - math.sqrt(r["handlength"] ** 2 - (s_z * h) ** 2)
        add("acromion_x", r["biacromialbreadth"] / 2 + (gh - dactylion) - r["span"] / 2, h)
        add("seat", r["sittingheight"] - (h - r["trochanterionheight"]), h)
        add("midpatella_y", r["kneeheightmidpatella"] - r["lateralfemoralepicondyleheight"], h)
        f = r["kneeheightsitting"] - r["lateralfemoralepicondyleheight"]
        add("suprapatella", f, h)
        add("popliteal", r["lateralfemoralepicondyleheight"] - r["poplitealheight"], h)
        thigh = r["trochanterionheight"] - r["lateralfemoralepicondyleheight"]
        add("buttock", r["buttockkneelength"] - thigh - f, h)
        pinch = r["wristheight"] - PINCH * r["handlength"]
        add("shoulder_blade", r["thumbtipreach"] - (gh - pinch), h)
        add("trochanterion_x", r["hipbreadth"] / 2, h)
        add("tibiale_y", r["tibialheight"] - r["lateralfemoralepicondyleheight"], h)
        add("iliocristale_y", r["iliocristaleheight"] - r["trochanterionheight"], h)
        add("iliocristale_x", r["bicristalbreadth"] / 2, h)
        add("malleolus_x", r["bimalleolarbreadth"] / 2, h)
        add("tragion_y", r["tragiontopofhead"], h)
        add("tragion_x", r["headbreadth"] / 2, h)
    out = {"acromion_y": a_y, "stylion_z": s_z}
    out.update({k: sum(v) / len(v) for k, v in acc.items()})
    return len(rows), out


# the measures a manikin is built from (src/figure/measures.h), in its order
MEASURES = ("stature acromialheight wristheight trochanterionheight kneeheightmidpatella "
            "lateralmalleolusheight sittingheight eyeheightsitting acromionradialelength "
            "radialestylionlength handlength footlength buttockkneelength kneeheightsitting "
            "poplitealheight biacromialbreadth hipbreadth span thumbtipreach").split()


def ratios(sex):
    """Each measure's mean ratio to stature: what a build takes for a measure not given."""
    rows = read(sex)
    return {k: sum(r[k] / r["stature"] for r in rows) / len(rows) for k in MEASURES}


def main():
    for sex in ("male", "female"):
        n, o = offsets(sex)
        print(f"{sex} (n = {n}), fractions of stature:")
        for k, v in o.items():
            print(f"  {k:16s} {v:8.4f}")
        print(f"{sex}, each measure's mean ratio to stature:")
        for k, v in ratios(sex).items():
            print(f"  {k:24s} {v:8.5f}")


if __name__ == "__main__":
    main()
