"""Vectorised SE(3) helpers: rotation matrices, quaternions (``xyzw``), roll-pitch-yaw.

Every function accepts leading batch dimensions (``(..., 3, 3)``, ``(..., 4)``, ...) and
returns new arrays. Conventions:

* ``T_a_b`` is a 4x4 homogeneous transform, the pose of frame b in frame a.
* Quaternions are ``xyzw`` (ROS message order) unless a name says ``wxyz``.
* roll-pitch-yaw are fixed-axis angles, ``R = Rz(yaw) @ Ry(pitch) @ Rx(roll)`` (URDF, tf2).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "axis_angle_matrix",
    "inverse_transform",
    "log_rotation",
    "matrix_from_quat_xyzw",
    "matrix_from_rpy",
    "quat_xyzw_from_matrix",
    "quat_xyzw_from_rpy",
    "rotation_z_to",
    "rpy_from_matrix",
    "rpy_from_quat_xyzw",
    "slerp_xyzw",
    "transform_from_xyz_quat_xyzw",
    "transform_from_xyz_rpy",
]

F64 = NDArray[np.float64]


def _f64(x: ArrayLike) -> F64:
    return np.asarray(x, dtype=np.float64)


def matrix_from_rpy(rpy_rad: ArrayLike) -> F64:
    """Rotation matrices ``(..., 3, 3)`` from fixed-axis roll, pitch, yaw ``(..., 3)`` [rad]."""
    rpy = _f64(rpy_rad)
    cr, cp, cy = np.cos(rpy[..., 0]), np.cos(rpy[..., 1]), np.cos(rpy[..., 2])
    sr, sp, sy = np.sin(rpy[..., 0]), np.sin(rpy[..., 1]), np.sin(rpy[..., 2])
    R = np.empty((*rpy.shape[:-1], 3, 3))
    R[..., 0, 0] = cy * cp
    R[..., 0, 1] = cy * sp * sr - sy * cr
    R[..., 0, 2] = cy * sp * cr + sy * sr
    R[..., 1, 0] = sy * cp
    R[..., 1, 1] = sy * sp * sr + cy * cr
    R[..., 1, 2] = sy * sp * cr - cy * sr
    R[..., 2, 0] = -sp
    R[..., 2, 1] = cp * sr
    R[..., 2, 2] = cp * cr
    return R


def rpy_from_matrix(R: ArrayLike) -> F64:
    """Roll, pitch, yaw ``(..., 3)`` [rad] of rotation matrices, as tf2's ``getEulerYPR``.

    At gimbal lock (``|R[2, 0]| >= 1``) yaw is 0 and roll takes the remaining rotation, as in
    ``tf2::Matrix3x3::getEulerYPR`` (solution 1), which tf2_echo prints.
    """
    M = _f64(R)
    r20 = M[..., 2, 0]
    locked = np.abs(r20) >= 1.0
    pitch = -np.arcsin(np.clip(r20, -1.0, 1.0))
    cp = np.cos(pitch)
    safe = np.where(locked, 1.0, cp)
    roll = np.arctan2(M[..., 2, 1] / safe, M[..., 2, 2] / safe)
    yaw = np.arctan2(M[..., 1, 0] / safe, M[..., 0, 0] / safe)
    neg = r20 < 0
    lock_pitch = np.where(neg, np.pi / 2, -np.pi / 2)
    lock_roll = np.where(
        neg, np.arctan2(M[..., 0, 1], M[..., 0, 2]), np.arctan2(-M[..., 0, 1], -M[..., 0, 2])
    )
    out = np.empty((*M.shape[:-2], 3))
    out[..., 0] = np.where(locked, lock_roll, roll)
    out[..., 1] = np.where(locked, lock_pitch, pitch)
    out[..., 2] = np.where(locked, 0.0, yaw)
    return out


def quat_xyzw_from_rpy(rpy_rad: ArrayLike) -> F64:
    """Unit quaternions ``(..., 4)`` (xyzw) from fixed-axis roll, pitch, yaw [rad]."""
    rpy = _f64(rpy_rad) / 2.0
    cr, cp, cy = np.cos(rpy[..., 0]), np.cos(rpy[..., 1]), np.cos(rpy[..., 2])
    sr, sp, sy = np.sin(rpy[..., 0]), np.sin(rpy[..., 1]), np.sin(rpy[..., 2])
    q = np.empty((*rpy.shape[:-1], 4))
    q[..., 0] = sr * cp * cy - cr * sp * sy
    q[..., 1] = cr * sp * cy + sr * cp * sy
    q[..., 2] = cr * cp * sy - sr * sp * cy
    q[..., 3] = cr * cp * cy + sr * sp * sy
    return q


def rpy_from_quat_xyzw(quat_xyzw: ArrayLike) -> F64:
    """Roll, pitch, yaw [rad] of quaternions (xyzw), with tf2's gimbal-lock rule."""
    return rpy_from_matrix(matrix_from_quat_xyzw(quat_xyzw))


def matrix_from_quat_xyzw(quat_xyzw: ArrayLike) -> F64:
    """Rotation matrices ``(..., 3, 3)`` of quaternions (xyzw); the input is normalised first.

    Raises:
        ValueError: a quaternion has zero norm.
    """
    q = _f64(quat_xyzw)
    norm = np.linalg.norm(q, axis=-1, keepdims=True)
    if np.any(norm == 0.0):
        raise ValueError("zero quaternion has no rotation")
    q = q / norm
    x, y, z, w = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    R = np.empty((*q.shape[:-1], 3, 3))
    R[..., 0, 0] = 1 - 2 * (y * y + z * z)
    R[..., 0, 1] = 2 * (x * y - z * w)
    R[..., 0, 2] = 2 * (x * z + y * w)
    R[..., 1, 0] = 2 * (x * y + z * w)
    R[..., 1, 1] = 1 - 2 * (x * x + z * z)
    R[..., 1, 2] = 2 * (y * z - x * w)
    R[..., 2, 0] = 2 * (x * z - y * w)
    R[..., 2, 1] = 2 * (y * z + x * w)
    R[..., 2, 2] = 1 - 2 * (x * x + y * y)
    return R


def quat_xyzw_from_matrix(R: ArrayLike) -> F64:
    """Unit quaternions (xyzw, ``w >= 0``) of rotation matrices (Shepperd's method)."""
    M = _f64(R)
    m00, m11, m22 = M[..., 0, 0], M[..., 1, 1], M[..., 2, 2]
    trace = m00 + m11 + m22
    # Four candidate formulas; each is accurate where its pivot is largest.
    cand = np.empty((*M.shape[:-2], 4, 4))
    cand[..., 0, :] = np.stack(
        [
            M[..., 2, 1] - M[..., 1, 2],
            M[..., 0, 2] - M[..., 2, 0],
            M[..., 1, 0] - M[..., 0, 1],
            1 + trace,
        ],
        axis=-1,
    )
    cand[..., 1, :] = np.stack(
        [
            1 + m00 - m11 - m22,
            M[..., 0, 1] + M[..., 1, 0],
            M[..., 0, 2] + M[..., 2, 0],
            M[..., 2, 1] - M[..., 1, 2],
        ],
        axis=-1,
    )
    cand[..., 2, :] = np.stack(
        [
            M[..., 0, 1] + M[..., 1, 0],
            1 - m00 + m11 - m22,
            M[..., 1, 2] + M[..., 2, 1],
            M[..., 0, 2] - M[..., 2, 0],
        ],
        axis=-1,
    )
    cand[..., 3, :] = np.stack(
        [
            M[..., 0, 2] + M[..., 2, 0],
            M[..., 1, 2] + M[..., 2, 1],
            1 - m00 - m11 + m22,
            M[..., 1, 0] - M[..., 0, 1],
        ],
        axis=-1,
    )
    pivots = np.stack([trace, m00, m11, m22], axis=-1)
    best = np.argmax(pivots, axis=-1)
    q = np.take_along_axis(cand, best[..., None, None], axis=-2)[..., 0, :]
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    result: F64 = np.where(q[..., 3:4] < 0, -q, q)
    return result


def transform_from_xyz_rpy(xyz_m: ArrayLike, rpy_rad: ArrayLike) -> F64:
    """4x4 transforms from translations [m] and roll, pitch, yaw [rad]."""
    xyz = _f64(xyz_m)
    R = matrix_from_rpy(rpy_rad)
    T = np.zeros((*np.broadcast_shapes(xyz.shape[:-1], R.shape[:-2]), 4, 4))
    T[..., :3, :3] = R
    T[..., :3, 3] = xyz
    T[..., 3, 3] = 1.0
    return T


def transform_from_xyz_quat_xyzw(xyz_m: ArrayLike, quat_xyzw: ArrayLike) -> F64:
    """4x4 transforms from translations [m] and quaternions (xyzw, normalised here)."""
    xyz = _f64(xyz_m)
    R = matrix_from_quat_xyzw(quat_xyzw)
    T = np.zeros((*np.broadcast_shapes(xyz.shape[:-1], R.shape[:-2]), 4, 4))
    T[..., :3, :3] = R
    T[..., :3, 3] = xyz
    T[..., 3, 3] = 1.0
    return T


def inverse_transform(T_a_b: ArrayLike) -> F64:
    """``T_b_a`` from ``T_a_b`` (rigid transforms, using the transpose of the rotation)."""
    T = _f64(T_a_b)
    out = np.zeros_like(T)
    Rt = np.swapaxes(T[..., :3, :3], -1, -2)
    out[..., :3, :3] = Rt
    out[..., :3, 3] = -np.einsum("...ij,...j->...i", Rt, T[..., :3, 3])
    out[..., 3, 3] = 1.0
    return out


def axis_angle_matrix(axis: ArrayLike, angle_rad: ArrayLike) -> F64:
    """Rodrigues' rotation ``(..., 3, 3)`` about unit ``axis`` ``(..., 3)`` by ``angle_rad``."""
    a = _f64(axis)
    t = _f64(angle_rad)
    c, s = np.cos(t), np.sin(t)
    C = 1.0 - c
    x, y, z = a[..., 0], a[..., 1], a[..., 2]
    shape = np.broadcast_shapes(a.shape[:-1], t.shape)
    R = np.empty((*shape, 3, 3))
    R[..., 0, 0] = c + x * x * C
    R[..., 0, 1] = x * y * C - z * s
    R[..., 0, 2] = x * z * C + y * s
    R[..., 1, 0] = y * x * C + z * s
    R[..., 1, 1] = c + y * y * C
    R[..., 1, 2] = y * z * C - x * s
    R[..., 2, 0] = z * x * C - y * s
    R[..., 2, 1] = z * y * C + x * s
    R[..., 2, 2] = c + z * z * C
    return R


def log_rotation(R: ArrayLike) -> F64:
    """Rotation vectors ``(..., 3)`` (axis times angle [rad], angle in [0, pi]) of matrices."""
    M = _f64(R)
    q = quat_xyzw_from_matrix(M)  # w >= 0, so the angle is in [0, pi]
    v = q[..., :3]
    sin_half = np.linalg.norm(v, axis=-1)
    angle = 2.0 * np.arctan2(sin_half, q[..., 3])
    small = sin_half < 1e-12
    scale = np.where(small, 2.0, angle / np.where(small, 1.0, sin_half))
    return v * scale[..., None]


def rotation_z_to(axis: ArrayLike) -> F64:
    """A rotation ``P`` with ``P @ [0, 0, 1] == axis`` (unit), the minimal one.

    For ``axis == -z`` it is the half turn about x. Used to turn every joint axis into z.
    """
    a = _f64(axis)
    z = np.array([0.0, 0.0, 1.0])
    c = float(np.dot(z, a))
    if c < -1.0 + 1e-12:
        return np.diag([1.0, -1.0, -1.0])
    v = np.cross(z, a)
    vx = np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])
    result: F64 = np.eye(3) + vx + vx @ vx / (1.0 + c)
    return result


def slerp_xyzw(q0_xyzw: ArrayLike, q1_xyzw: ArrayLike, ratio: float) -> F64:
    """Spherical interpolation between unit quaternions along the shorter arc (as tf2)."""
    q0 = _f64(q0_xyzw)
    q1 = _f64(q1_xyzw)
    d = float(np.dot(q0, q1))
    if d < 0.0:
        q1 = -q1
        d = -d
    if d > 1.0 - 1e-12:
        q = q0 + ratio * (q1 - q0)
    else:
        theta = np.arccos(min(d, 1.0))
        s = np.sin(theta)
        q = (np.sin((1.0 - ratio) * theta) * q0 + np.sin(ratio * theta) * q1) / s
    result: F64 = q / np.linalg.norm(q)
    return result
