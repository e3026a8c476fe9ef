"""The rclpy face against robomodel's own node API, on the same Zenoh bus.

1. **1 kHz publisher -> subscriber**, two processes: A publishes ``std_msgs/Header`` stamped
   with the wall clock at 1 kHz, B subscribes and records publish -> callback latency. Once
   with robomodel's API on both sides (``Context("zenoh").create_node``, ``ctx.spin()``),
   once with rclpy's (``create_publisher``/``create_subscription``, ``rclpy.spin``); the two
   alternate round by round. Both publishers are paced by the same loop, so the difference is
   what the face adds to a publish and a delivery.
2. **Cost per message in one process** (the in-process bus, no Zenoh: what the face itself
   adds, free of the scheduling noise of two processes): publish one message and spin once
   until its callback ran, 20,000 times; the best of ``--rounds`` alternating runs.
3. **Start-up**: a fresh process's time from its first line to a node on the bus,
   ``import rclpy; rclpy.init(); rclpy.create_node('n')`` against
   ``from robomodel.runtime import Context; Context('zenoh').create_node('n')`` (median of
   ``--starts`` alternating runs; interpreter start-up itself not counted).

Run: ``.venv/bin/python bench/bench_clientlibs.py [--seconds 5] [--rounds 3] [--starts 9]``.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import paced_sends

DOMAIN = 91


def _stamp(header: Any) -> None:
    ns = time.time_ns()
    header.stamp.sec, header.stamp.nanosec = divmod(ns, 1_000_000_000)


def role_pub(api: str, seconds: float, rate: float) -> None:
    if api == "rclpy":
        import rclpy
        from std_msgs.msg import Header

        rclpy.init(args=[], domain_id=DOMAIN)
        node = rclpy.create_node("bench_pub")
        publisher = node.create_publisher(Header, "bench", 10)
        count = publisher.get_subscription_count
    else:
        from robomodel.runtime import Context
        from robomodel.runtime.msg.types.std_msgs import Header

        ctx = Context("zenoh", domain_id=DOMAIN)
        node = ctx.create_node("bench_pub")
        publisher = node.create_publisher(Header, "bench", 10)
        count = publisher.get_subscription_count
    deadline = time.monotonic() + 30
    while count() < 1 and time.monotonic() < deadline:
        time.sleep(0.01)
    time.sleep(0.5)  # the subscriber's session settles
    msg = Header()

    def send(k: int) -> None:
        msg.frame_id = str(k)
        _stamp(msg)
        publisher.publish(msg)

    sent, elapsed = paced_sends(seconds, rate, send)
    print(json.dumps({"sent": sent, "elapsed": elapsed}), flush=True)
    time.sleep(0.5)
    if api == "rclpy":
        rclpy.shutdown()
    else:
        ctx.shutdown()


def role_sub(api: str, seconds: float) -> None:
    latencies: list[float] = []
    last = [float("inf")]  # monotonic time of the last message

    def on_msg(msg: Any) -> None:
        stamp = msg.stamp
        latencies.append(time.time() - (stamp.sec + stamp.nanosec * 1e-9))
        last[0] = time.monotonic()

    def over() -> bool:  # the publisher has stopped (none for a second)
        return time.monotonic() - last[0] > 1.0

    if api == "rclpy":
        import rclpy
        from std_msgs.msg import Header

        rclpy.init(args=[], domain_id=DOMAIN)
        node = rclpy.create_node("bench_sub")
        node.create_subscription(Header, "bench", on_msg, 10)
        print("ready", flush=True)
        end = time.monotonic() + seconds
        while time.monotonic() < end and not over():
            rclpy.spin_once(node, timeout_sec=0.05)
        rclpy.shutdown()
    else:
        from robomodel.runtime import Context
        from robomodel.runtime.msg.types.std_msgs import Header

        with Context("zenoh", domain_id=DOMAIN) as ctx:
            ctx.create_node("bench_sub").create_subscription(Header, "bench", on_msg, 10)
            print("ready", flush=True)
            ctx.spin(duration_s=seconds, until=over)
    print(json.dumps({"latencies": latencies}), flush=True)


def _pubsub_round(api: str, seconds: float, rate: float) -> dict[str, float]:
    me = [sys.executable, __file__]
    sub = subprocess.Popen([*me, "--role", "sub", "--api", api, "--seconds", str(seconds + 60)],
                           stdout=subprocess.PIPE, text=True)  # fmt: skip
    assert sub.stdout is not None and sub.stdout.readline().strip() == "ready"
    pub = subprocess.run([*me, "--role", "pub", "--api", api, "--seconds", str(seconds),
                          "--rate", str(rate)], capture_output=True, text=True, check=True)  # fmt: skip
    sent = json.loads(pub.stdout.strip().splitlines()[-1])["sent"]
    out, _ = sub.communicate(timeout=seconds + 60)
    latencies = sorted(json.loads(out.strip().splitlines()[-1])["latencies"])
    if len(latencies) < 2:
        raise SystemExit(f"{api}: the subscriber received {len(latencies)} of {sent} messages")
    q = statistics.quantiles(latencies, n=100)
    return {"sent": sent, "received": len(latencies), "p50_us": q[49] * 1e6, "p99_us": q[98] * 1e6}


def _inproc_us(api: str, count: int = 20_000) -> float:
    """Microseconds per publish -> callback on the in-process bus."""
    got = [0]

    def on_msg(msg: Any) -> None:
        got[0] += 1

    if api == "rclpy":
        import rclpy
        from rclpy.executors import SingleThreadedExecutor
        from std_msgs.msg import Header

        rclpy.init(args=[], bus="inproc")
        node = rclpy.create_node("bench_inproc")
        node.create_subscription(Header, "bench", on_msg, 10)
        publish = node.create_publisher(Header, "bench", 10).publish
        executor = SingleThreadedExecutor()
        executor.add_node(node)  # an executor runs its own nodes' callbacks only
        spin = executor.spin_once
        msg: Any = Header()
    else:
        from robomodel.runtime import Context
        from robomodel.runtime.msg.types.std_msgs import Header as RobomodelHeader

        ctx = Context()
        robomodel_node = ctx.create_node("bench_inproc")
        robomodel_node.create_subscription(RobomodelHeader, "bench", on_msg, 10)
        publish = robomodel_node.create_publisher(RobomodelHeader, "bench", 10).publish
        spin = ctx.spin_once
        msg = RobomodelHeader()
    start = time.perf_counter()
    for _ in range(count):
        publish(msg)
        spin(0.0)
    elapsed = time.perf_counter() - start
    assert got[0] == count, got
    if api == "rclpy":
        rclpy.shutdown()
    else:
        ctx.shutdown()
    return elapsed / count * 1e6


_START = {
    "rclpy": "import rclpy; rclpy.init(args=[], domain_id={d}); rclpy.create_node('n')",
    "robomodel": "from robomodel.runtime import Context; Context('zenoh', domain_id={d}).create_node('n')",
}


def _start_s(api: str) -> float:
    code = (
        "import time; t0 = time.perf_counter(); "
        + _START[api].format(d=DOMAIN)
        + "; print(time.perf_counter() - t0, flush=True); import os; os._exit(0)"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return float(run.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--role", choices=["pub", "sub"])
    parser.add_argument("--api", choices=["rclpy", "robomodel"], default="robomodel")
    parser.add_argument("--seconds", type=float, default=5.0)
    parser.add_argument("--rate", type=float, default=1000.0)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--starts", type=int, default=9)
    args = parser.parse_args()
    if args.role == "pub":
        role_pub(args.api, args.seconds, args.rate)
        return
    if args.role == "sub":
        role_sub(args.api, args.seconds)
        return
    os.environ.pop("ROBOMODEL_RCLPY_BUS", None)
    results: dict[str, list[dict[str, float]]] = {"robomodel": [], "rclpy": []}
    for round_ in range(args.rounds):
        for api in ("robomodel", "rclpy"):
            got = _pubsub_round(api, args.seconds, args.rate)
            results[api].append(got)
            print(f"round {round_ + 1} {api:9s}: {got['received']}/{got['sent']} received, "
                  f"p50 {got['p50_us']:.0f} us, p99 {got['p99_us']:.0f} us", flush=True)  # fmt: skip
    med = {
        api: {k: statistics.median(r[k] for r in rows) for k in ("p50_us", "p99_us")}
        for api, rows in results.items()
    }
    for key in ("p50_us", "p99_us"):
        ratio = med["rclpy"][key] / med["robomodel"][key]
        print(f"1 kHz pub->sub {key[:3]}: robomodel {med['robomodel'][key]:.0f} us, "
              f"rclpy {med['rclpy'][key]:.0f} us, ratio {ratio:.2f} (target <= 1.2)")  # fmt: skip
    costs: dict[str, list[float]] = {"robomodel": [], "rclpy": []}
    for _ in range(args.rounds):
        for api in ("robomodel", "rclpy"):
            costs[api].append(_inproc_us(api))
    best = {api: min(values) for api, values in costs.items()}
    print(f"in-process publish -> callback: robomodel {best['robomodel']:.1f} us, "
          f"rclpy {best['rclpy']:.1f} us, ratio {best['rclpy'] / best['robomodel']:.2f}")  # fmt: skip
    starts: dict[str, list[float]] = {"robomodel": [], "rclpy": []}
    for _ in range(args.starts):
        for api in ("robomodel", "rclpy"):
            starts[api].append(_start_s(api))
    robomodel_s, rclpy_s = (statistics.median(starts[a]) for a in ("robomodel", "rclpy"))
    print(f"start-up to a node: robomodel {robomodel_s * 1e3:.0f} ms, rclpy {rclpy_s * 1e3:.0f} ms, "
          f"ratio {rclpy_s / robomodel_s:.2f} (target <= 1.5)")  # fmt: skip


if __name__ == "__main__":
    main()
