"""The simulation scenarios, headless and faster than real time (physics 1 kHz, controllers in the loop)."""

from __future__ import annotations

import numpy as np

from robomodel.loading import load
from robomodel.sim import Simulation

from .conftest import RRBOT, RRBOT_YAML, UR5, UR5_YAML


def test_rrbot_pid_position_controllers_reach_and_settle() -> None:
    """Seed 000: effort PID (p 100, i 0.01, d 10) to 1.5 and 1.0 rad.

    With these gains the arm settles where p * error balances gravity (the integral gain is
    too small to matter within seconds), so the settled error is checked against gravity
    torques from robomodel's own dynamics (RNEA, independent of MuJoCo).
    """
    from robomodel.kinematics import Kinematics

    robot = load(str(RRBOT))
    sim = Simulation()
    sim.add_robot(robot)
    manager = sim.control(RRBOT_YAML).manager
    manager.entries["joint1_position_controller"].controller.set_command(1.5)  # type: ignore[attr-defined]
    manager.entries["joint2_position_controller"].controller.set_command(1.0)  # type: ignore[attr-defined]
    sim.step(6000)
    q = np.array([sim.data.joint("joint1").qpos[0], sim.data.joint("joint2").qpos[0]])
    qd = np.array([sim.data.joint("joint1").qvel[0], sim.data.joint("joint2").qvel[0]])
    assert np.abs(qd).max() < 1e-3  # settled
    assert np.abs(q - [1.5, 1.0]).max() < 0.2  # reached
    kin = Kinematics(robot)
    gravity = kin.dynamics().gravity(kin.q_from_dict({"joint1": q[0], "joint2": q[1]}))
    np.testing.assert_allclose(100.0 * (np.array([1.5, 1.0]) - q), gravity, rtol=0.02, atol=0.02)


def test_ur5_position_controllers_follow_a_trajectory() -> None:
    """Seed 001: six position controllers (gazebo_ros_control sets position joints directly)."""
    sim = Simulation()
    sim.add_robot(load(str(UR5)))
    manager = sim.control(UR5_YAML).manager
    controllers = [manager.entries[f"joint{i}_position_controller"].controller for i in range(1, 7)]
    joints = sim.robot().joints
    errors = []
    for k in range(1, 101):  # 2 s sampled at 50 Hz: q_i(t) = 0.5 sin(2 pi 0.5 t + i)
        t = k * 0.02
        target = [0.5 * np.sin(np.pi * t + i) for i in range(6)]
        for c, value in zip(controllers, target, strict=True):
            c.set_command([value])  # type: ignore[attr-defined]
        sim.step(20)
        q = [sim.data.joint(j).qpos[0] for j in joints]
        errors.append(np.abs(np.subtract(q, target)).max())
    assert max(errors) < 1e-3
