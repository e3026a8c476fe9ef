"""Property tests of the SE(3) helpers: round trips, near identity, gimbal lock, batches."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from robomodel.description.model.pose import matrix_from_xyz_rpy
from robomodel.kinematics.se3 import (
    axis_angle_matrix,
    inverse_transform,
    log_rotation,
    matrix_from_quat_xyzw,
    matrix_from_rpy,
    quat_xyzw_from_matrix,
    quat_xyzw_from_rpy,
    rpy_from_matrix,
    rpy_from_quat_xyzw,
    slerp_xyzw,
    transform_from_xyz_quat_xyzw,
    transform_from_xyz_rpy,
)

finite = st.floats(-10, 10, allow_nan=False)
angle = st.floats(-math.pi, math.pi, allow_nan=False)
quats = arrays(np.float64, 4, elements=st.floats(-1, 1, allow_nan=False)).filter(
    lambda q: np.linalg.norm(q) > 1e-3
)


def _same_rotation(q1: np.ndarray, q2: np.ndarray) -> bool:
    return bool(abs(abs(float(np.dot(q1, q2))) - 1.0) < 1e-9)


@given(quats)
def test_quaternion_matrix_round_trip(q: np.ndarray) -> None:
    q = q / np.linalg.norm(q)
    R = matrix_from_quat_xyzw(q)
    np.testing.assert_allclose(R @ R.T, np.eye(3), atol=1e-12)
    assert np.linalg.det(R) > 0
    back = quat_xyzw_from_matrix(R)
    assert back[3] >= 0 and _same_rotation(back, q)


@given(angle, st.floats(-1.5, 1.5), angle)
def test_rpy_round_trips(roll: float, pitch: float, yaw: float) -> None:
    rpy = np.array([roll, pitch, yaw])
    R = matrix_from_rpy(rpy)
    np.testing.assert_allclose(
        R, matrix_from_xyz_rpy((0, 0, 0), (roll, pitch, yaw))[:3, :3], atol=1e-12
    )
    np.testing.assert_allclose(matrix_from_quat_xyzw(quat_xyzw_from_rpy(rpy)), R, atol=1e-12)
    np.testing.assert_allclose(matrix_from_rpy(rpy_from_matrix(R)), R, atol=1e-9)
    np.testing.assert_allclose(
        matrix_from_rpy(rpy_from_quat_xyzw(quat_xyzw_from_rpy(rpy))), R, atol=1e-9
    )


@given(angle, angle, st.sampled_from([math.pi / 2, -math.pi / 2]))
def test_gimbal_lock_keeps_the_rotation(roll: float, yaw: float, pitch: float) -> None:
    R = matrix_from_rpy([roll, pitch, yaw])
    rpy = rpy_from_matrix(R)
    assert rpy[2] == 0.0 or abs(abs(rpy[1]) - math.pi / 2) > 1e-6
    np.testing.assert_allclose(matrix_from_rpy(rpy), R, atol=1e-6)


@given(arrays(np.float64, 3, elements=st.floats(-1e-9, 1e-9)))
def test_near_identity(v: np.ndarray) -> None:
    angle_rad = float(np.linalg.norm(v))
    axis = v / angle_rad if angle_rad > 0 else np.array([0.0, 0.0, 1.0])
    R = axis_angle_matrix(axis, angle_rad)
    np.testing.assert_allclose(log_rotation(R), v, atol=1e-15)
    q = quat_xyzw_from_matrix(R)
    np.testing.assert_allclose(q, [*(v / 2), 1.0], atol=1e-15)


@given(
    arrays(np.float64, 3, elements=st.floats(-1, 1)).filter(lambda a: np.linalg.norm(a) > 1e-3),
    st.floats(0.0, math.pi),
)
def test_log_inverts_axis_angle(axis: np.ndarray, theta: float) -> None:
    axis = axis / np.linalg.norm(axis)
    w = log_rotation(axis_angle_matrix(axis, theta))
    np.testing.assert_allclose(
        axis_angle_matrix(axis, theta),
        axis_angle_matrix(w / max(np.linalg.norm(w), 1e-300), np.linalg.norm(w)),
        atol=1e-9,
    )


@settings(max_examples=50)
@given(arrays(np.float64, (5, 3), elements=finite), arrays(np.float64, (5, 3), elements=angle))
def test_transform_group_axioms_batched(xyz: np.ndarray, rpy: np.ndarray) -> None:
    T = transform_from_xyz_rpy(xyz, rpy)
    assert T.shape == (5, 4, 4)
    np.testing.assert_allclose(inverse_transform(T) @ T, np.tile(np.eye(4), (5, 1, 1)), atol=1e-12)
    Tq = transform_from_xyz_quat_xyzw(xyz, quat_xyzw_from_rpy(rpy))
    np.testing.assert_allclose(Tq, T, atol=1e-12)
    # Associativity of composition through the helpers.
    A, B, C = T[0], T[1], T[2]
    np.testing.assert_allclose((A @ B) @ C, A @ (B @ C), atol=1e-9)


@given(quats, quats, st.floats(0, 1))
def test_slerp_end_points_and_unit_norm(q0: np.ndarray, q1: np.ndarray, t: float) -> None:
    q0, q1 = q0 / np.linalg.norm(q0), q1 / np.linalg.norm(q1)
    assert _same_rotation(slerp_xyzw(q0, q1, 0.0), q0)
    assert _same_rotation(slerp_xyzw(q0, q1, 1.0), q1)
    assert abs(np.linalg.norm(slerp_xyzw(q0, q1, t)) - 1.0) < 1e-12
