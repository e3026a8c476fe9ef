"""rospy's face against robomodel's own node API on the ROS 1 bus: a 1 kHz publisher ->
subscriber across two processes, and the time to make a node.

Run: ``.venv/bin/python bench/bench_rospy.py [--seconds 5] [--rate 1000] [--rounds 3]``.

Both variants run on robomodel's own master (``robomodel master``), one process publishing
``std_msgs/String`` at ``--rate`` Hz and another subscribing, over TCPROS. robomodel: a
``Context("ros1")`` node's ``create_publisher``/``create_subscription``, the subscriber spinning
its context on the main thread. rospy: ``rospy.init_node``, ``rospy.Publisher(queue_size=100)``
and ``rospy.Subscriber``, then ``rospy.spin()`` (callbacks on the topic's callback thread, as
rospy's). Each message carries ``time.monotonic_ns()`` at publish in its text (one clock for
every process of a Linux machine); the callback subtracts it. Rounds alternate the two, so the
machine's load falls on both alike. Target: rospy's p50 and p99 within 1.2x robomodel's.

Node start-up: in a fresh process, ``import rospy; rospy.init_node('n')`` against ``from
robomodel.runtime.context import Context; Context("ros1").create_node("n")``, from before the
import until the node is registered, medians of ``--starts`` processes each.
"""

from __future__ import annotations

import argparse
import json
import os
import socket
import statistics
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import paced_sends

TOPIC = "/bench_rospy"
_STOP = "stop"


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


# -- the processes ------------------------------------------------------------------------------
def subscriber(variant: str) -> None:
    latencies: list[int] = []
    done = []

    def on_message(msg: object) -> None:
        text = msg.data  # type: ignore[attr-defined]
        if text == _STOP:
            done.append(True)
            return
        latencies.append(time.monotonic_ns() - int(text))

    if variant == "rospy":
        import rospy
        from std_msgs.msg import String

        rospy.init_node("bench_sub", disable_signals=True)
        rospy.Subscriber(TOPIC, String, on_message, queue_size=1000)
        print("ready", flush=True)
        while not done:
            time.sleep(0.05)
        rospy.signal_shutdown("done")
    else:
        from robomodel.runtime.context import Context
        from robomodel.runtime.msg import String

        context = Context("ros1")
        node = context.create_node("bench_sub")
        node.create_subscription(String, TOPIC, on_message, 1000)
        print("ready", flush=True)
        context.spin(until=lambda: bool(done))
        context.shutdown()
    print(json.dumps(latencies), flush=True)


def publisher(variant: str, seconds: float, rate_hz: float) -> None:
    if variant == "rospy":
        import rospy
        from std_msgs.msg import String

        rospy.init_node("bench_pub", disable_signals=True)
        pub = rospy.Publisher(TOPIC, String, queue_size=100)
        connected = pub.get_num_connections
    else:
        from robomodel.runtime.context import Context
        from robomodel.runtime.msg import String

        context = Context("ros1")
        pub = context.create_node("bench_pub").create_publisher(String, TOPIC, 100)
        connected = pub.get_subscription_count
    while connected() < 1:
        time.sleep(0.01)
    time.sleep(0.2)  # the subscriber's reader is connected once the count says so; let it settle
    paced_sends(seconds, rate_hz, lambda k: pub.publish(String(data=str(time.monotonic_ns()))))
    for _ in range(20):  # the stop word, until the subscriber has surely read it
        pub.publish(String(data=_STOP))
        time.sleep(0.05)
    if variant == "rospy":
        rospy.signal_shutdown("done")
    else:
        context.shutdown()


def start_node(variant: str) -> None:
    start = time.perf_counter()
    if variant == "rospy":
        import rospy

        rospy.init_node("bench_start", disable_signals=True)
        elapsed = time.perf_counter() - start
        rospy.signal_shutdown("done")
    else:
        from robomodel.runtime.context import Context

        context = Context("ros1")
        context.create_node("bench_start")
        elapsed = time.perf_counter() - start
        context.shutdown()
    print(json.dumps(elapsed), flush=True)


# -- the runs -----------------------------------------------------------------------------------
def _run_pair(variant: str, env: dict[str, str], args: argparse.Namespace) -> list[int]:
    me = [sys.executable, __file__]
    sub = subprocess.Popen(
        [*me, "--role", "sub", "--variant", variant], stdout=subprocess.PIPE, text=True, env=env
    )
    assert sub.stdout is not None
    assert sub.stdout.readline().strip() == "ready"
    pub = subprocess.run(
        [*me, "--role", "pub", "--variant", variant, "--seconds", str(args.seconds),
         "--rate", str(args.rate)],
        env=env, check=True,
    )  # fmt: skip
    del pub
    latencies: list[int] = json.loads(sub.stdout.readline())
    sub.wait()
    return latencies


def _percentile(values: list[int], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(q * len(ordered)))] / 1e3


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=5.0)
    parser.add_argument("--rate", type=float, default=1000.0)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--starts", type=int, default=7)
    parser.add_argument("--role", choices=("sub", "pub", "start"))
    parser.add_argument("--variant", choices=("robomodel", "rospy"))
    args = parser.parse_args()
    if args.role == "sub":
        subscriber(args.variant)
        return
    if args.role == "pub":
        publisher(args.variant, args.seconds, args.rate)
        return
    if args.role == "start":
        start_node(args.variant)
        return
    port = _free_port()
    env = {**os.environ, "ROS_MASTER_URI": f"http://127.0.0.1:{port}/", "ROS_IP": "127.0.0.1"}
    master = subprocess.Popen(
        [sys.executable, "-m", "robomodel.cli.main", "master", "--port", str(port)],
        env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )  # fmt: skip
    try:
        time.sleep(2.0)  # the master's port (a benchmark may wait; tests must not)
        print(
            f"1 kHz std_msgs/String over TCPROS, {args.seconds:g} s per run, {args.rounds} rounds"
        )
        print(f"load average at start: {os.getloadavg()[0]:.1f}")
        rows: dict[str, list[tuple[float, float, int]]] = {"robomodel": [], "rospy": []}
        for _ in range(args.rounds):
            for variant in rows:
                found = _run_pair(variant, env, args)
                rows[variant].append(
                    (_percentile(found, 0.5), _percentile(found, 0.99), len(found))
                )
        print(f"{'':<12}{'p50 [us]':>10}{'p99 [us]':>10}{'received':>10}")
        medians = {}
        for variant, results in rows.items():
            p50 = statistics.median(r[0] for r in results)
            p99 = statistics.median(r[1] for r in results)
            got = statistics.median(r[2] for r in results)
            medians[variant] = (p50, p99)
            print(f"{variant:<12}{p50:>10.0f}{p99:>10.0f}{got:>10.0f}")
        ratio50 = medians["rospy"][0] / medians["robomodel"][0]
        ratio99 = medians["rospy"][1] / medians["robomodel"][1]
        print(f"rospy / robomodel: p50 {ratio50:.2f}x, p99 {ratio99:.2f}x")
        starts: dict[str, list[float]] = {"robomodel": [], "rospy": []}
        for _ in range(args.starts):
            for variant in starts:
                out = subprocess.run(
                    [sys.executable, __file__, "--role", "start", "--variant", variant],
                    env=env, capture_output=True, text=True, check=True,
                )  # fmt: skip
                starts[variant].append(json.loads(out.stdout.strip().splitlines()[-1]))
        for variant, times in starts.items():
            print(f"node start-up, {variant}: {statistics.median(times) * 1e3:.0f} ms")
        ratio = statistics.median(starts["rospy"]) / statistics.median(starts["robomodel"])
        print(f"rospy / robomodel start-up: {ratio:.2f}x")
    finally:
        master.terminate()
        master.wait()


if __name__ == "__main__":
    main()
