"""32 clients x 1000 commands at once: every reply arrives, in order per client, and
every client reads back exactly what it wrote.

All clients share one figure; each owns one joint of it, which only it writes, so a
client's reads of that joint (through `get joint` and `get posture`) must return its own
last write bit for bit whatever the others do. Requests are pipelined in windows and
tagged "c<client>.<n>", so the order of replies is checked one by one.
"""
import random
import threading
import time

import pytest

from daemon import daemon, daemon_factory  # noqa: F401  (fixtures)

CLIENTS = 32
COMMANDS = 1000
WINDOW = 25          # requests in flight per client
WRITE_SHARE = 0.3    # the rest are reads


def joint_table(client):
    """{joint: (lower, upper)} of every joint with dofs of the shared figure."""
    fig = client.request("show figure shared")
    return {j["name"]: list(zip(j["lower"], j["upper"])) for j in fig["joints"] if j["lower"]}


def run_client(daemon, index, joint, limits, results):
    """One client's session; stores None on success or a description of what failed."""
    rng = random.Random(index)
    last = None  # this client's last acknowledged values of its joint
    try:
        with daemon.client(timeout=60) as c:
            n = 0
            while n < COMMANDS:
                batch = []
                for _ in range(min(WINDOW, COMMANDS - n)):
                    r = rng.random()
                    if r < WRITE_SHARE:
                        values = [lo + (hi - lo) * rng.random() for lo, hi in limits]
                        batch.append(("set", values,
                                      f"set joint shared {joint} " + " ".join(map(repr, values))))
                    elif r < 0.6:
                        batch.append(("get", None, f"get joint shared {joint}"))
                    elif r < 0.7:
                        batch.append(("posture", None, "get posture shared"))
                    elif r < 0.85:
                        batch.append(("status", None, "status"))
                    else:
                        batch.append(("error", None, f"get joint shared no_such_joint_{index}"))
                tags = [f"c{index}.{n + k}" for k in range(len(batch))]
                replies = c.pipeline([f"#{t} {line}" for t, (_, _, line) in zip(tags, batch)])
                for tag, (kind, values, line), reply in zip(tags, batch, replies):
                    if reply.get("tag") != tag:
                        raise AssertionError(f"reply {reply.get('tag')!r} where {tag!r} was due")
                    if kind == "error":
                        if reply["ok"] or reply["error"]["code"] != "not-found":
                            raise AssertionError(f"{tag} {line}: {reply}")
                        continue
                    if not reply["ok"]:
                        raise AssertionError(f"{tag} {line}: {reply}")
                    res = reply["result"]
                    if kind == "set":
                        if res["values"] != values:
                            raise AssertionError(f"{tag}: set echoed {res['values']} for {values}")
                        last = values
                    elif kind == "get" and last is not None and res["values"] != last:
                        raise AssertionError(f"{tag}: read {res['values']}, wrote {last}")
                    elif kind == "posture" and last is not None and res["posture"][joint] != last:
                        raise AssertionError(f"{tag}: posture has {res['posture'][joint]}, "
                                             f"wrote {last}")
                n += len(batch)
        results[index] = ("ok", last)
    except Exception as e:  # reported by the test
        results[index] = ("failed", f"client {index}: {type(e).__name__}: {e}")


def test_32_clients_1000_commands(daemon):
    """Every one of the 32000 replies arrives in order; writes are read back exactly, and
    the final posture holds every client's last write."""
    with daemon.client() as c:
        c.request("load human as shared")
        joints = joint_table(c)
    owned = sorted(joints)[:CLIENTS]
    assert len(owned) == CLIENTS
    results = [None] * CLIENTS
    threads = [threading.Thread(target=run_client,
                                args=(daemon, i, owned[i], joints[owned[i]], results))
               for i in range(CLIENTS)]
    t0 = time.monotonic()
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=240)
    elapsed = time.monotonic() - t0
    assert not any(t.is_alive() for t in threads), "clients still waiting for replies"
    failures = [r[1] for r in results if r is None or r[0] != "ok"]
    assert not failures, "\n".join(failures[:10])
    with daemon.client() as c:
        posture = c.request("get posture shared")["posture"]
        for i, joint in enumerate(owned):
            if results[i][1] is not None:
                assert posture[joint] == results[i][1], joint
        assert c.status()["clients"] == 1
    print(f"\n{CLIENTS * COMMANDS} commands in {elapsed:.2f} s "
          f"({CLIENTS * COMMANDS / elapsed:.0f}/s)")
