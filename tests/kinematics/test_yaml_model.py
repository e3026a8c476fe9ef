"""Seed 004's kinematics YAML: model, URDF output, FK by hand, errors."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from robomodel.description import read_urdf
from robomodel.errors import InputError
from robomodel.kinematics import Kinematics
from robomodel.kinematics.yaml_model import kinematics_yaml_to_urdf, read_kinematics_yaml

# The seed's kinematics_parameters.yaml, as its slides show it.
SEED = """
base:
  orientation: 0.0 0.0 0.0
  position: 0.0 0.0 0.0
types:
  - revolute
  - revolute
  - revolute
links:
  - orientation: 0.0 0.0 0.0
    position: 0.0 0.0 0.2
  - orientation: 0.0 -1.5707963267948966 -1.5707963267948966
    position: 0.0 -0.12 0.0
  - orientation: 0.0 0.0 0.0
    position: 0.25 0.0 0.1
joints:
  - lower: -3.141592653589793
    upper: 3.141592653589793
    velocity: 1000.0
    effort: 1000.0
  - lower: -3.141592653589793
    upper: 3.141592653589793
    velocity: 1000.0
    effort: 1000.0
  - lower: -3.141592653589793
    upper: 3.141592653589793
    velocity: 1000.0
    effort: 1000.0
end_effector:
  orientation: 1.5707963267948966 0.0 1.5707963267948966
  position: 0.28 0.0 0.0
"""


def test_seed_robot_structure(tmp_path: Path) -> None:
    path = tmp_path / "kinematics_parameters.yaml"
    path.write_text(SEED)
    robot = read_kinematics_yaml(str(path))
    assert [link.name for link in robot.links] == [
        "base",
        "link_0",
        "link_1",
        "link_2",
        "link_3",
        "end_effector",
    ]
    assert [j.name for j in robot.joints] == [
        "base_offset",
        "joint_1",
        "joint_2",
        "joint_3",
        "end_effector_offset",
    ]
    assert robot.joint("joint_2").origin.rpy_rad == (0.0, -math.pi / 2, -math.pi / 2)
    assert (
        robot.joint("joint_1").limit is not None and robot.joint("joint_1").limit.velocity == 1000.0
    )


def test_urdf_round_trip_and_fk() -> None:
    urdf = kinematics_yaml_to_urdf(SEED)
    robot = read_urdf(urdf).robot
    assert robot == read_kinematics_yaml(SEED)
    kin = Kinematics(robot)
    assert kin.joint_names == ("joint_1", "joint_2", "joint_3")
    # At zero: z 0.2 up; joint 2's frame has x -> -z... check the end effector by composing by hand.
    T = np.eye(4)
    for joint in robot.joints:
        T = T @ joint.origin.matrix()
    np.testing.assert_allclose(kin.fk_link([0, 0, 0], "end_effector"), T, atol=1e-15)
    # joint_1 turns everything above it about the base z axis.
    Rz = np.array(
        [[0.0, -1.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0, 0, 0, 1.0]]
    )
    np.testing.assert_allclose(kin.fk_link([math.pi / 2, 0, 0], "end_effector"), Rz @ T, atol=1e-12)


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (
            ("- revolute\nlinks", "- revolut\nlinks"),
            "unknown joint type 'revolut' (did you mean 'revolute'?)",
        ),
        (
            ("position: 0.28 0.0 0.0", "position: 0.28 0.0"),
            "end_effector.position must be three finite numbers",
        ),
        (
            (
                "  - lower: -3.141592653589793\n    upper: 3.141592653589793\n    velocity: 1000.0\n    effort: 1000.0\nend",
                "end",
            ),
            "same length",
        ),
        (
            (
                "velocity: 1000.0\n    effort: 1000.0\nend",
                "velocty: 1000.0\n    effort: 1000.0\nend",
            ),
            "did you mean 'velocity'",
        ),
    ],
)
def test_errors_name_the_key(edit: tuple[str, str], message: str) -> None:
    text = SEED.replace(*edit)
    assert text != SEED
    with pytest.raises(
        InputError, match=message.replace("(", r"\(").replace(")", r"\)").replace("?", r"\?")
    ):
        read_kinematics_yaml(text)
