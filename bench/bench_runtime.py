"""Runtime benchmark: /joint_states at 1 kHz from process A into robot_state_publisher in
process B, /tf received in process C, over Zenoh on loopback, for a 60-link robot.

Run: ``.venv/bin/python bench/bench_runtime.py [--seconds 10] [--rate 1000]``.

Prints the sustained rates, the latency from A's publish to C's receipt of the matching /tf
(p50/p99/max, from the JointState stamp: all processes share the machine's clock) and the CPU
use of each process. robot_state_publisher runs with ignore_timestamp so that every message
produces /tf (its default publish_frequency of 20 Hz would rate-limit to 20 Hz).
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import example_robot_data

ROBOT = "talos_data/robots/talos_full_v2.urdf"


def _cpu_s(pid: int) -> float:
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def role_rsp(domain: int) -> None:
    from robomodel.runtime import Context
    from robomodel.runtime.nodes.robot_state_publisher import RobotStatePublisher

    with Context("zenoh", domain_id=domain) as ctx:
        text = example_robot_data(ROBOT).read_text()
        RobotStatePublisher(ctx, text, parameters={"ignore_timestamp": True})
        print("ready", flush=True)
        with contextlib.suppress(KeyboardInterrupt):
            ctx.spin()


def role_sink(domain: int, seconds: float) -> None:
    from robomodel.runtime import Context
    from robomodel.runtime.msg import TFMessage

    latencies: list[float] = []
    arrivals: list[float] = []
    with Context("zenoh", domain_id=domain) as ctx:
        node = ctx.create_node("sink")

        def on_tf(msg: TFMessage) -> None:
            now = time.time()
            stamp = msg.transforms[0].header.stamp
            latencies.append(now - (stamp.sec + stamp.nanosec * 1e-9))
            arrivals.append(time.monotonic())

        node.create_subscription(TFMessage, "/tf", on_tf, 1000)
        print("ready", flush=True)
        ctx.spin(duration_s=seconds)
    print(json.dumps({"latencies": latencies, "arrivals": arrivals}), flush=True)


def _percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(q * len(ordered)))]


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--rate", type=float, default=1000.0)
    parser.add_argument("--role", choices=("driver", "rsp", "sink"), default="driver")
    parser.add_argument("--domain", type=int, default=77)
    args = parser.parse_args()
    if args.role == "rsp":
        role_rsp(args.domain)
        return
    if args.role == "sink":
        role_sink(args.domain, args.seconds + 6.0)
        return

    from robomodel.description import read_urdf
    from robomodel.kinematics import Kinematics
    from robomodel.runtime import Context
    from robomodel.runtime.msg import Header, JointState, Time

    robot = read_urdf(example_robot_data(ROBOT)).robot
    names = list(Kinematics(robot).joint_names)
    me = [sys.executable, __file__, "--domain", str(args.domain), "--seconds", str(args.seconds)]
    rsp = subprocess.Popen([*me, "--role", "rsp"], stdout=subprocess.PIPE, text=True)
    sink = subprocess.Popen([*me, "--role", "sink"], stdout=subprocess.PIPE, text=True)
    for proc in (rsp, sink):
        assert proc.stdout is not None and proc.stdout.readline().strip() == "ready"
    with Context("zenoh", domain_id=args.domain) as ctx:
        pub = ctx.create_node("driver").create_publisher(JointState, "/joint_states", 1000)
        time.sleep(2.0)  # let the three peers link up
        cpu0 = {p.pid: _cpu_s(p.pid) for p in (rsp, sink)}
        own0 = time.process_time()
        period = 1.0 / args.rate
        start = time.perf_counter()
        sent = 0
        positions = [0.0] * len(names)
        while True:
            now = time.perf_counter()
            if now - start >= args.seconds:
                break
            target = start + sent * period
            if now < target:
                time.sleep(max(0.0, target - now - 0.0001))
                continue
            stamp = Time.from_seconds(time.time())
            positions[0] = 0.001 * sent
            pub.publish(JointState(Header(stamp), names, list(positions)))
            sent += 1
        elapsed = time.perf_counter() - start
        own_cpu = time.process_time() - own0
        cpu = {p.pid: _cpu_s(p.pid) - cpu0[p.pid] for p in (rsp, sink)}
    out, _ = sink.communicate(timeout=30)
    rsp.terminate()
    rsp.wait(timeout=10)
    data = json.loads(out.strip().splitlines()[-1])
    lat = data["latencies"]
    arrivals = data["arrivals"]
    received_rate = (len(arrivals) - 1) / (arrivals[-1] - arrivals[0]) if len(arrivals) > 1 else 0.0
    print(f"robot: talos_full_v2 ({len(robot.links)} links, {len(names)} joints in each message)")
    print(f"A published {sent} /joint_states in {elapsed:.2f} s: {sent / elapsed:.1f} Hz")
    print(f"C received {len(lat)} /tf ({len(lat) / sent:.1%}): sustained {received_rate:.1f} Hz")
    if lat:
        print(
            f"latency A->B->C: p50 {statistics.median(lat) * 1e3:.3f} ms, "
            f"p99 {_percentile(lat, 0.99) * 1e3:.3f} ms, max {max(lat) * 1e3:.3f} ms"
        )
    print(
        f"CPU: A (publisher) {own_cpu / elapsed:.0%}, B (robot_state_publisher) "
        f"{cpu[rsp.pid] / elapsed:.0%}, C (/tf subscriber) {cpu[sink.pid] / elapsed:.0%} of one core"
    )


if __name__ == "__main__":
    main()
