#!/usr/bin/env python3
"""The frame loop as the kiosk runs it: its stalls while the view turns, its cost at rest.

Starts build/rel/bin/postured as `make run` does (tools/kiosk.init: the standard human
and a 1280x720 view `main`, whose picture goes to FRAMES/main.png) with no input devices,
and lets it settle. Then:

- idle: nothing happens for IDLE_S seconds; the daemon's CPU time (utime + stime of
  /proc/PID/stat) over that time, and the frames solved and pictures written meanwhile;
- stall: change view (F2, the left button held, the pointer swept to and fro by `input
  motion` lines, BATCH to a write) turns the camera for SWEEP_S seconds, so every frame
  has a new picture; `status` gives the longest loop round outside solving and rendering
  of each second (`stall_max_us`), and the same in the loop thread's own CPU time
  (`stall_cpu_max_us`: its work, not its waits for a CPU), read four times a second.

The input comes over the socket, so its replies wake this client: on a 2-core machine
that wake-up now and then costs the loop a few milliseconds, which a mouse read directly
would not. (A mocked evdev mouse under umockdev-run is no better a stand-in: its emulated
read() alone took up to 17 ms.)

Prints `BENCH loop.idle cpu_pct=... frames=... written=...` and `BENCH loop.stall
max_ms=... median_ms=... cpu_max_ms=... draw_ms=... written=... dropped=...` (the largest
and the median of the per-second figures, the largest in CPU time; draw_ms is the median
rendering time of a frame).
"""
import os
import pathlib
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = ROOT / os.environ.get("POSTURE_BUILD", "build/rel")
sys.path.insert(0, str(ROOT / "tools"))

from posture import Client  # noqa: E402

IDLE_S = 10.0
SWEEP_S = 6.0
SWEEP_HZ = 120  # motion lines a second, more than the frames
BATCH = 4       # lines a write: the replies wake this client less often


def wait_file(path, proc, timeout=60.0):
    """Returns once path exists; exits if the process died."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            sys.exit(f"postured exited with status {proc.returncode} at start-up")
        if path.exists():
            return
        time.sleep(0.02)
    sys.exit(f"{path} did not appear after {timeout} s")


def cpu_seconds(pid):
    """utime + stime of pid, in seconds."""
    fields = pathlib.Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def idle(c, pid):
    s0, t0, cpu0 = c.request("status"), time.monotonic(), cpu_seconds(pid)
    time.sleep(IDLE_S)
    s1, t1, cpu1 = c.request("status"), time.monotonic(), cpu_seconds(pid)
    pct = 100.0 * (cpu1 - cpu0) / (t1 - t0)
    print(f"BENCH loop.idle cpu_pct={pct:.2f} seconds={t1 - t0:.1f} "
          f"frames={s1['frame'] - s0['frame']} "
          f"written={s1.get('frames_written', 0) - s0.get('frames_written', 0)}", flush=True)


def sweep(c):
    # change view (F2 at the kiosk), then the left button sweeps the camera round the figure
    for line in ("input pointer main 640 360", "input key KEY_F2 down", "input key KEY_F2 up",
                 "input button left down"):
        c.request(line)
    w0 = c.request("status")
    stall, cpu, draw = [], [], []
    start = last = time.monotonic()
    k = 0
    while time.monotonic() - start < SWEEP_S:
        dx = 3 if (k // 200) % 2 == 0 else -3  # to and fro
        c.pipeline([f"input motion {dx} 0"] * BATCH)
        k += BATCH
        if time.monotonic() - last >= 0.25:  # each second's figure seen at least once
            s = c.request("status")
            stall.append(s["stall_max_us"])
            cpu.append(s.get("stall_cpu_max_us", 0))
            draw.append(s["draw_us"])
            last = time.monotonic()
        time.sleep(max(0.0, start + k / SWEEP_HZ - time.monotonic()))
    time.sleep(1.1)  # the sweep's last second published
    s = c.request("status")
    stall.append(s["stall_max_us"])
    cpu.append(s.get("stall_cpu_max_us", 0))
    for line in ("input button left up", "input key KEY_ESC down", "input key KEY_ESC up"):
        c.request(line)
    stall, cpu = stall[1:], cpu[1:]  # the first figures are of the second before the sweep
    print(f"BENCH loop.stall max_ms={max(stall) / 1000:.2f} "
          f"median_ms={sorted(stall)[len(stall) // 2] / 1000:.2f} "
          f"cpu_max_ms={max(cpu) / 1000:.2f} "
          f"draw_ms={sorted(draw)[len(draw) // 2] / 1000:.2f} "
          f"solved={s['frame'] - w0['frame']} "
          f"written={s.get('frames_written', 0) - w0.get('frames_written', 0)} "
          f"dropped={s.get('frames_dropped', 0) - w0.get('frames_dropped', 0)} "
          f"seconds={SWEEP_S:.0f}", flush=True)


def main():
    exe = BUILD / "bin" / "postured"
    if not exe.exists():
        sys.exit(f"{exe} is missing: build it first (make {exe.relative_to(ROOT)})")
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="lbench-", dir="/tmp"))
    sock, frames = tmp / "postured.sock", tmp / "frames"
    frames.mkdir()
    log = open(tmp / "postured.log", "wb")
    proc = subprocess.Popen([str(exe), "--socket", str(sock), "--state-dir", str(tmp / "state"),
                             "--frames", str(frames), "--init", str(ROOT / "tools" / "kiosk.init"),
                             "--library", str(ROOT / "src" / "figure" / "library"),
                             "--input", "none"], stdout=log, stderr=log)
    try:
        wait_file(frames / "main.png", proc)
        while True:  # the socket comes up after the first picture's start-up
            with socket.socket(socket.AF_UNIX) as s:
                if s.connect_ex(str(sock)) == 0:
                    break
            time.sleep(0.02)
        with Client(socket_path=str(sock)) as c:
            time.sleep(3.0)  # the standing human settles, the start-up picture is written
            idle(c, proc.pid)
            sweep(c)
    finally:
        proc.send_signal(signal.SIGTERM)
        try:
            proc.wait(20)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
        log.close()
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
