"""What gazebo_ros's rate for /gazebo/model_states and /gazebo/link_states costs on a ROS 1 graph.

Run: ``.venv/bin/python bench/bench_states_rate.py [--seconds 3] [--rounds 3]``.

The UR5 of bench_sim (six PID position controllers and the joint state broadcaster, /clock at
100 Hz, 1 kHz physics) with its SimBridge on robomodel's own ROS 1 master, twice: with the
controller manager at 1 kHz (gazebo_ros_control's default, the physics rate: Python runs at
every step anyway), and with no controllers, the arm hanging (MuJoCo steps 10 steps per call
between /clock ticks while nobody subscribes). ROS 1 graphs
publish the states at every physics step while the topics have subscribers (as gazebo_ros),
none without, so stepping stays batched then. Each round runs, side by side:

- idle: nobody subscribes to the states;
- subscribed: Debian's ``rostopic hz`` on both topics (two processes, outside this one).

and prints, for each, the real-time factor as fast as possible (by wall time and by this
process's CPU time, writer threads included) and the CPU this process takes at real time
(``real_time_factor=1``; a fraction of one core). Medians over the rounds.
"""

from __future__ import annotations

import argparse
import os
import shutil
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import ros1_env
from bench_sim import HOME, JOINTS, UR5_PID_YAML, _ur5_effort

TOPICS = ("/gazebo/model_states", "/gazebo/link_states")


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


def _scene(master: str, manager_rate_hz: float | None):  # type: ignore[no-untyped-def]
    from robomodel.control.config import load_controller_config
    from robomodel.runtime import Context, ManualClock
    from robomodel.sim import Simulation
    from robomodel.sim.bus import SimBridge

    context = Context("ros1", clock=ManualClock(), master=master)
    sim = Simulation()
    sim.add_robot(_ur5_effort())
    for j, q in zip(JOINTS, HOME, strict=True):
        sim.data.joint(f"{j}_joint").qpos = q
    if manager_rate_hz is not None:
        config = load_controller_config("ur5_pid.yaml", text=UR5_PID_YAML)
        sim.control(config, context=context, update_rate_hz=manager_rate_hz)
    bridge = SimBridge(sim, context)
    return context, sim, bridge


def _measure(sim, seconds: float) -> tuple[float, float, float]:  # type: ignore[no-untyped-def]
    """(RTF by wall, RTF by CPU, CPU fraction at real time)."""
    cpu = time.process_time()
    wall = sim.run(seconds)
    cpu = time.process_time() - cpu
    paced_cpu = time.process_time()
    paced_wall = sim.run(seconds, real_time_factor=1.0)
    paced_cpu = time.process_time() - paced_cpu
    return seconds / wall, seconds / cpu, paced_cpu / paced_wall


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=3.0)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    port = _free_port()
    work = Path(tempfile.mkdtemp(prefix="bench-states-"))
    from tests.ros1wire.test_gazebo_topics import gazebo_msgs_python  # genpy's gazebo_msgs

    base = ros1_env(work, port)
    env = {**base, "PYTHONPATH": str(gazebo_msgs_python(work))}  # rostopic's
    robomodel = [sys.executable, "-m", "robomodel.cli.main"]
    master = subprocess.Popen(
        [*robomodel, "master", "--port", str(port)],
        env={**os.environ, **base, "PATH": os.environ["PATH"]},
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    try:
        time.sleep(2.0)  # the master's port (a benchmark may wait; tests must not)
        print(
            f"UR5, 1 kHz physics, {args.seconds:g} s of sim time per run, medians of {args.rounds}"
        )
        print(f"{'':<28}{'RTF (wall)':>12}{'RTF (CPU)':>12}{'CPU at RTF 1':>14}")
        for manager_rate_hz in (1000.0, None):
            results = _rounds(f"http://localhost:{port}/", env, manager_rate_hz, args)
            for name, rows in results.items():
                wall, cpu, paced = (statistics.median(c) for c in zip(*rows, strict=True))
                scene = "no controllers" if manager_rate_hz is None else "manager 1 kHz"
                label = f"{scene}, {name}"
                print(f"{label:<28}{wall:>11.1f}x{cpu:>11.1f}x{paced:>13.0%}")
    finally:
        master.terminate()
        master.wait()
        shutil.rmtree(work, ignore_errors=True)  # ROS_HOME and the generated gazebo_msgs


def _rounds(
    master: str, env: dict[str, str], manager_rate_hz: float | None, args: argparse.Namespace
) -> dict[str, list[tuple[float, float, float]]]:
    results: dict[str, list[tuple[float, float, float]]] = {"idle": [], "subscribed": []}
    context, sim, bridge = _scene(master, manager_rate_hz)
    pubs = [p for p in bridge.node._publishers if p.topic in TOPICS]
    for _ in range(args.rounds):
        results["idle"].append(_measure(sim, args.seconds))
        hz = [
            subprocess.Popen(
                ["/usr/bin/rostopic", "hz", topic],
                env=env,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )
            for topic in TOPICS
        ]
        deadline = time.monotonic() + 60.0
        while not all(p.get_subscription_count() for p in pubs):
            if time.monotonic() > deadline or any(h.poll() is not None for h in hz):
                raise SystemExit("rostopic hz did not subscribe within 60 s")
            sim.run(0.01, real_time_factor=1.0)
        results["subscribed"].append(_measure(sim, args.seconds))
        for proc in hz:
            proc.terminate()
            proc.wait()
        while any(p.get_subscription_count() for p in pubs):
            sim.run(0.01, real_time_factor=1.0)
    context.shutdown()
    return results


if __name__ == "__main__":
    main()
