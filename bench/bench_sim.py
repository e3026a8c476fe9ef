"""Simulation benchmark: real-time factor (sim seconds per wall second), headless.

Run: ``.venv/bin/python bench/bench_sim.py [--seconds 5] [--rounds 5]``.

1. UR5 (examples/ur5_description, transmissions switched to EffortJointInterface) with six
   effort_controllers/JointPositionController (PID) + joint_state_broadcaster (50 Hz) +
   robot_state_publisher on the in-process bus, physics and controller manager at 1 kHz,
   /clock at 100 Hz, following a sine trajectory. Target >= 50x real time.
2. simplebot with its 360-ray lidar at 10 Hz in the wall world, diff_drive_controller at
   100 Hz driven by a constant /cmd_vel, JSB + robot_state_publisher, ground truth at 50 Hz,
   physics at 1 kHz. Target >= 20x real time.
3. For reference: raw ``mj_step`` on the UR5 model (no Python per step) and the per-step Python
   loop of the engine with no controllers.

Each of 1 and 2 is followed by raw ``mj_step`` (``nstep``) on the same compiled model from the
same initial state (the UR5 held against gravity by a constant generalised force, simplebot with
the wheels' final servo commands); the ratio raw/ours is the Python overhead (the
target: <= 2 for the UR5, <= 1.5 for simplebot). The scenes run interleaved, round after round.

Each round builds the scene anew and runs ``--seconds`` of sim time as fast as possible;
the median over the rounds is printed (the machine is shared; take medians).
"""

from __future__ import annotations

import argparse
import dataclasses
import logging
import math
import statistics
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
HOME = (0.0, -1.2, 1.0, -1.4, -1.57, 0.0)  # arm up, clear of the ground
JOINTS = ("shoulder_pan", "shoulder_lift", "elbow", "wrist_1", "wrist_2", "wrist_3")
# Gains per joint size (the URDF has no rotor inertia, so the wrists are light).
GAINS = ("{p: 2000.0, i: 0.0, d: 50.0}",) * 3 + ("{p: 50.0, i: 0.0, d: 0.1}",) * 3
UR5_PID_YAML = (
    "joint_state_controller:\n  type: joint_state_controller/JointStateController\n"
    "  publish_rate: 50\n"
) + "".join(
    f"joint{i}_position_controller:\n  type: effort_controllers/JointPositionController\n"
    f"  joint: {j}_joint\n  pid: {g}\n"
    for i, (j, g) in enumerate(zip(JOINTS, GAINS, strict=True), 1)
)


def _ur5_effort():  # type: ignore[no-untyped-def]
    from robomodel.loading import load

    robot = load(str(EXAMPLES / "ur5_description/urdf/ur5.urdf.xacro"))
    effort = ("hardware_interface/EffortJointInterface",)
    transmissions = tuple(
        dataclasses.replace(
            t, joints=tuple(dataclasses.replace(j, hardware_interfaces=effort) for j in t.joints)
        )
        for t in robot.transmissions
    )
    return dataclasses.replace(robot, transmissions=transmissions)


def ur5_round(seconds: float) -> tuple[float, float, float, float]:
    """(real-time factor by wall time, by process CPU time, final tracking error [rad],
    raw ``mj_step`` real-time factor on the same compiled model, run right after)."""
    from robomodel.control.config import load_controller_config
    from robomodel.description.urdf.writer import urdf_to_string
    from robomodel.runtime import Context, ManualClock
    from robomodel.runtime.nodes.robot_state_publisher import RobotStatePublisher
    from robomodel.sim import Simulation
    from robomodel.sim.bus import SimBridge

    robot = _ur5_effort()
    context = Context(clock=ManualClock())
    sim = Simulation()
    sim.add_robot(robot)
    for j, q in zip(JOINTS, HOME, strict=True):
        sim.data.joint(f"{j}_joint").qpos = q
    config = load_controller_config("ur5_pid.yaml", text=UR5_PID_YAML)
    manager = sim.control(config, context=context, update_rate_hz=1000).manager
    SimBridge(sim, context)
    RobotStatePublisher(context, urdf_to_string(robot))
    controllers = [manager.entries[f"joint{i}_position_controller"].controller for i in range(1, 7)]
    targets = list(HOME)

    def command(t: float) -> None:
        for i, c in enumerate(controllers):
            targets[i] = HOME[i] + 0.3 * (math.sin(0.5 * t + i) - math.sin(i))
            c.set_command(targets[i])  # type: ignore[attr-defined]

    sim.every(50.0, command, order=-2)
    raw_data = _held_copy(sim)
    cpu = time.process_time()
    wall = sim.run(seconds)
    cpu = time.process_time() - cpu
    q = [sim.data.joint(f"{j}_joint").qpos[0] for j in JOINTS]
    error = max(abs(a - b) for a, b in zip(q, targets, strict=True))
    context.shutdown()
    return seconds / wall, seconds / cpu, error, _raw_rtf(sim, raw_data, seconds)


def _held_copy(sim):  # type: ignore[no-untyped-def]
    """A fresh ``MjData`` of ``sim``'s model in its current state, with gravity held by a
    constant generalised force (so the raw reference stays near the same pose, contacts
    and all, as the controlled arm)."""
    import mujoco

    data = mujoco.MjData(sim.model)
    data.qpos[:] = sim.data.qpos
    mujoco.mj_forward(sim.model, data)
    data.qfrc_applied[:] = data.qfrc_bias
    return data


def _raw_rtf(sim, data, seconds: float) -> float:  # type: ignore[no-untyped-def]
    """Real-time factor of plain ``mj_step`` (``nstep``: no Python per step) on ``data``."""
    import mujoco

    n = round(seconds / sim.timestep_s)
    start = time.perf_counter()
    mujoco.mj_step(sim.model, data, nstep=n)
    return seconds / (time.perf_counter() - start)


def simplebot_round(seconds: float) -> tuple[float, float, int, float]:
    """(real-time factor by wall time, by process CPU time, scans received, raw ``mj_step``
    real-time factor on the same compiled model with the wheels' final servo commands)."""
    from robomodel.description.urdf.writer import urdf_to_string
    from robomodel.loading import load
    from robomodel.runtime import Context, ManualClock
    from robomodel.runtime.msg.types.sensor_msgs import LaserScan
    from robomodel.runtime.nodes.robot_state_publisher import RobotStatePublisher
    from robomodel.sim import Placement, Simulation, read_world
    from robomodel.sim.bus import SimBridge
    from robomodel.sim.scripted import CmdVelDriver

    robot = load(str(EXAMPLES / "simplebot_description/urdf/simplebot_lidar.urdf.xacro"))
    context = Context(clock=ManualClock())
    sim = Simulation(read_world(EXAMPLES / "simplebot_description/worlds/wall.world"))
    sim.add_robot(robot, placement=Placement(xyz_m=(0.0, 0.0, 0.076)))
    system = sim.control(
        EXAMPLES / "simplebot_description/config/simplebot_controllers.yaml", context=context
    )
    SimBridge(sim, context)
    RobotStatePublisher(context, urdf_to_string(robot))
    CmdVelDriver.attach(sim, system, context, (0.1, 0.0, 0.2))
    scans: list[LaserScan] = []
    context.create_node("listener").create_subscription(LaserScan, "/scan", scans.append)
    import mujoco

    raw_data = mujoco.MjData(sim.model)
    raw_data.qpos[:] = sim.data.qpos
    cpu = time.process_time()
    wall = sim.run(seconds)
    cpu = time.process_time() - cpu
    context.shutdown()
    raw_data.ctrl[:] = sim.data.ctrl  # the wheels' velocity servos, as the controller left them
    return seconds / wall, seconds / cpu, len(scans), _raw_rtf(sim, raw_data, seconds)


def raw_round(seconds: float) -> tuple[float, float]:
    """(raw mj_step real-time factor, engine loop without controllers)."""
    import mujoco

    from robomodel.sim import Simulation

    sim = Simulation()
    sim.add_robot(_ur5_effort())
    n = round(seconds / sim.timestep_s)
    start = time.perf_counter()
    mujoco.mj_step(sim.model, sim.data, nstep=n)
    raw = seconds / (time.perf_counter() - start)
    sim.reset()
    start = time.perf_counter()
    sim.step(n)
    return raw, seconds / (time.perf_counter() - start)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--seconds", type=float, default=5.0, help="sim time per round [s]")
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args()
    print(f"simulation benchmark: {args.seconds:g} s of sim time x {args.rounds} rounds (median)")
    logging.getLogger("robomodel").setLevel(logging.ERROR)  # clamping notices, not timed
    ur5, bot, raw = [], [], []
    for _ in range(args.rounds):  # interleaved: the shared machine's load hits all alike
        ur5.append(ur5_round(args.seconds))
        bot.append(simplebot_round(args.seconds))
        raw.append(raw_round(args.seconds))
    med = statistics.median
    print(
        f"UR5 + 6 PID + JSB + RSP, 1 kHz       median {med(r[0] for r in ur5):6.1f}x "
        f"real time (best {max(r[0] for r in ur5):.1f}x; by CPU time "
        f"{med(r[1] for r in ur5):.1f}x; target >= 50x; "
        f"tracking error {ur5[-1][2]:.4f} rad)"
    )
    print(
        f"  raw mj_step, same model           median {med(r[3] for r in ur5):6.1f}x; "
        f"ratio raw/ours {med(r[3] / r[0] for r in ur5):.2f} (target <= 2)"
    )
    print(
        f"simplebot + 360-ray lidar 10 Hz       median {med(r[0] for r in bot):6.1f}x "
        f"real time (best {max(r[0] for r in bot):.1f}x; by CPU time "
        f"{med(r[1] for r in bot):.1f}x; target >= 20x; {bot[-1][2]} scans)"
    )
    print(
        f"  raw mj_step, same model           median {med(r[3] for r in bot):6.1f}x; "
        f"ratio raw/ours {med(r[3] / r[0] for r in bot):.2f} (target <= 1.5)"
    )
    print(
        f"UR5 raw mj_step (nstep)               median {med(r for r, _ in raw):6.1f}x"
        f"; engine loop, no controllers {med(e for _, e in raw):6.1f}x"
    )


if __name__ == "__main__":
    main()
