"""posture.replay - replay tests: a recording and the expectations its replay must meet.

A test is a folder holding ``recording/`` (made by ``postured --record`` or ``record start``)
and ``expect``, a text file::

    posture-replay 1
    # at the end, or after frame N of the recording:
    at end posture 4bfd054cc1653b14                  the hash `postured --replay` prints
    at 120 site human hand_r.palm 0.31 1.02 0.40 tol=1e-9    a site's position (m)
    at end joint human knee_l 0.5235987755982988 tol=1e-12   a joint's values
    at end margin human above 0.02                   the stability margin (m) above a value
    at end picture front front.png tol=1.5           the view against a golden PNG beside
                                                     expect: mean channel difference <= tol

Every replay must also end with no divergence from its recording. ``run_test`` replays the
recording once per point (``--until N``, ``--after`` the queries, ``--frames`` for pictures);
``update`` rewrites the measured values (hashes, positions, joints, pictures; a margin's bound
stays) after a reviewed change. Standard library only.
"""
import dataclasses
import json
import os
import pathlib
import re
import shutil
import struct
import subprocess
import tempfile
import time
import zlib

EXPECT_HEADER = "posture-replay 1"
REPLAY_LINE = re.compile(r"^replay: frames=(\d+) posture=([0-9a-f]{16}) divergences=(\d+)$")
KINDS = {"posture": (1, 1), "site": (5, 6), "joint": (3, 99), "margin": (3, 3),
         "picture": (2, 3)}


class ExpectError(ValueError):
    """An expectations file that cannot be read: the message says file:line."""


@dataclasses.dataclass
class Expectation:
    lineno: int
    point: int          # the frame after which it holds; 0: the end
    kind: str
    words: list         # the words after the kind, tol=... removed
    tol: float = None

    def text(self):
        tol = "" if self.tol is None else " tol=%s" % fmt(self.tol)
        at = "end" if self.point == 0 else str(self.point)
        return " ".join(["at", at, self.kind, *self.words]) + tol


def fmt(x):
    return repr(float(x)) if not isinstance(x, str) else x


def parse_expect(path):
    """The expectations of the file at path (and its lines, for update)."""
    path = pathlib.Path(path)
    lines = path.read_text().splitlines()
    if not lines or lines[0].strip() != EXPECT_HEADER:
        raise ExpectError("%s:1: the first line must be '%s'" % (path, EXPECT_HEADER))
    out = []
    for n, line in enumerate(lines[1:], start=2):
        words = line.split()
        if not words or words[0].startswith("#"):
            continue
        where = "%s:%d" % (path, n)
        if len(words) < 3 or words[0] != "at" or words[2] not in KINDS:
            raise ExpectError("%s: expected 'at end|FRAME %s ...'" % (where, "|".join(KINDS)))
        if words[1] == "end":
            point = 0
        elif words[1].isdigit() and int(words[1]) > 0:
            point = int(words[1])
        else:
            raise ExpectError("%s: the point is 'end' or a frame number from 1" % where)
        kind, rest, tol = words[2], words[3:], None
        if rest and rest[-1].startswith("tol="):
            try:
                tol = float(rest.pop()[4:])
            except ValueError:
                raise ExpectError("%s: tol=NUMBER" % where) from None
        lo, hi = KINDS[kind]
        if not lo <= len(rest) <= hi:
            raise ExpectError("%s: %s takes %d to %d words" % (where, kind, lo, hi))
        e = Expectation(n, point, kind, rest, tol)
        try:
            check_words(e)
        except ValueError as err:
            raise ExpectError("%s: %s" % (where, err)) from None
        out.append(e)
    if not out:
        raise ExpectError("%s: no expectations" % path)
    return out, lines


def check_words(e):
    w = e.words
    if e.kind == "posture" and not re.fullmatch(r"[0-9a-f]{16}", w[0]):
        raise ValueError("posture HASH: 16 hex digits")
    if e.kind == "site":
        [float(x) for x in w[2:5]]
    if e.kind == "joint":
        [float(x) for x in w[2:]]
    if e.kind == "margin" and (w[1] != "above" or float(w[2]) != float(w[2])):
        raise ValueError("margin FIG above VALUE")
    if e.kind == "picture" and not w[1].endswith(".png"):
        raise ValueError("picture VIEW FILE.png")


def query_of(e):
    """The command whose reply an expectation reads, or None."""
    if e.kind == "site":
        return "get site %s %s" % (e.words[0], e.words[1])
    if e.kind == "joint":
        return "get joint %s %s" % (e.words[0], e.words[1])
    if e.kind == "margin":
        return "get balance %s" % e.words[0]
    return None


# ---- pictures ----------------------------------------------------------------------------

def read_png(path):
    """(width, height, channels, bytes) of an 8-bit, non-interlaced RGB or RGBA PNG."""
    data = pathlib.Path(path).read_bytes()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("%s: not a PNG" % path)
    pos, idat, head = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            head = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    w, h, depth, color, _, _, interlace = head
    if depth != 8 or color not in (2, 6) or interlace:
        raise ValueError("%s: only 8-bit RGB or RGBA, not interlaced" % path)
    ch = 3 if color == 2 else 4
    raw, stride = zlib.decompress(idat), w * ch
    out, prev = bytearray(h * stride), bytearray(stride)
    for y in range(h):
        f, row = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = row[i - ch] if i >= ch else 0
            b, c = prev[i], prev[i - ch] if i >= ch else 0
            if f == 1:
                row[i] = (row[i] + a) & 255
            elif f == 2:
                row[i] = (row[i] + b) & 255
            elif f == 3:
                row[i] = (row[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                row[i] = (row[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out[y * stride:(y + 1) * stride] = row
        prev = row
    return w, h, ch, bytes(out)


def picture_difference(a, b):
    """The mean absolute difference of the RGB channels of two PNGs, or None if sizes differ."""
    wa, ha, ca, pa = read_png(a)
    wb, hb, cb, pb = read_png(b)
    if (wa, ha) != (wb, hb):
        return None
    total = 0
    for i in range(wa * ha):
        for k in range(3):
            total += abs(pa[i * ca + k] - pb[i * cb + k])
    return total / (wa * ha * 3)


# ---- running -----------------------------------------------------------------------------

@dataclasses.dataclass
class Result:
    name: str
    failures: list
    frames: int = 0
    seconds: float = 0.0

    @property
    def passed(self):
        return not self.failures


def default_postured():
    """The tree's build (POSTURE_BUILD, else build/rel); installed (make install, the
    Debian package), the postured on PATH."""
    root = pathlib.Path(__file__).resolve().parents[2]
    built = root / os.environ.get("POSTURE_BUILD", "build/rel") / "bin" / "postured"
    if built.exists() or "POSTURE_BUILD" in os.environ:
        return built
    return pathlib.Path(shutil.which("postured") or built)


def replay_once(postured, rec, point, queries, frames_dir):
    """One replay to the point: (frames, posture, divergences, replies, stderr, status)."""
    with tempfile.NamedTemporaryFile("w", suffix=".after", delete=False) as f:
        f.write("".join(q + "\n" for q in queries))
    try:
        argv = [str(postured), "--replay", str(rec), "--after", f.name]
        if point:
            argv += ["--until", str(point)]
        if frames_dir:
            argv += ["--frames", str(frames_dir)]
        p = subprocess.run(argv, capture_output=True, text=True, timeout=600)
    finally:
        os.unlink(f.name)
    lines = p.stdout.splitlines()
    m = REPLAY_LINE.match(lines[-1]) if lines else None
    replies = [json.loads(ln[7:]) for ln in lines if ln.startswith("reply: ")]
    if not m:
        return None, None, None, replies, p.stderr, p.returncode
    return int(m[1]), m[2], int(m[3]), replies, p.stderr, p.returncode


def judge(e, reply, got_posture, frames_dir, test_dir, update):
    """None when e holds (after updating it when asked), else why not."""
    where = "expect:%d" % e.lineno
    if e.kind == "posture":
        if got_posture != e.words[0]:
            if update:
                e.words[0] = got_posture
                return None
            return "%s: posture %s, expected %s" % (where, got_posture, e.words[0])
        return None
    if e.kind == "picture":
        shot, golden = pathlib.Path(frames_dir) / (e.words[0] + ".png"), test_dir / e.words[1]
        if not shot.exists():
            return "%s: the replay drew no picture of view %s" % (where, e.words[0])
        if update:
            shutil.copyfile(shot, golden)
            return None
        if not golden.exists():
            return "%s: no golden picture %s (--update makes it)" % (where, golden.name)
        diff = picture_difference(shot, golden)
        tol = 1.0 if e.tol is None else e.tol
        if diff is None or diff > tol:
            return "%s: view %s differs from %s by %s (tol %g)" % (
                where, e.words[0], golden.name, "its size" if diff is None else "%.3f" % diff, tol)
        return None
    if not reply or not reply.get("ok"):
        return "%s: %s failed: %s" % (where, query_of(e), reply and reply.get("error"))
    res = reply["result"]
    tol = 1e-9 if e.tol is None else e.tol
    if e.kind == "site":
        got, want = res["position"], [float(x) for x in e.words[2:5]]
        if update:
            e.words[2:5] = [fmt(x) for x in got]
            return None
        if max(abs(a - b) for a, b in zip(got, want)) > tol:
            return "%s: site %s at %s, expected %s (tol %g)" % (where, e.words[1], got, want, tol)
    elif e.kind == "joint":
        got, want = res["values"], [float(x) for x in e.words[2:]]
        if update:
            e.words[2:] = [fmt(x) for x in got]
            return None
        if len(got) != len(want) or max(abs(a - b) for a, b in zip(got, want)) > tol:
            return "%s: joint %s is %s, expected %s (tol %g)" % (where, e.words[1], got, want, tol)
    elif e.kind == "margin":
        if not res["margin"] > float(e.words[2]):
            return "%s: margin %.6f m, not above %s" % (where, res["margin"], e.words[2])
    return None


def run_test(test_dir, postured=None, update=False):
    """Replays the test in test_dir against its expectations: a Result (update: rewritten)."""
    test_dir = pathlib.Path(test_dir)
    postured = postured or default_postured()
    name, t0 = test_dir.name, time.monotonic()
    try:
        exps, lines = parse_expect(test_dir / "expect")
    except (OSError, ExpectError) as err:
        return Result(name, [str(err)])
    failures, frames = [], 0
    for point in sorted({e.point for e in exps}, key=lambda p: (p == 0, p)):
        here = [e for e in exps if e.point == point]
        queries = [q for q in map(query_of, here) if q]
        with tempfile.TemporaryDirectory() as shots:
            pics = any(e.kind == "picture" for e in here)
            n, posture, div, replies, err, status = replay_once(
                postured, test_dir / "recording", point, queries, shots if pics else None)
            if n is None:
                failures.append("the replay was refused: %s" % err.strip().splitlines()[-1:])
                break
            frames = max(frames, n)
            if div or status:
                said = [ln for ln in err.splitlines() if "diverged" in ln or "astray" in ln]
                failures.append("the replay diverged from its recording: %s" % " ".join(said))
            if point and n != point:
                failures.append("the recording has %d frames, not %d" % (n, point))
            it = iter(replies)
            for e in here:
                why = judge(e, next(it) if query_of(e) else None, posture, shots, test_dir, update)
                if why:
                    failures.append(why)
    if update and not failures:
        for e in exps:
            lines[e.lineno - 1] = e.text()
        (test_dir / "expect").write_text("\n".join(lines) + "\n")
    return Result(name, failures, frames, time.monotonic() - t0)
