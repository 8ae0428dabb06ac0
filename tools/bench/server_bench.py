#!/usr/bin/env python3
"""Round trips over the Unix socket: postured beside a trivial echo server, same run.

Starts build/rel/bin/postured (a temporary state directory, one human loaded) and
build/rel/bench/echo_server, then runs build/rel/bench/rtt_client (C, so that no Python
overhead is measured) against each with 1 and with 32 clients, one request in flight per
client. The request is a small read, `get joint bench knee_l`. Prints the BENCH lines
(`BENCH server.rtt.1client median_us=... p99_us=... rps=...`, `BENCH echo.rtt.1client
...`) and a summary of what postured adds over the echo server.
"""
import os
import pathlib
import re
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

REQUEST = "get joint bench knee_l"
RUNS = [(1, 20000), (32, 1000)]  # (clients, timed requests per client)


def wait_socket(path, proc, timeout=20.0):
    """Returns once path accepts connections; exits if the process died."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            sys.exit(f"{proc.args[0]} exited with status {proc.returncode} at start-up")
        with socket.socket(socket.AF_UNIX) as s:
            try:
                s.connect(str(path))
                return
            except OSError:
                time.sleep(0.01)
    sys.exit(f"{path} not ready after {timeout} s")


def stop(proc):
    proc.send_signal(signal.SIGTERM)
    try:
        proc.wait(20)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()


def measure(sock, name):
    """Runs rtt_client for every (clients, requests); returns {clients: (median, p99, rps)}."""
    out = {}
    for clients, requests in RUNS:
        proc = subprocess.run([str(BUILD / "bench" / "rtt_client"), str(sock), str(clients),
                               str(requests), REQUEST, name], capture_output=True, text=True)
        print(proc.stdout, end="", flush=True)
        if proc.returncode != 0:
            sys.exit(f"rtt_client against {name} failed ({proc.returncode}):\n{proc.stderr}")
        m = re.search(r"median_us=([0-9.]+) p99_us=([0-9.]+) rps=([0-9.]+)", proc.stdout)
        out[clients] = tuple(float(x) for x in m.groups())
    return out


def main():
    for exe in (BUILD / "bin" / "postured", BUILD / "bench" / "rtt_client",
                BUILD / "bench" / "echo_server"):
        if not exe.exists():
            sys.exit(f"{exe} is missing: build it first (make {exe.relative_to(ROOT)})")
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="pbench-", dir="/tmp"))
    try:
        state = tmp / "state"
        state.mkdir()
        sock = tmp / "postured.sock"
        with open(tmp / "postured.log", "wb") as log:
            daemon = subprocess.Popen([str(BUILD / "bin" / "postured"), "--socket", str(sock),
                                       "--state-dir", str(state)], stdout=log, stderr=log)
        try:
            wait_socket(sock, daemon)
            with Client(socket_path=str(sock)) as c:
                c.request("load human as bench")
            ours = measure(sock, "server")
        finally:
            stop(daemon)
        echo_sock = tmp / "echo.sock"
        echo = subprocess.Popen([str(BUILD / "bench" / "echo_server"), str(echo_sock)])
        try:
            wait_socket(echo_sock, echo)
            peer = measure(echo_sock, "echo")
        finally:
            stop(echo)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    for clients, _ in RUNS:
        o, p = ours[clients], peer[clients]
        print(f"server_bench: {clients} client(s): postured median {o[0]:.1f} us, p99 {o[1]:.1f} us, "
              f"{o[2]:.0f} req/s; echo server median {p[0]:.1f} us, p99 {p[1]:.1f} us, "
              f"{p[2]:.0f} req/s (postured adds {o[0] - p[0]:.1f} us at the median)")


if __name__ == "__main__":
    main()
