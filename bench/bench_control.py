"""Controller-manager loop benchmark: UR5, six effort PID position controllers + JSB.

Run: ``.venv/bin/python bench/bench_control.py [--cycles 200000] [--rounds 7]``.

The hardware is mock_components/GenericSystem with, per joint, an effort command and position,
velocity and effort states (effort mirrors the command; no dynamics, so this is the pure
read -> update -> write cost). Three variants: (1) no bus: controllers without nodes, the pure
loop; (2) in-process bus: joint_state_broadcaster also builds and publishes a JointState every
cycle (no subscriber); (3) like (2) plus command limits on every joint. Prints cycles/s
(median of the rounds) and microseconds per cycle.
"""

from __future__ import annotations

import argparse
import gc
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import example_robot_data

ROBOT = "ur_description/urdf/ur5_robot.urdf"
JOINTS = (
    "shoulder_pan_joint",
    "shoulder_lift_joint",
    "elbow_joint",
    "wrist_1_joint",
    "wrist_2_joint",
    "wrist_3_joint",
)


def build(bus: str | None, limits: bool):  # type: ignore[no-untyped-def]
    import math

    from robomodel.control import ControllerManager
    from robomodel.control.hardware import (
        ComponentInfo,
        GenericSystem,
        HardwareInfo,
        InterfaceDescription,
        ResourceManager,
    )
    from robomodel.loading import load
    from robomodel.runtime import Context
    from robomodel.runtime.clock import ManualClock

    robot = load(example_robot_data(ROBOT))
    lim = 150.0 if limits else math.inf
    joints = tuple(
        ComponentInfo(
            j,
            (InterfaceDescription(j, "effort", min=-lim, max=lim),),
            tuple(InterfaceDescription(j, k) for k in ("position", "velocity", "effort")),
        )
        for j in JOINTS
    )
    rm = ResourceManager([GenericSystem(HardwareInfo("UR5", joints=joints))])
    context = None if bus is None else Context(bus, clock=ManualClock())
    cm = ControllerManager(rm, context=context, robot=robot, update_rate_hz=1000)
    cm.load_controller("jsb", "joint_state_broadcaster/JointStateBroadcaster")
    for k, j in enumerate(JOINTS):
        cm.load_controller(
            f"joint{k + 1}_position_controller",
            "effort_controllers/JointPositionController",
            {"joint": j, "pid.p": 100.0, "pid.i": 0.01, "pid.d": 10.0, "pid.i_clamp": 1.0},
        )
    cm.spawn(list(cm.entries))
    for k, name in enumerate(list(cm.entries)[1:]):
        cm.entries[name].controller.set_command(0.1 * (k + 1))  # type: ignore[attr-defined]
    return cm, context


def measure(cycles: int, rounds: int, bus: str | None, limits: bool) -> list[float]:
    cm, context = build(bus, limits)
    step = cm.step
    for _ in range(1000):
        step(0.001)
    rates = []
    for _ in range(rounds):
        gc.collect()
        t0 = time.perf_counter()
        for _ in range(cycles):
            step(0.001)
        rates.append(cycles / (time.perf_counter() - t0))
    if context is not None:
        context.shutdown()
    return rates


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--cycles", type=int, default=100_000)
    parser.add_argument("--rounds", type=int, default=7)
    args = parser.parse_args()
    print(
        f"UR5, 6 x effort_controllers/JointPositionController + JSB; {args.cycles} cycles x {args.rounds} rounds"
    )
    for label, bus, limits in (
        ("pure loop (no bus)", None, False),
        ("JSB publishing on inproc bus", "inproc", False),
        ("inproc bus + command limits", "inproc", True),
    ):
        rates = measure(args.cycles, args.rounds, bus, limits)
        median = statistics.median(rates)
        print(
            f"{label:32s} median {median / 1000:7.1f} kHz  ({1e6 / median:6.2f} us/cycle; best {max(rates) / 1000:.1f} kHz)"
        )


if __name__ == "__main__":
    main()
