"""The simulated control loop equals a hand-written one, to rounding.

Six effort_controllers/JointPositionController (PID with i = 0) on the UR5 through the
controller manager, resource manager and simulated hardware must give the same trajectory as
a plain loop: read qpos, effort = p e + d (e - e_last) / dt clamped to the URDF effort limit,
write qfrc_applied, mj_step. A hardware layer that reads or writes the wrong joint, clamps
differently, or is a step late diverges from it at once.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from tests.sim.conftest import EXAMPLES

mujoco = pytest.importorskip("mujoco")

JOINTS = ("shoulder_pan", "shoulder_lift", "elbow", "wrist_1", "wrist_2", "wrist_3")
HOME = (0.0, -1.2, 1.0, -1.4, -1.57, 0.0)
GAINS = ((2000.0, 50.0),) * 3 + ((50.0, 0.1),) * 3


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


def _target(t: float, i: int) -> float:
    return HOME[i] + 0.3 * (math.sin(5.0 * t + i) - math.sin(i))


def test_ur5_pid_through_the_manager_equals_a_plain_pd_loop() -> None:
    from robomodel.control.config import load_controller_config
    from robomodel.sim import Simulation

    yaml = "".join(
        f"joint{i}_position_controller:\n  type: effort_controllers/JointPositionController\n"
        f"  joint: {j}_joint\n  pid: {{p: {p}, i: 0.0, d: {d}}}\n"
        for i, (j, (p, d)) in enumerate(zip(JOINTS, GAINS, strict=True), 1)
    )
    robot = _ur5_effort()
    sim = Simulation()
    sim.add_robot(robot)
    for j, q in zip(JOINTS, HOME, strict=True):
        sim.data.joint(f"{j}_joint").qpos = q
    model = sim.model
    ref = mujoco.MjData(model)
    ref.qpos[:] = sim.data.qpos
    mujoco.mj_forward(model, ref)
    config = load_controller_config("pid.yaml", text=yaml)
    manager = sim.control(config, update_rate_hz=1000).manager
    controllers = [manager.entries[f"joint{i}_position_controller"].controller for i in range(1, 7)]

    def command(t: float) -> None:
        for i, c in enumerate(controllers):
            c.set_command(_target(t, i))  # type: ignore[attr-defined]

    sim.every(100.0, command, order=-2)
    qadr = [int(model.joint(f"{j}_joint").qposadr[0]) for j in JOINTS]
    dadr = [int(model.joint(f"{j}_joint").dofadr[0]) for j in JOINTS]
    limit = [
        robot.joint(f"{j}_joint").limit.effort  # type: ignore[union-attr]
        for j in JOINTS
    ]
    dt = sim.timestep_s
    steps = 1500
    setpoint = [ref.qpos[a] for a in qadr]  # starting(): hold the current position
    last_error = [0.0] * 6  # the PID's first derivative differentiates against 0
    for k in range(steps):
        if k % round(1.0 / (100.0 * dt)) == 0:
            setpoint = [_target(ref.time, i) for i in range(6)]
        for i in range(6):
            error = setpoint[i] - ref.qpos[qadr[i]]
            p, d = GAINS[i]
            effort = p * error + 0.0 + d * ((error - last_error[i]) / dt)
            last_error[i] = error
            ref.qfrc_applied[dadr[i]] = min(max(effort, -limit[i]), limit[i])
        mujoco.mj_step(model, ref)
    sim.step(steps)

    assert sim.data.time == pytest.approx(ref.time, abs=1e-12)
    moved = np.abs(ref.qpos[qadr] - np.asarray(HOME)).max()
    assert moved > 0.05  # the arm followed the moving set points: not a trivial comparison
    np.testing.assert_allclose(sim.data.qpos, ref.qpos, rtol=0.0, atol=1e-12)
    np.testing.assert_allclose(sim.data.qvel, ref.qvel, rtol=0.0, atol=1e-12)
