"""The CAN panel's oracles: the committed maps, logs and expectations are what
tools/dbc2panel and cantools give today; dbc2panel's warnings for a defective
DBC; python-can's candump-log writer and reader against our files (which
tests/test_can.c reads and writes byte for byte)."""

import os
import subprocess
import sys

import can
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CAN_DIR = os.path.join(ROOT, "tests", "input", "can")
DBC2PANEL = os.path.join(ROOT, "tools", "dbc2panel")


def dbc2panel(*args):
    return subprocess.run([sys.executable, DBC2PANEL, *args], capture_output=True, text=True)


def map_lines(text):
    return [line.split() for line in text.splitlines() if line.split("#")[0].strip()]


@pytest.mark.parametrize("name", ["panel", "mux", "defects"])
def test_committed_files_are_what_cantools_and_dbc2panel_give(tmp_path, name):
    subprocess.run([sys.executable, os.path.join(CAN_DIR, "make_expect.py"), str(tmp_path)],
                   check=True)
    for ext in ("map", "log", "expect"):
        with open(os.path.join(CAN_DIR, f"{name}.{ext}")) as f:
            committed = f.read()
        with open(tmp_path / f"{name}.{ext}") as f:
            assert f.read() == committed, f"{name}.{ext} differs: re-run make_expect.py"


def test_expectations_cover_every_kind_of_signal():
    with open(os.path.join(CAN_DIR, "panel.map")) as f:
        lines = map_lines(f.read())
    fields = {line[3]: line[2] for line in lines}
    assert fields["Knobs.KnobB"].endswith("@0-")          # Motorola, signed
    assert fields["Dials.Dial3"] == "35|13@1-"            # unaligned, signed
    assert fields["Tilt.Odd"] == "3|13@1+"                # start bit 3, length 13
    assert any(len(line[1]) == 8 for line in lines)       # extended ids
    with open(os.path.join(CAN_DIR, "mux.map")) as f:
        assert any("mux=Pages.Page:1" in line for line in f)
    # truncated frames are among the frames checked: some expectations lack signals
    with open(os.path.join(CAN_DIR, "panel.log")) as f:
        lengths = {len(line.split("#")[1].strip()) // 2 for line in f}
    assert lengths >= set(range(0, 9))


def test_defective_dbc_warns_and_goes_on():
    path = os.path.join(CAN_DIR, "defects.dbc")
    r = dbc2panel(path)
    assert r.returncode == 0
    err = r.stderr
    assert f"{path}:11: warning: message id 0x18FF0A42 is above 0x7FF without the extended " \
           "flag: taken as extended" in err
    assert f"{path}:9: warning: comment (CM_) before or among the messages" in err
    assert f"{path}:13: warning: comment (CM_) before or among the messages" in err
    assert f"{path}:27: warning: comment for signal Missing of message 601" in err
    assert f"{path}:29: warning: value table (VAL_) for signal Ghost of message 601" in err
    assert "signal Floaty.Temp is a float: skipped" in err
    assert "message Fd is 12 bytes long (CAN FD): skipped" in err
    assert err.count("warning:") == 7
    names = {line[3]: line for line in map_lines(r.stdout)}
    assert names["NoFlag.Speed"][1] == "18FF0A42"
    assert "Floaty.Temp" not in names and "Fd.Far" not in names
    assert "Floaty.Count" in names and "Plain.Level" in names


def test_clean_dbc_gives_no_warning():
    r = dbc2panel(os.path.join(CAN_DIR, "mux.dbc"))
    assert r.returncode == 0 and r.stderr == ""


def test_signals_option_keeps_the_named_and_their_multiplexers(tmp_path):
    out = tmp_path / "p.map"
    r = dbc2panel(os.path.join(CAN_DIR, "mux.dbc"), "--signals", "Pages.A1,ExtMux.Tail",
                  "-o", str(out))
    assert r.returncode == 0, r.stderr
    names = [line[3] for line in map_lines(out.read_text())]
    assert names == ["Pages.Page", "Pages.A1", "ExtMux.Tail"]
    r = dbc2panel(os.path.join(CAN_DIR, "mux.dbc"), "--signals", "Pages.Nope")
    assert r.returncode == 1 and "no such signal: Pages.Nope" in r.stderr


def test_unreadable_dbc_fails(tmp_path):
    bad = tmp_path / "bad.dbc"
    bad.write_text('VERSION ""\nBU_: Y\nBO_ 1 X: 8 Y\n SG_ A : 0|8@1+ (1,0) [0|0] "" Y\n'
                   ' SG_ B : 99|x@1+ (1,0) [0|0] "" Y\n')
    r = dbc2panel(str(bad))
    assert r.returncode == 1 and "cannot read the DBC" in r.stderr and "line 5" in r.stderr
    bad.write_text("BO_ 1 X: 8 Y\n")
    r = dbc2panel(str(bad))
    assert r.returncode == 1 and "no signal to map" in r.stderr
    assert dbc2panel(str(tmp_path / "none.dbc")).returncode == 1


# the messages tests/test_can.c expects in pycan.log
def pycan_messages():
    return [
        can.Message(timestamp=1700000000.0, arbitration_id=0x181, is_extended_id=False,
                    data=bytes([0xE8, 0x03, 0xF4, 0x01]), channel="can0"),
        can.Message(timestamp=1700000000.010123, arbitration_id=0x18FF0A42, is_extended_id=True,
                    data=bytes(range(1, 9)), channel="can0"),
        can.Message(timestamp=1700000000.020456, arbitration_id=0x123, is_extended_id=False,
                    is_remote_frame=True, dlc=0, channel="can0"),
        can.Message(timestamp=1700000000.5, arbitration_id=0x7FF, is_extended_id=False,
                    data=b"", is_rx=False, channel="can0"),
        can.Message(timestamp=1700000001.0, is_error_frame=True, channel="can0"),
        can.Message(timestamp=1700000002.999999, arbitration_id=0x1FFFFFFF, is_extended_id=True,
                    data=b"\xab", channel="can0"),
    ]


def test_python_can_writer_gives_the_committed_log(tmp_path):
    out = tmp_path / "pycan.log"
    w = can.CanutilsLogWriter(str(out))
    for m in pycan_messages():
        w.on_message_received(m)
    w.stop()
    with open(os.path.join(CAN_DIR, "pycan.log")) as f:
        assert out.read_text() == f.read()


def test_python_can_reader_reads_our_writers_format():
    # candump.log: the text tests/test_can.c checks our writer gives byte for byte
    msgs = list(can.CanutilsLogReader(os.path.join(CAN_DIR, "candump.log")))
    assert len(msgs) == 9
    m = msgs[0]
    assert (m.timestamp, m.channel, m.arbitration_id, m.is_extended_id, bytes(m.data)) == \
        (1700000000.0, "can0", 0x181, False, bytes.fromhex("E803F40100F80000"))
    assert msgs[1].channel == "vcan10" and msgs[1].is_extended_id
    assert msgs[1].arbitration_id == 0x18FF0A42 and msgs[1].timestamp == 1700000000.010123
    assert msgs[2].is_remote_frame and msgs[2].dlc == 0
    assert msgs[3].is_remote_frame and msgs[3].dlc == 5
    assert msgs[4].arbitration_id == 0x7FF and msgs[4].dlc == 0
    assert msgs[5].is_error_frame
    assert msgs[6].arbitration_id == 1 and msgs[6].is_extended_id and bytes(msgs[6].data) == b"\xff"
    assert msgs[7].is_rx and msgs[7].dlc == 7
    assert not msgs[8].is_rx and msgs[8].arbitration_id == 0x1FFFFFFF
