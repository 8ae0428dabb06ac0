"""tools/dbc2panel's repairs of the defects real DBC files have (the survey of opendbc's files
found each: tests/input/can/opendbc/survey.txt), each with a warning naming file:line, and
the limits of a map it keeps to (buttons, stale times, fields within the frame, one name
once), so that the map it writes always loads: posture-input takes it."""
import os
import pathlib
import subprocess
import sys

import cantools

ROOT = pathlib.Path(__file__).resolve().parents[2]
DBC2PANEL = ROOT / "tools" / "dbc2panel"
TOOL = ROOT / os.environ.get("POSTURE_BUILD", "build/rel") / "bin" / "posture-input"

HEAD = 'VERSION ""\n\nNS_ :\n\tCM_\n\tBA_DEF_\n\tVAL_\n\nBS_:\n\nBU_: Panel\n\n'


def dbc2panel(*args):
    return subprocess.run([sys.executable, str(DBC2PANEL), *map(str, args)],
                          capture_output=True, text=True, timeout=120)


def map_lines(text):
    return [line.split() for line in text.splitlines() if line.split("#")[0].strip()]


def loads_in_posture_input(tmp_path, text):
    """posture-input decode --map takes the map (with a log of a frame no line reads)"""
    (tmp_path / "p.map").write_text(text)
    (tmp_path / "one.log").write_text("(1700000000.000000) can0 7FF#00\n")
    r = subprocess.run([str(TOOL), "decode", str(tmp_path / "one.log"), "--map",
                        str(tmp_path / "p.map")], capture_output=True, text=True, timeout=30)
    return r.returncode == 0, r.stderr


def test_each_defect_of_the_survey_is_repaired_with_its_line(tmp_path):
    path = tmp_path / "vendor.dbc"
    path.write_text(HEAD + (
        'CM_ "a file concatenated with another: a general comment with no \';\'"\n'  # 12
        "BO_ 1275 2017_5: 8 Panel\n"                                                 # 13
        ' SG_ 0_COUNTER : 3|4@0+ (1,0) [0|15] "" Panel\n'                           # 14
        ' SG_ Torque : 23|13@0+ (.25,-500) [-500|1547.5] "Nm" Panel\n'              # 15
        "\n"
        "BO_ 1075054137 TooLong: 8 Panel\n"                                         # 17
        ' SG_ Lost : 0|8@1+ (1,0) [0|255] "" Panel\n'
        "\n"
        "BO_ 304 Plain: 2 Panel\n"                                                  # 20
        ' SG_ Level : 0|16@1+ (1,0) [0|0] "" Panel\n'
        "\n"
        'CM_ SG_ 304 "a signal\'s comment that names no signal";\n'                 # 23
        'CM_ 304 "a message\'s comment without BO_";\n'                              # 24
        'CM_ BU_ "a comment of a shape nobody reads";\n'                             # 25
        'VAL_ 1275 0_COUNTER 0 "zero" 1 "one"\n'                                    # 26
        "SIG_VALTYPE_ 304 Ghost : 1;\n"                                             # 27
        'VAL_ 304 Level 0 "off" ;\n'))
    # cantools refuses the file as it is
    try:
        cantools.database.load_file(str(path), strict=False)
        raise AssertionError("cantools read the defective file")
    except cantools.database.UnsupportedDatabaseFormatError:
        pass
    r = dbc2panel(path)
    assert r.returncode == 0, r.stderr
    want = [
        (12, "CM_ statement without its ';': ended with one"),
        (12, "comment (CM_) before or among the messages: moved after them"),
        (13, "name 2017_5 begins with a digit, which cantools cannot read: read as _2017_5, "
             "written as 2017_5"),
        (14, "name 0_COUNTER begins with a digit, which cantools cannot read: read as "
             "_0_COUNTER, written as 0_COUNTER"),
        (15, "number .25 without a digit before its point: read as 0.25"),
        (17, "message TooLong has id 0x40140639, more than 29 bits, which is no CAN id: "
             "dropped with its signals"),
        (23, "comment for a signal of message 304 that names no signal: dropped"),
        (24, "comment for message 304 without BO_: read as the message's comment"),
        (25, "comment (CM_) in a shape cantools does not read: dropped"),
        (26, "VAL_ statement without its ';': ended with one"),
        (27, "value type (SIG_VALTYPE_) for signal Ghost of message 304, which does not "
             "exist: dropped"),
    ]
    assert r.stderr.splitlines() == [f"dbc2panel: {path}:{n}: warning: {t}" for n, t in want]
    # the map keeps the DBC's own names, and the factor read as 0.25
    assert map_lines(r.stdout) == [
        ["axis", "4FB", "3|4@0+", "2017_5.0_COUNTER", "dlc=8"],
        ["axis", "4FB", "23|13@0+", "2017_5.Torque", "factor=0.25", "offset=-500", "dlc=8"],
        ["axis", "130", "0|16@1+", "Plain.Level", "dlc=2"],
    ]
    r = dbc2panel(path, "--signals", "2017_5.0_COUNTER")
    assert r.returncode == 0 and [line[3] for line in map_lines(r.stdout)] == \
        ["2017_5.0_COUNTER"]
    assert loads_in_posture_input(tmp_path, dbc2panel(path).stdout) == (True, "")


def test_a_text_outside_the_file_s_strings_is_what_is_repaired(tmp_path):
    """a keyword, a ';' or .5 inside a comment's text is text: not a statement to mend"""
    path = tmp_path / "strings.dbc"
    path.write_text(HEAD + (
        "BO_ 100 M: 8 Panel\n"
        ' SG_ A : 0|8@1+ (1,0) [0|0] "" Panel\n'
        "\n"
        'CM_ SG_ 100 A "two lines,\nVAL_ 100 A 1 .5 without\n;";\n'
        'CM_ "a \\" quote; and // no comment";\n'))
    r = dbc2panel(path)
    assert r.returncode == 0 and r.stderr == "", r.stderr


def buttons_dbc(path, n):
    """n one-bit signals, 8 a message"""
    text = HEAD
    for m in range((n + 7) // 8):
        text += f"BO_ {0x100 + m} Keys{m}: 1 Panel\n"
        for b in range(min(8, n - 8 * m)):
            text += f' SG_ K{b} : {b}|1@1+ (1,0) [0|1] "" Panel\n'
        text += "\n"
    path.write_text(text)


def test_more_buttons_than_codes_are_written_as_axes_and_the_map_loads(tmp_path):
    path = tmp_path / "keys.dbc"
    buttons_dbc(path, 40)
    r = dbc2panel(path)
    assert r.returncode == 0 and r.stderr == ""
    assert [line[0] for line in map_lines(r.stdout)] == ["button"] * 40
    assert loads_in_posture_input(tmp_path, r.stdout) == (True, "")
    buttons_dbc(path, 45)
    r = dbc2panel(path)
    assert r.returncode == 0
    assert r.stderr == (f"dbc2panel: {path}: warning: 45 one-bit signals, more than the 40 "
                        "button codes of a map (BTN_TRIGGER_HAPPY1..40): the last 5, from "
                        "Keys5.K0 on, are written as axes (valuators of 0 or 1); --signals "
                        "chooses the signals, and so the buttons\n")
    lines = map_lines(r.stdout)
    assert [line[0] for line in lines] == ["button"] * 40 + ["axis"] * 5
    assert lines[40] == ["axis", "105", "0|1@1+", "Keys5.K0", "dlc=1"]
    assert loads_in_posture_input(tmp_path, r.stdout) == (True, "")
    # --signals chooses which are buttons
    r = dbc2panel(path, "--signals", "Keys5.K0,Keys5.K4")
    assert [line[0] for line in map_lines(r.stdout)] == ["button", "button"]


def test_a_map_s_other_limits_are_kept(tmp_path):
    path = tmp_path / "limits.dbc"
    path.write_text(HEAD + (
        "BO_ 100 Slow: 8 Panel\n"
        ' SG_ A : 0|8@1+ (1,0) [0|0] "" Panel\n'
        ' SG_ Past : 60|8@1+ (1,0) [0|0] "" Panel\n'
        ' SG_ PastM : 59|8@0+ (1,0) [0|0] "" Panel\n'
        ' SG_ A : 8|8@1+ (1,0) [0|0] "" Panel\n'
        "\n"
        "BO_ 101 Slow: 8 Panel\n"
        ' SG_ B : 0|8@1+ (1,0) [0|0] "" Panel\n'
        "\n"
        'BA_DEF_ BO_ "GenMsgCycleTime" INT 0 10000000;\n'
        'BA_ "GenMsgCycleTime" BO_ 100 2000000;\n'))
    r = dbc2panel(path)
    assert r.returncode == 0, r.stderr
    assert r.stderr.splitlines() == [
        f"dbc2panel: {path}: warning: message Slow: its cycle time 2000000 ms gives a stale "
        "timeout above the map's 3600000 ms: 3600000 taken",
        f"dbc2panel: {path}: warning: signal Slow.A is defined twice in its message: the "
        "second skipped",
        f"dbc2panel: {path}: warning: signal Slow.Past (60|8@1+) lies past the 8 bytes of a "
        "CAN frame: skipped",
        f"dbc2panel: {path}: warning: signal Slow.PastM (59|8@0+) lies past the 8 bytes of a "
        "CAN frame: skipped",
        f"dbc2panel: {path}: warning: message Slow (id 0x65) is defined twice: the second "
        "skipped",
    ]
    assert map_lines(r.stdout) == [["axis", "064", "0|8@1+", "Slow.A", "stale=3600000",
                                    "dlc=8"]]
    assert loads_in_posture_input(tmp_path, r.stdout) == (True, "")
