"""Scalar rigid-body maths on plain float tuples: quaternions, roll-pitch-yaw and poses.

One pose or rotation at a time, in plain Python floats: for one 3-vector scalar code is several
times faster than numpy, and it needs no numpy at all (parsing and checking a URDF never load
it). The batched forms over arrays are :mod:`robomodel.kinematics.se3`.

Quaternions are named by their order: ``xyzw`` (ROS messages, tf2, URDF 1.1) or ``wxyz``
(MuJoCo, viser). A pose is ``(translation [m], rotation xyzw)``, ``T_a_b`` the pose of frame b
in frame a, composed as tf2 composes ``Transform``s. Roll, pitch and yaw are fixed-axis angles
[rad] with R = Rz(yaw) Ry(pitch) Rx(roll), as in URDF.
"""

from __future__ import annotations

import math

__all__ = [
    "IDENTITY_POSE",
    "PoseXyzw",
    "QuatWxyz",
    "QuatXyzw",
    "Vec3",
    "compose_poses",
    "conjugate_xyzw",
    "invert_pose",
    "qmul_xyzw",
    "quat_wxyz_from_rpy",
    "quat_xyzw_from_rpy",
    "rotate_xyzw",
    "rpy_exact_from_quat_xyzw",
    "rpy_from_quat_xyzw",
    "wxyz_from_xyzw",
    "xyzw_from_wxyz",
]

Vec3 = tuple[float, float, float]
QuatXyzw = tuple[float, float, float, float]
QuatWxyz = tuple[float, float, float, float]
PoseXyzw = tuple[Vec3, QuatXyzw]
IDENTITY_POSE: PoseXyzw = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))


def wxyz_from_xyzw(q_xyzw: QuatXyzw) -> QuatWxyz:
    """The same quaternion in ``wxyz`` order."""
    x, y, z, w = q_xyzw
    return (w, x, y, z)


def xyzw_from_wxyz(q_wxyz: QuatWxyz) -> QuatXyzw:
    """The same quaternion in ``xyzw`` order."""
    w, x, y, z = q_wxyz
    return (x, y, z, w)


def qmul_xyzw(a: QuatXyzw, b: QuatXyzw) -> QuatXyzw:
    """The Hamilton product ``a * b`` of two xyzw quaternions (``b``'s rotation first), summed
    in the order of tf2's ``Quaternion::operator*=``."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by + ay * bw + az * bx - ax * bz,
        aw * bz + az * bw + ax * by - ay * bx,
        aw * bw - ax * bx - ay * by - az * bz,
    )


def rotate_xyzw(q_xyzw: QuatXyzw, v: Vec3) -> Vec3:
    """``v`` rotated by the unit quaternion ``q_xyzw``: ``q v q*``, as tf2's ``quatRotate``
    evaluates it (two products), so a quarter turn about an axis maps axes exactly."""
    x, y, z, _ = qmul_xyzw(qmul_xyzw(q_xyzw, (v[0], v[1], v[2], 0.0)), conjugate_xyzw(q_xyzw))
    return (x, y, z)


def conjugate_xyzw(q_xyzw: QuatXyzw) -> QuatXyzw:
    """The conjugate (for a unit quaternion: the inverse rotation)."""
    x, y, z, w = q_xyzw
    return (-x, -y, -z, w)


def compose_poses(T_a_b: PoseXyzw, T_b_c: PoseXyzw) -> PoseXyzw:
    """``T_a_c = T_a_b * T_b_c``, as tf2 composes: ``quatRotate(q_ab, t_bc) + t_ab``,
    ``q_ab * q_bc``. Rotations about one axis stay exact (no matrix round trip)."""
    (ax, ay, az), q_ab = T_a_b
    rx, ry, rz = rotate_xyzw(q_ab, T_b_c[0])
    return (ax + rx, ay + ry, az + rz), qmul_xyzw(q_ab, T_b_c[1])


def invert_pose(T_a_b: PoseXyzw) -> PoseXyzw:
    """``T_b_a``, the inverse of a pose with a unit quaternion."""
    q_ba = conjugate_xyzw(T_a_b[1])
    tx, ty, tz = rotate_xyzw(q_ba, T_a_b[0])
    return (-tx, -ty, -tz), q_ba


def quat_xyzw_from_rpy(roll: float, pitch: float, yaw: float) -> QuatXyzw:
    """The unit quaternion of R = Rz(yaw) Ry(pitch) Rx(roll) [rad], as urdfdom's
    ``Rotation::setFromRPY`` computes it (normalised)."""
    cr, sr = math.cos(roll / 2.0), math.sin(roll / 2.0)
    cp, sp = math.cos(pitch / 2.0), math.sin(pitch / 2.0)
    cy, sy = math.cos(yaw / 2.0), math.sin(yaw / 2.0)
    x = sr * cp * cy - cr * sp * sy
    y = cr * sp * cy + sr * cp * sy
    z = cr * cp * sy - sr * sp * cy
    w = cr * cp * cy + sr * sp * sy
    norm = math.sqrt(x * x + y * y + z * z + w * w)
    return (x / norm, y / norm, z / norm, w / norm)


def quat_wxyz_from_rpy(roll: float, pitch: float, yaw: float) -> QuatWxyz:
    """:func:`quat_xyzw_from_rpy` in ``wxyz`` order (MuJoCo's ``quat``)."""
    return wxyz_from_xyzw(quat_xyzw_from_rpy(roll, pitch, yaw))


def rpy_exact_from_quat_xyzw(x: float, y: float, z: float, w: float) -> Vec3:
    """Roll, pitch, yaw [rad] of a unit quaternion that give back the same rotation, however
    close pitch is to ±90° (where roll and yaw share one angle; pitch is clamped to ±90°)."""
    r20 = 2.0 * (x * z - w * y)
    pitch = math.asin(max(-1.0, min(1.0, -r20)))
    roll = math.atan2(2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y))
    yaw = math.atan2(2.0 * (x * y + w * z), 1.0 - 2.0 * (y * y + z * z))
    return (roll, pitch, yaw)


def rpy_from_quat_xyzw(x: float, y: float, z: float, w: float) -> Vec3:
    """Roll, pitch, yaw [rad] of a unit quaternion, by urdfdom's ``Rotation::getRPY`` and its
    branch rules: within about 0.26° of pitch ±90° it reports exactly ±90°, roll 0 and yaw the
    rest (what urdf_to_graphviz prints; :func:`rpy_exact_from_quat_xyzw` keeps the rotation)."""
    sqw, sqx, sqy, sqz = w * w, x * x, y * y, z * z
    sarg = -2.0 * (x * z - w * y)
    if sarg <= -0.99999:
        return (0.0, -0.5 * math.pi, 2.0 * math.atan2(x, -y))
    if sarg >= 0.99999:
        return (0.0, 0.5 * math.pi, 2.0 * math.atan2(-x, y))
    pitch = math.asin(sarg)
    roll = math.atan2(2.0 * (y * z + w * x), sqw - sqx - sqy + sqz)
    yaw = math.atan2(2.0 * (x * y + w * z), sqw + sqx - sqy - sqz)
    return (roll, pitch, yaw)
