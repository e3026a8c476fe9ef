"""Analytic UR IK: parameters measured on the model, every solution reproduces the target."""

from __future__ import annotations

import math

import numpy as np
import pytest

from robomodel.description import read_urdf
from robomodel.kinematics import Kinematics
from robomodel.kinematics.se3 import log_rotation
from robomodel.kinematics.ur import NotAnalyticError
from tests.conftest import example_robot_data_dir

UR = example_robot_data_dir() / "ur_description/urdf"


def test_ur5_parameters_are_seed_001s_dh_table(ur5: Kinematics) -> None:
    g = ur5.ur_geometry("tool0")
    # Seed 001: d1 0.089159, a2 -0.425, a3 -0.39225, d4 0.10915, d5 0.09465, d6 0.0823.
    assert (g.d1, g.a2, g.a3, g.d4, g.d5, g.d6) == pytest.approx(
        (0.089159, 0.425, 0.39225, 0.10915, 0.09465, 0.0823), abs=1e-12
    )


@pytest.mark.parametrize(
    "name", ["ur3_robot.urdf", "ur5_robot.urdf", "ur10_robot.urdf", "ur5_joint_limited_robot.urdf"]
)
@pytest.mark.parametrize("link", ["tool0", "wrist_3_link"])
def test_every_solution_reproduces_the_target(name: str, link: str) -> None:
    kin = Kinematics(read_urdf(str(UR / name)).robot)
    counts = []
    for q in kin.random_q(40, seed=8):
        T = kin.fk_link(q, link)
        solutions = kin.analytic_ik(T, link)
        counts.append(len(solutions))
        assert 1 <= len(solutions) <= 8
        for s in solutions:
            assert np.all(s >= kin.lower) and np.all(s <= kin.upper)
            T_s = kin.fk_link(s, link)
            assert np.linalg.norm(T_s[:3, 3] - T[:3, 3]) < 1e-9
            assert np.linalg.norm(log_rotation(T[:3, :3] @ T_s[:3, :3].T)) < 1e-9
        # The configuration the target came from is one of them (modulo 2 pi).
        diff = (solutions - q + math.pi) % (2 * math.pi) - math.pi
        assert np.min(np.max(np.abs(diff), axis=1)) < 1e-7
    assert max(counts) == 8


def test_unreachable_gives_no_solution(ur5: Kinematics) -> None:
    T = np.eye(4)
    T[:3, 3] = [3.0, 0.0, 0.0]
    assert ur5.analytic_ik(T, "tool0").shape == (0, 6)


def test_not_a_ur_arm(panda: Kinematics) -> None:
    with pytest.raises(NotAnalyticError, match="exactly 6 revolute"):
        panda.analytic_ik(np.eye(4), "panda_hand")
    with pytest.raises(NotAnalyticError, match="exactly 6 revolute"):
        panda.analytic_ik(np.eye(4), "panda_hand")  # cached refusal, same message
