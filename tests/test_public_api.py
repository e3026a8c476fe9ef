"""Every public name resolves; the model is immutable plain data."""

from __future__ import annotations

import dataclasses
import importlib
import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import robomodel
import robomodel.description as description
from robomodel.description import Joint, JointType, Origin, Robot
from robomodel.description.model.pose import quat_xyzw_from_rpy, rpy_from_quat_xyzw

MODULES = [
    "robomodel",
    "robomodel.bag",
    "robomodel.description",
    "robomodel.description.model",
    "robomodel.errors",
]


@pytest.mark.parametrize("module_name", MODULES)
def test_all_names_resolve(module_name: str) -> None:
    module = importlib.import_module(module_name)
    for name in module.__all__:
        assert getattr(module, name) is not None, name


def test_model_is_frozen() -> None:
    robot = description.read_urdf('<robot name="r"><link name="a"/></robot>').robot
    with pytest.raises(dataclasses.FrozenInstanceError):
        robot.name = "x"  # type: ignore[misc]
    assert isinstance(robot.links, tuple)
    inertia = description.Inertia(1, 0, 0, 1, 0, 1).matrix()
    with pytest.raises(ValueError):
        inertia[0, 0] = 2.0


def test_load_is_exported() -> None:
    assert robomodel.load is not None
    robot = robomodel.load('<robot name="r"><link name="a"/></robot>')
    assert isinstance(robot, Robot)


def test_self_loop_tree_walk_terminates() -> None:
    robot = Robot(
        "r",
        links=(description.Link("a"), description.Link("b")),
        joints=(Joint("j1", JointType.FIXED, "a", "b"), Joint("j2", JointType.FIXED, "b", "b")),
    )
    assert robot.tree().links_depth_first() == ("a", "b")
    from robomodel.description.report import check_urdf_text

    # b is listed under itself once (as check_urdf would) but not entered again.
    assert check_urdf_text(robot).endswith(
        "root Link: a has 1 child(ren)\n    child(1):  b\n        child(1):  b\n"
    )


angles = st.floats(min_value=-math.pi, max_value=math.pi, allow_nan=False)


@given(angles, st.floats(min_value=-1.5, max_value=1.5), angles)
def test_rpy_quaternion_matrix_agree(roll: float, pitch: float, yaw: float) -> None:
    T = Origin((0, 0, 0), (roll, pitch, yaw)).matrix()
    q = quat_xyzw_from_rpy(roll, pitch, yaw)
    Tq = Origin((0, 0, 0), (0, 0, 0), q).matrix()
    np.testing.assert_allclose(T, Tq, atol=1e-12)
    r2, p2, y2 = rpy_from_quat_xyzw(*q)
    np.testing.assert_allclose(Origin((0, 0, 0), (r2, p2, y2)).matrix(), T, atol=1e-9)


def test_gimbal_lock_branch() -> None:
    q = quat_xyzw_from_rpy(0.3, math.pi / 2, 0.2)
    r, p, y = rpy_from_quat_xyzw(*q)
    assert r == 0.0 and p == pytest.approx(math.pi / 2)
    T = Origin((0, 0, 0), (0.3, math.pi / 2, 0.2)).matrix()
    np.testing.assert_allclose(Origin((0, 0, 0), (r, p, y)).matrix(), T, atol=1e-6)
