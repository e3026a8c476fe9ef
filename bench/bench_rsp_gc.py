"""robot_state_publisher in one process: latency per /joint_states message and the garbage
collector's pauses meanwhile (is the collector on the hot path?).

Run: ``.venv/bin/python bench/bench_rsp_gc.py [--messages 20000]``.

talos_full_v2 (32 joints per message), the in-process bus: each message is published, the
executor runs robot_state_publisher's callback (FK of the 32 joints, one TFMessage) and a /tf
subscriber's, timed from publish to return. A long-lived heap of 300,000 small objects stands
in for a real process's set-up (models, modules). Two interleaved variants: the collector as
Python sets it, and after ``gc.collect(); gc.freeze()`` (set-up objects out of its view). A
``gc.callbacks`` hook records every collection's generation and duration during the timed part.
"""

from __future__ import annotations

import argparse
import gc
import statistics
import sys
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import example_robot_data

ROBOT = "talos_data/robots/talos_full_v2.urdf"


def run(messages: int, freeze: bool) -> tuple[list[float], list[tuple[int, float]]]:
    """(per-message latencies [s], (generation, pause [s]) of each collection)."""
    from robomodel.description import read_urdf
    from robomodel.kinematics import Kinematics
    from robomodel.runtime import Context
    from robomodel.runtime.msg import Header, JointState, TFMessage, Time
    from robomodel.runtime.nodes.robot_state_publisher import RobotStatePublisher

    text = example_robot_data(ROBOT).read_text()
    names = list(Kinematics(read_urdf(text).robot).joint_names)
    ctx = Context()
    RobotStatePublisher(ctx, text, parameters={"ignore_timestamp": True})
    got: list[TFMessage] = []
    ctx.create_node("sink").create_subscription(TFMessage, "/tf", got.append, 10)
    pub = ctx.create_node("driver").create_publisher(JointState, "/joint_states", 10)
    heap = [{"i": i} for i in range(300_000)]  # a real process's long-lived objects
    if freeze:
        gc.collect()
        gc.freeze()
    pauses: list[tuple[int, float]] = []
    began = [0.0]

    def on_gc(phase: str, info: dict[str, Any]) -> None:
        if phase == "start":
            began[0] = time.perf_counter()
        else:
            pauses.append((int(info["generation"]), time.perf_counter() - began[0]))

    gc.callbacks.append(on_gc)
    latencies = []
    positions = [0.0] * len(names)
    try:
        for i in range(messages):
            positions[0] = 0.001 * i
            start = time.perf_counter()
            pub.publish(JointState(Header(Time.from_seconds(i * 1e-3)), names, list(positions)))
            ctx.spin_once(0.0)
            latencies.append(time.perf_counter() - start)
            got.clear()
    finally:
        gc.callbacks.remove(on_gc)
        if freeze:
            gc.unfreeze()
        ctx.shutdown()
    assert len(heap) == 300_000
    return latencies, pauses


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--messages", type=int, default=20_000)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    for k in range(args.rounds):
        for freeze in (False, True):
            lat, pauses = run(args.messages, freeze)
            lat.sort()
            by_gen = {g: [p for gg, p in pauses if gg == g] for g in (0, 1, 2)}
            print(
                f"round {k + 1} {'gc.freeze()' if freeze else 'default gc '}: p50 "
                f"{statistics.median(lat) * 1e3:.3f} ms, p99 {lat[int(0.99 * len(lat))] * 1e3:.3f}"
                f" ms, max {lat[-1] * 1e3:.3f} ms; collections "
                + ", ".join(
                    f"gen{g} {len(v)} (max {max(v, default=0.0) * 1e3:.2f} ms)"
                    for g, v in by_gen.items()
                ),
                flush=True,
            )


if __name__ == "__main__":
    main()
