"""Rigid poses as (translation, quaternion xyzw) tuples, composed as tf2 composes them.

The buffer's lookups accumulate poses this way rather than as matrices, as tf2's
``TransformAccum`` does, so pure rotations about one axis stay exact.
"""

from __future__ import annotations

__all__ = ["IDENTITY", "Pose", "Quat", "Vec3", "compose", "inverse", "qmul", "rotate"]

Vec3 = tuple[float, float, float]
Quat = tuple[float, float, float, float]
Pose = tuple[Vec3, Quat]
IDENTITY: Pose = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))


def qmul(a: Quat, b: Quat) -> Quat:
    """The Hamilton product ``a * b`` of two xyzw quaternions."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by + ay * bw + az * bx - ax * bz,
        aw * bz + az * bw + ax * by - ay * bx,
        aw * bw - ax * bx - ay * by - az * bz,
    )


def rotate(q: Quat, v: Vec3) -> Vec3:
    """``v`` rotated by the unit xyzw quaternion ``q`` (``q * v * conj(q)``)."""
    x, y, z, _ = qmul(qmul(q, (v[0], v[1], v[2], 0.0)), (-q[0], -q[1], -q[2], q[3]))
    return (x, y, z)


def compose(a: Pose, b: Pose) -> Pose:
    """``a * b`` (b expressed in a), as tf2's ``quatRotate(a.q, b.t) + a.t``, ``a.q * b.q``."""
    r = rotate(a[1], b[0])
    return (r[0] + a[0][0], r[1] + a[0][1], r[2] + a[0][2]), qmul(a[1], b[1])


def inverse(a: Pose) -> Pose:
    """The inverse of a pose with a unit quaternion."""
    x, y, z, w = a[1]
    inv: Quat = (-x, -y, -z, w)
    t = rotate(inv, a[0])
    return (-t[0], -t[1], -t[2]), inv
