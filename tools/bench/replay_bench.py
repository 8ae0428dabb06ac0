#!/usr/bin/env python3
"""Recording and replay: how fast a recorded kiosk session replays, and what
recording costs the live loop.

A SESSION_S-second kiosk session is performed on build/rel/bin/postured at 60 fps: the
standard human with its behaviours on and a 640x480 view, its right hand dragged to and fro
through `input pointer` lines at 125 Hz (the mouse of a person at the kiosk), recorded with
--record. Then:

- replay.speed: `postured --replay` of it as fast as it goes, without frames: the session's
  length over the replay's wall time (x);
- replay.speed_frames: the same with `--hash-frames yes`: every view drawn after every frame
  and its pixels hashed (x);
- record.overhead: the same session performed again with and without --record, alternating,
  REPEATS each, OVERHEAD_S seconds; the CPU time per frame solved of the loop's thread
  (loop_pct: what recording costs the loop) and of the whole daemon with the recording's
  writer thread (pct), the median of each (/proc/PID/task/PID/stat, /proc/PID/stat).

Prints `BENCH replay.speed x=... session_s=... frames=... wall_s=...`, `BENCH
replay.speed_frames x=... pictures=...` and `BENCH record.overhead loop_pct=... pct=...`.
"""
import math
import os
import pathlib
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
POSTURED = BUILD / "bin" / "postured"
sys.path.insert(0, str(ROOT / "tools"))

from posture import Client  # noqa: E402

SESSION_S = float(os.environ.get("REPLAY_BENCH_S", "60"))
OVERHEAD_S = 6.0
REPEATS = 9
MOUSE_HZ = 125


def start(tmp, record=None):
    sock = tmp / "sock"
    state = tmp / "state"
    state.mkdir(exist_ok=True)
    argv = [str(POSTURED), "--socket", str(sock), "--state-dir", str(state), "--input", "none",
            "--fps", "60"]
    if record:
        argv += ["--record", str(record)]
    proc = subprocess.Popen(argv, stderr=subprocess.DEVNULL)
    for _ in range(400):
        if sock.exists():
            break
        time.sleep(0.05)
    return proc, Client(str(sock))


def cpu_s(pid, thread=False):
    """The process's CPU time (s), or its main thread's (the loop's) with thread."""
    path = "/proc/%d/task/%d/stat" % (pid, pid) if thread else "/proc/%d/stat" % pid
    fields = pathlib.Path(path).read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def perform(c, seconds):
    """The drag: returns the frames the daemon ran meanwhile."""
    c.request("load human as human")
    c.request("add view front width=640 height=480 eye=0.4,1.1,3.2 target=0,0.9,0")
    c.request("behave human on")
    c.request("manipulate hand human right view=front")
    f0 = c.request("status")["frame"]
    t0 = time.monotonic()
    c.request("input pointer front 240 260")
    c.request("input button left down")
    k = 0
    while time.monotonic() - t0 < seconds:
        k += 1
        x = 240 - 60 * math.sin(k / MOUSE_HZ * 2 * math.pi / 4)  # to and fro every 4 s
        y = 260 - 40 * (1 - math.cos(k / MOUSE_HZ * 2 * math.pi / 4))
        c.request("input pointer front %d %d" % (round(x), round(y)))
        sleep = t0 + k / MOUSE_HZ - time.monotonic()
        if sleep > 0:
            time.sleep(sleep)
    c.request("input button left up")
    return c.request("status")["frame"] - f0


def session(tmp, seconds, record=None):
    proc, c = start(tmp, record)
    cpu0, loop0 = cpu_s(proc.pid), cpu_s(proc.pid, thread=True)
    frames = perform(c, seconds)
    cpu, loop = cpu_s(proc.pid) - cpu0, cpu_s(proc.pid, thread=True) - loop0
    c.close()
    proc.terminate()
    proc.wait(30)
    shutil.rmtree(tmp / "state", ignore_errors=True)
    return frames, cpu, loop


def replay(rec, *extra):
    t0 = time.monotonic()
    p = subprocess.run([str(POSTURED), "--replay", str(rec), *extra], capture_output=True,
                       text=True)
    wall = time.monotonic() - t0
    if p.returncode != 0:
        sys.exit("replay_bench: the replay failed:\n" + p.stderr)
    lines = p.stdout.split("\n")
    frames = int(lines[-2].split()[1].split("=")[1])
    pictures = next((ln.split()[1].split("=")[1] for ln in lines if ln.startswith("pictures:")),
                    "0")
    return wall, frames, int(pictures)


def main():
    with tempfile.TemporaryDirectory(prefix="replay-bench-", dir="/tmp") as d:
        tmp = pathlib.Path(d)
        rec = tmp / "rec"
        session(tmp, SESSION_S, record=rec)
        wall, frames, _ = replay(rec)
        print("BENCH replay.speed x=%.1f session_s=%.0f frames=%d wall_s=%.3f" % (
            SESSION_S / wall, SESSION_S, frames, wall), flush=True)
        wall, frames, pictures = replay(rec, "--hash-frames", "yes")
        print("BENCH replay.speed_frames x=%.2f session_s=%.0f frames=%d pictures=%d wall_s=%.2f "
              "size=640x480" % (SESSION_S / wall, SESSION_S, frames, pictures, wall), flush=True)
        live, rec_ = [], []
        for k in range(REPEATS):
            for sink, dest in ((None, live), (tmp / ("o%d" % k), rec_)):
                frames, cpu, loop = session(tmp, OVERHEAD_S, record=sink)
                dest.append((cpu / max(frames, 1) * 1e6, loop / max(frames, 1) * 1e6))
        a, b = [statistics.median(x[0] for x in v) for v in (rec_, live)]
        la, lb = [statistics.median(x[1] for x in v) for v in (rec_, live)]
        # the spread: each recorded session against the plain one run just before it
        pairs = sorted(100 * (r[1] - p[1]) / p[1] for r, p in zip(rec_, live))
        print("BENCH record.overhead loop_pct=%.1f pct=%.1f loop_us_frame_rec=%.0f "
              "loop_us_frame_live=%.0f us_frame_rec=%.0f us_frame_live=%.0f pairs_pct=%.1f..%.1f "
              "repeats=%d" % (100 * (la - lb) / lb, 100 * (a - b) / b, la, lb, a, b, pairs[0],
                              pairs[-1], REPEATS), flush=True)


if __name__ == "__main__":
    main()
