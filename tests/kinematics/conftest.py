"""Robots shared by the kinematics tests."""

from __future__ import annotations

import pytest

from robomodel.description import read_urdf
from robomodel.kinematics import Kinematics
from tests.conftest import example_robot_data_dir

PANDA = example_robot_data_dir() / "panda_description/urdf/panda.urdf"
UR5 = example_robot_data_dir() / "ur_description/urdf/ur5_robot.urdf"


@pytest.fixture(scope="session")
def panda() -> Kinematics:
    return Kinematics(read_urdf(str(PANDA)).robot)


@pytest.fixture(scope="session")
def ur5() -> Kinematics:
    return Kinematics(read_urdf(str(UR5)).robot)
