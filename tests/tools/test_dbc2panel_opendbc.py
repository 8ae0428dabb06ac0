"""tools/dbc2panel on real vendors' DBC files: opendbc's (tests/input/can/opendbc, a fixed
revision, with the *_generated.dbc files its own generator makes from it). The survey of
which files cantools refuses as they are, and why, is what survey.py prints today; every
file converts after dbc2panel's repairs; each map loads in posture-input and decodes
frames as cantools decodes them with the DBC, and loads in the daemon; and the repairs
change nothing cantools reads in a file it reads as it is."""
import importlib.machinery
import importlib.util
import io
import os
import pathlib
import random
import subprocess
import sys

import cantools
import pytest
from cantools.database.utils import create_encode_decode_formats, decode_data

ROOT = pathlib.Path(__file__).resolve().parents[2]
OPENDBC = ROOT / "tests" / "input" / "can" / "opendbc"
TOOL = ROOT / os.environ.get("POSTURE_BUILD", "build/rel") / "bin" / "posture-input"
sys.path.insert(0, str(ROOT / "tests" / "system"))
sys.path.insert(0, str(ROOT / "tests" / "input" / "can"))

import make_expect  # noqa: E402  (after sys.path)
from daemon import Daemon  # noqa: E402


def load(name, path):
    loader = importlib.machinery.SourceFileLoader(name, str(path))
    spec = importlib.util.spec_from_loader(name, loader)
    mod = importlib.util.module_from_spec(spec)
    loader.exec_module(mod)
    return mod


survey = load("survey", OPENDBC / "survey.py")
dbc2panel = survey.load_dbc2panel()


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """(name, path) of every DBC: dbc/*.dbc and the generated ones"""
    return survey.dbc_files(str(tmp_path_factory.mktemp("opendbc")))


@pytest.fixture(scope="module")
def surveyed(files):
    return [(name, survey.survey_file(dbc2panel, path)) for name, path in files]


@pytest.fixture(scope="module")
def maps(files, surveyed, tmp_path_factory):
    """name -> (path of the DBC, path of the map dbc2panel wrote)"""
    out = tmp_path_factory.mktemp("maps")
    made = {}
    for (name, path), (_, r) in zip(files, surveyed):
        map_path = out / (name[:-4] + ".map")
        map_path.write_text(r["map"])
        made[name] = (path, map_path)
    return made


def test_the_survey_is_what_cantools_and_dbc2panel_give_today(surveyed):
    out = io.StringIO()
    survey.report(surveyed, out)
    assert out.getvalue() == (OPENDBC / "survey.txt").read_text(), \
        "tests/input/can/opendbc/survey.txt differs: re-run survey.py"


def test_every_file_cantools_refuses_converts_after_repair(surveyed):
    refused = [(name, r) for name, r in surveyed if r["as_is"]]
    for name, r in refused:
        assert r["after"] is None and r["db_repaired"] is not None, (name, r["after"])
        assert r["mapped"], name
        assert r["refused_for"], name
    # the folder as surveyed: 57 files and 39 generated, 32 of them refused as they are
    assert (len(surveyed), len(refused)) == (96, 32)


def test_repairs_change_nothing_cantools_reads_in_a_file_it_reads(surveyed):
    def contents(db):
        return sorted((m.frame_id, m.is_extended_frame, m.name, m.length,
                       sorted((s.name, s.start, s.length, s.byte_order, s.is_signed,
                               float(s.scale), float(s.offset), s.multiplexer_signal,
                               tuple(s.multiplexer_ids or ()), s.is_float)
                              for s in m.signals))
                      for m in db.messages)
    read = [(name, r) for name, r in surveyed if not r["as_is"]]
    for name, r in read:
        assert contents(r["db_repaired"]) == contents(r["db_as_is"]), name
    assert len(read) == 64


def map_lines(path):
    return [line.split() for line in path.read_text().splitlines()
            if line.split("#")[0].strip()]


def test_every_map_keeps_within_what_a_map_can_hold(maps):
    for name, (_, map_path) in maps.items():
        lines = map_lines(map_path)
        assert 0 < len(lines) <= 256, name
        assert sum(1 for line in lines if line[0] == "button") <= 40, name
        names = [line[3] for line in lines]
        assert len(set(names)) == len(names), name


def frames(msg, rng):
    """a few frames of a message: zeros, ones, random; every multiplexer set to a value
    it has branches for (cantools decodes no other), each value of the first at least once"""
    n = msg.length
    muxes = []
    for mux in (s for s in msg.signals if s.is_multiplexer):
        values = sorted({v for s in msg.signals if s.multiplexer_signal == mux.name
                         for v in s.multiplexer_ids})
        if values:
            muxes.append((mux, values))
    count = max([5] + [min(len(v), 16) for _, v in muxes])
    out = [bytes(n), b"\xff" * n] + [bytes(rng.getrandbits(8) for _ in range(n))
                                     for _ in range(count - 2)]
    for i, data in enumerate(out):
        for mux, values in muxes:
            raw = int((values[i % len(values)] - mux.offset) / mux.scale)
            data = make_expect.set_raw(data, msg, mux, raw)
        out[i] = data
    return out


def cantools_values(msg, data):
    """cantools' decoding of data, signal by signal where it will not decode the whole
    message (overlapping signals, or a signal past the frame: the map has neither)"""
    try:
        return msg.decode(data, decode_choices=False, allow_truncated=True)
    except cantools.database.DecodeError:
        pass
    out = {}
    for sig in msg.signals:
        fmts = create_encode_decode_formats([sig], msg.length)
        try:
            out.update(decode_data(data, msg.length, [sig], fmts, False, True, True, True))
        except cantools.database.DecodeError:
            pass
    return out


def test_every_map_loads_in_posture_input_and_decodes_as_cantools(maps, tmp_path):
    """each map with a candump log of frames of its messages: posture-input decodes each
    frame to the values cantools decodes from it with the DBC (as dbc2panel mends it)"""
    checked = 0
    for name, (path, map_path) in sorted(maps.items()):
        renamed = {}
        db = cantools.database.load_string(
            dbc2panel.repair(dbc2panel.read_dbc(path), lambda *a: None, renamed), "dbc",
            strict=False)
        in_map = {line[3] for line in map_lines(map_path)}
        rng = random.Random(name)
        log, want = [], {}
        for msg in db.messages:
            mname = renamed.get(msg.name, msg.name)
            if not 0 < msg.length <= 8 or not any(n.startswith(mname + ".") for n in in_map):
                continue
            for data in frames(msg, rng):
                t = f"(1700000000.{len(log):06d})"
                ident = f"{msg.frame_id:08X}" if msg.is_extended_frame else f"{msg.frame_id:03X}"
                log.append(f"{t} can0 {ident}#{data.hex().upper()}")
                values = {f"{mname}.{renamed.get(s, s)}": float(v)
                          for s, v in cantools_values(msg, data).items()}
                values = {k: v for k, v in values.items() if k in in_map}
                if values:
                    want.setdefault(t, {}).update(values)
        log_path = tmp_path / (name + ".log")
        log_path.write_text("\n".join(log) + "\n")
        r = subprocess.run([str(TOOL), "decode", str(log_path), "--map", str(map_path)],
                           capture_output=True, text=True, timeout=60)
        assert r.returncode == 0, f"{name}: {r.stderr}"
        got = {}
        for line in r.stdout.splitlines():
            words = line.split()
            got.setdefault(words[0], {}).update(
                {k: float(v) for k, v in (w.split("=", 1) for w in words[2:])})
        assert want, name
        for t, values in want.items():
            assert t in got, (name, t)
            assert got[t].keys() == values.keys(), (name, t)
            for k, v in values.items():
                assert got[t][k] == pytest.approx(v, rel=1e-12, abs=1e-12), (name, t, k)
        checked += 1
    assert checked == len(maps) == 96


def test_every_map_loads_in_the_daemon(maps):
    """the daemon started with each map as its panel knows the map's dials by name"""
    for name, (_, map_path) in sorted(maps.items()):
        lines = map_lines(map_path)
        dial = next(line[3] for line in lines if line[0] in ("axis", "mux"))
        d = Daemon(extra=("--panel", str(map_path)))
        d.start()
        try:
            with d.client() as c:
                c.request(f"input valuator {dial} 1")
        finally:
            d.stop()
            d.cleanup()
