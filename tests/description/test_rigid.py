"""The scalar quaternion and pose maths against 4x4 matrices and the batched numpy forms."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from robomodel.description.model.pose import matrix_from_xyz_rpy
from robomodel.description.rigid import (
    IDENTITY_POSE,
    PoseXyzw,
    compose_poses,
    invert_pose,
    qmul_xyzw,
    quat_wxyz_from_rpy,
    quat_xyzw_from_rpy,
    rotate_xyzw,
    rpy_exact_from_quat_xyzw,
    rpy_from_quat_xyzw,
    wxyz_from_xyzw,
    xyzw_from_wxyz,
)
from robomodel.kinematics.se3 import matrix_from_quat_xyzw
from robomodel.kinematics.se3 import quat_xyzw_from_rpy as quat_xyzw_from_rpy_batched

_angle = st.floats(-math.pi, math.pi)
_coordinate = st.floats(-10.0, 10.0)
_rpy = st.tuples(_angle, _angle, _angle)
_xyz = st.tuples(_coordinate, _coordinate, _coordinate)


def _matrix(pose: PoseXyzw) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = matrix_from_quat_xyzw(pose[1])
    T[:3, 3] = pose[0]
    return T


def _pose(xyz: tuple[float, float, float], rpy: tuple[float, float, float]) -> PoseXyzw:
    return xyz, quat_xyzw_from_rpy(*rpy)


@settings(max_examples=200, deadline=None)
@given(_rpy)
def test_rpy_quaternion_is_urdf_rotation_and_the_batched_form(rpy: tuple[float, ...]) -> None:
    q = quat_xyzw_from_rpy(*rpy)
    assert math.isclose(math.sqrt(sum(v * v for v in q)), 1.0, rel_tol=1e-15)
    R = matrix_from_xyz_rpy((0.0, 0.0, 0.0), rpy)[:3, :3]  # type: ignore[arg-type]
    np.testing.assert_allclose(matrix_from_quat_xyzw(q), R, atol=1e-12)
    np.testing.assert_allclose(quat_xyzw_from_rpy_batched(rpy), q, atol=1e-15)
    assert quat_wxyz_from_rpy(*rpy) == (q[3], q[0], q[1], q[2])


@settings(max_examples=200, deadline=None)
@given(_rpy, _rpy, _xyz)
def test_product_and_rotation_are_the_matrices(
    a: tuple[float, float, float], b: tuple[float, float, float], v: tuple[float, float, float]
) -> None:
    qa, qb = quat_xyzw_from_rpy(*a), quat_xyzw_from_rpy(*b)
    np.testing.assert_allclose(
        matrix_from_quat_xyzw(qmul_xyzw(qa, qb)),
        matrix_from_quat_xyzw(qa) @ matrix_from_quat_xyzw(qb),
        atol=1e-12,
    )
    np.testing.assert_allclose(rotate_xyzw(qa, v), matrix_from_quat_xyzw(qa) @ v, atol=1e-12)


@settings(max_examples=200, deadline=None)
@given(_xyz, _rpy, _xyz, _rpy)
def test_compose_and_invert_are_the_matrices(
    t_ab: tuple[float, float, float],
    r_ab: tuple[float, float, float],
    t_bc: tuple[float, float, float],
    r_bc: tuple[float, float, float],
) -> None:
    T_a_b, T_b_c = _pose(t_ab, r_ab), _pose(t_bc, r_bc)
    np.testing.assert_allclose(
        _matrix(compose_poses(T_a_b, T_b_c)), _matrix(T_a_b) @ _matrix(T_b_c), atol=1e-11
    )
    np.testing.assert_allclose(
        _matrix(invert_pose(T_a_b)), np.linalg.inv(_matrix(T_a_b)), atol=1e-11
    )
    t, q = compose_poses(T_a_b, invert_pose(T_a_b))
    np.testing.assert_allclose(t, IDENTITY_POSE[0], atol=1e-11)
    np.testing.assert_allclose(matrix_from_quat_xyzw(q), np.eye(3), atol=1e-12)


def test_rotations_about_one_axis_stay_exact() -> None:
    """tf2 composes quaternions, not matrices: a quarter turn about z moves x onto y exactly."""
    quarter = (0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5))
    (x, y, z), _ = compose_poses(((1.0, 2.0, 3.0), quarter), ((1.0, 0.0, 0.0), IDENTITY_POSE[1]))
    assert (x, y, z) == (1.0, 3.0, 3.0)


@settings(max_examples=200, deadline=None)
@given(_rpy)
def test_rpy_round_trip_gives_the_same_rotation(rpy: tuple[float, float, float]) -> None:
    q = quat_xyzw_from_rpy(*rpy)
    back = rpy_exact_from_quat_xyzw(*q)
    np.testing.assert_allclose(
        matrix_from_quat_xyzw(quat_xyzw_from_rpy(*back)), matrix_from_quat_xyzw(q), atol=1e-7
    )
    if abs(abs(rpy[1]) - math.pi / 2) > 0.01:  # urdfdom's rule snaps near ±90° pitch
        urdfdom = rpy_from_quat_xyzw(*q)
        np.testing.assert_allclose(
            matrix_from_quat_xyzw(quat_xyzw_from_rpy(*urdfdom)), matrix_from_quat_xyzw(q), atol=1e-9
        )


def test_exact_rpy_keeps_a_pitch_near_90_degrees() -> None:
    """Where urdfdom's getRPY reports 90°, the exact form keeps 89.9° (SDF world poses)."""
    q = quat_xyzw_from_rpy(0.0, math.radians(89.9), 0.0)
    assert rpy_from_quat_xyzw(*q)[1] == math.pi / 2
    assert rpy_exact_from_quat_xyzw(*q)[1] == pytest.approx(math.radians(89.9), abs=1e-9)


def test_gimbal_lock_follows_urdfdom() -> None:
    """At pitch 90° urdfdom's getRPY puts the whole rotation in yaw, with roll 0."""
    roll, pitch, yaw = rpy_from_quat_xyzw(*quat_xyzw_from_rpy(0.3, math.pi / 2, 0.2))
    assert roll == 0.0 and pitch == math.pi / 2
    assert yaw == pytest.approx(0.2 - 0.3, abs=1e-6)


def test_orders() -> None:
    assert wxyz_from_xyzw((1.0, 2.0, 3.0, 4.0)) == (4.0, 1.0, 2.0, 3.0)
    assert xyzw_from_wxyz((4.0, 1.0, 2.0, 3.0)) == (1.0, 2.0, 3.0, 4.0)
