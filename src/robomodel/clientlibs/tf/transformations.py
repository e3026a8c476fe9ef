"""ROS 1's ``tf.transformations``: homogeneous 4x4 matrices, Euler angles in any of the 24
axis conventions, and quaternions in ROS's order ``[x, y, z, w]``, with numpy.

Conventions, as tf's module has them:

- ``axes`` is ``'s'`` (static: each rotation about a fixed axis of the original frame) or
  ``'r'`` (rotating: about the axis as moved by the rotations before), then the three axes in
  the order the angles are applied: ``'sxyz'`` (the default: roll about x, pitch about y, yaw
  about z, of the fixed frame) is ``'rzyx'`` with the angles reversed.
- ``quaternion_multiply(q1, q0)`` is the rotation ``q0`` followed by ``q1``.
- ``quaternion_from_matrix`` gives ``w >= 0`` when the rotation's trace is positive, else the
  largest of ``x``, ``y``, ``z`` positive.

Everything here is written from the formulas (rotations composed from elementary ones and
solved back by the angles' sines and cosines); the tests check it against Debian's
``tf.transformations`` and robomodel's own rigid-body code.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from typing import Any, NoReturn

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "compose_matrix",
    "concatenate_matrices",
    "decompose_matrix",
    "euler_from_matrix",
    "euler_from_quaternion",
    "euler_matrix",
    "identity_matrix",
    "inverse_matrix",
    "is_same_transform",
    "quaternion_about_axis",
    "quaternion_conjugate",
    "quaternion_from_euler",
    "quaternion_from_matrix",
    "quaternion_inverse",
    "quaternion_matrix",
    "quaternion_multiply",
    "quaternion_slerp",
    "random_quaternion",
    "random_rotation_matrix",
    "rotation_from_matrix",
    "rotation_matrix",
    "scale_matrix",
    "translation_from_matrix",
    "translation_matrix",
    "unit_vector",
    "vector_norm",
]

_EPS = np.finfo(float).eps * 4.0
Matrix = NDArray[np.float64]


# -- axes -----------------------------------------------------------------------------------------
@functools.cache
def _axes(axes: str) -> tuple[str, tuple[int, int, int]]:
    """``'sxyz'`` -> ``('s', (0, 1, 2))``; ValueError naming the valid forms."""
    if (
        not isinstance(axes, str)
        or len(axes) != 4
        or axes[0] not in "sr"
        or any(a not in "xyz" for a in axes[1:])
        or axes[1] == axes[2]
        or axes[2] == axes[3]
    ):
        raise ValueError(
            f"unknown axes {axes!r}: 's' (static) or 'r' (rotating) and three of x, y, z with"
            " no axis twice in a row, such as 'sxyz', 'rzyx', 'szxz'"
        )
    index = {"x": 0, "y": 1, "z": 2}
    first, second, third = (index[a] for a in axes[1:])
    return axes[0], (first, second, third)


def _static(
    axes: str, ai: float, aj: float, ak: float
) -> tuple[tuple[int, ...], tuple[float, ...]]:
    """The axes and angles of the same rotation as static rotations, in the order applied."""
    frame, order = _axes(axes)
    if frame == "r":  # rotating ABC by (a, b, c) is static CBA by (c, b, a)
        return order[::-1], (ak, aj, ai)
    return order, (ai, aj, ak)


def _elementary(axis: int, angle: float) -> Matrix:
    c, s = math.cos(angle), math.sin(angle)
    j, k = (axis + 1) % 3, (axis + 2) % 3
    m = np.eye(3)
    m[j, j], m[j, k], m[k, j], m[k, k] = c, -s, s, c
    return m


def _elementary_quaternion(axis: int, angle: float) -> Matrix:
    q = np.zeros(4)
    q[axis] = math.sin(angle / 2.0)
    q[3] = math.cos(angle / 2.0)
    return q


# -- matrices -------------------------------------------------------------------------------------
def identity_matrix() -> Matrix:
    """The 4x4 identity."""
    return np.identity(4)


def translation_matrix(direction: ArrayLike) -> Matrix:
    """The 4x4 matrix that translates by ``direction`` (3 values)."""
    m = np.identity(4)
    m[:3, 3] = np.asarray(direction, dtype=float)[:3]
    return m


def translation_from_matrix(matrix: ArrayLike) -> Matrix:
    """The translation of a 4x4 matrix."""
    return np.array(matrix, dtype=float, copy=True)[:3, 3]


def rotation_matrix(angle: float, direction: ArrayLike, point: ArrayLike | None = None) -> Matrix:
    """The 4x4 matrix that rotates by ``angle`` [rad] about the axis ``direction`` through
    ``point`` (the origin by default)."""
    axis = unit_vector(np.asarray(direction, dtype=float)[:3])
    c, s = math.cos(angle), math.sin(angle)
    cross = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    m = np.identity(4)
    m[:3, :3] = c * np.eye(3) + s * cross + (1.0 - c) * np.outer(axis, axis)  # Rodrigues
    if point is not None:
        p = np.asarray(point, dtype=float)[:3]
        m[:3, 3] = p - m[:3, :3] @ p
    return m


def rotation_from_matrix(matrix: ArrayLike) -> tuple[float, Matrix, Matrix]:
    """``(angle, direction, point)`` of a rotation matrix, so that
    ``rotation_matrix(angle, direction, point)`` is ``matrix``. ValueError if it is no
    rotation."""
    m = np.array(matrix, dtype=float, copy=False)
    r = m[:3, :3]
    values, vectors = np.linalg.eig(r.T)
    unit = np.where(abs(np.real(values) - 1.0) < 1e-8)[0]
    if not len(unit):
        raise ValueError("no unit eigenvector for the eigenvalue 1: not a rotation matrix")
    direction = np.real(vectors[:, unit[-1]]).squeeze()
    values, vectors = np.linalg.eig(m)
    unit = np.where(abs(np.real(values) - 1.0) < 1e-8)[0]
    if not len(unit):
        raise ValueError("no eigenvector for the eigenvalue 1: not a rotation matrix")
    point = np.real(vectors[:, unit[-1]]).squeeze()
    point = point / point[3]
    cosa = (np.trace(r) - 1.0) / 2.0
    # sin(angle) from the skew-symmetric part along the axis's largest component
    skew = np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]]) / 2.0
    big = int(np.argmax(abs(direction)))
    sina = skew[big] / direction[big]
    return math.atan2(sina, cosa), direction, point


def scale_matrix(
    factor: float, origin: ArrayLike | None = None, direction: ArrayLike | None = None
) -> Matrix:
    """The 4x4 matrix that scales by ``factor`` about ``origin``: in every direction, or
    along ``direction`` only."""
    m = np.identity(4)
    if direction is None:
        m[:3, :3] *= factor
    else:
        d = unit_vector(np.asarray(direction, dtype=float)[:3])
        m[:3, :3] -= (1.0 - factor) * np.outer(d, d)
    if origin is not None:
        o = np.asarray(origin, dtype=float)[:3]
        m[:3, 3] = o - m[:3, :3] @ o
    return m


def euler_matrix(ai: float, aj: float, ak: float, axes: str = "sxyz") -> Matrix:
    """The 4x4 rotation of Euler angles ``ai``, ``aj``, ``ak`` [rad] in convention ``axes``."""
    order, angles = _static(axes, ai, aj, ak)
    r = np.eye(3)
    for axis, angle in zip(order, angles, strict=True):
        r = _elementary(axis, angle) @ r  # each static rotation applies after the ones before
    m = np.identity(4)
    m[:3, :3] = r
    return m


def _permutation(order: tuple[int, ...]) -> tuple[Matrix, bool]:
    """The matrix whose columns are the axes (i, j, k), k completing i, j; and whether it
    swaps the handedness (then every angle changes sign)."""
    i, j = order[0], order[1]
    k = 3 - i - j
    p = np.zeros((3, 3))
    p[i, 0] = p[j, 1] = p[k, 2] = 1.0
    return p, bool(np.linalg.det(p) < 0)


def euler_from_matrix(matrix: ArrayLike, axes: str = "sxyz") -> tuple[float, float, float]:
    """The Euler angles ``(ai, aj, ak)`` [rad] of a rotation matrix in convention ``axes``."""
    frame, order = _axes(axes)
    static = order[::-1] if frame == "r" else order
    p, flipped = _permutation(static)
    m = p.T @ np.array(matrix, dtype=float, copy=False)[:3, :3] @ p  # in the axes' own frame
    if static[0] == static[2]:  # proper Euler: m = R1(c) R2(b) R1(a)
        sb = math.hypot(m[0, 1], m[0, 2])
        b = math.atan2(sb, m[0, 0])
        if sb > _EPS:
            a, c = math.atan2(m[0, 1], m[0, 2]), math.atan2(m[1, 0], -m[2, 0])
        else:  # gimbal lock: all of the first and last rotation in a
            a, c = math.atan2(-m[1, 2], m[1, 1]), 0.0
    else:  # Tait-Bryan: m = R3(c) R2(b) R1(a)
        cb = math.hypot(m[0, 0], m[1, 0])
        b = math.atan2(-m[2, 0], cb)
        if cb > _EPS:
            a, c = math.atan2(m[2, 1], m[2, 2]), math.atan2(m[1, 0], m[0, 0])
        else:
            a, c = math.atan2(-m[1, 2], m[1, 1]), 0.0
    if flipped:
        a, b, c = -a, -b, -c
    return (c, b, a) if frame == "r" else (a, b, c)


def euler_from_quaternion(quaternion: ArrayLike, axes: str = "sxyz") -> tuple[float, float, float]:
    """The Euler angles [rad] of quaternion ``[x, y, z, w]`` in convention ``axes``."""
    return euler_from_matrix(quaternion_matrix(quaternion), axes)


def quaternion_from_euler(ai: float, aj: float, ak: float, axes: str = "sxyz") -> Matrix:
    """The quaternion ``[x, y, z, w]`` of Euler angles [rad] in convention ``axes``."""
    order, angles = _static(axes, ai, aj, ak)
    q = np.array([0.0, 0.0, 0.0, 1.0])
    for axis, angle in zip(order, angles, strict=True):
        q = quaternion_multiply(_elementary_quaternion(axis, angle), q)
    return q


def compose_matrix(
    scale: ArrayLike | None = None,
    shear: ArrayLike | None = None,
    angles: ArrayLike | None = None,
    translate: ArrayLike | None = None,
    perspective: ArrayLike | None = None,
) -> Matrix:
    """``T @ P @ R @ Z @ S``: translation, perspective, rotation (static xyz Euler
    ``angles``), shear (xy, xz, yz factors) and scale, each left out when None."""
    m = np.identity(4)
    if perspective is not None:
        p = np.identity(4)
        p[3, :] = np.asarray(perspective, dtype=float)[:4]
        m = m @ p
    if translate is not None:
        m = translation_matrix(translate) @ m
    if angles is not None:
        ai, aj, ak = (float(a) for a in np.asarray(angles, dtype=float)[:3])
        m = m @ euler_matrix(ai, aj, ak, "sxyz")
    if shear is not None:
        z = np.identity(4)
        xy, xz, yz = (float(v) for v in np.asarray(shear, dtype=float)[:3])
        z[0, 1], z[0, 2], z[1, 2] = xy, xz, yz
        m = m @ z
    if scale is not None:
        s = np.identity(4)
        s[0, 0], s[1, 1], s[2, 2] = (float(v) for v in np.asarray(scale, dtype=float)[:3])
        m = m @ s
    m /= m[3, 3]
    return m


def decompose_matrix(
    matrix: ArrayLike,
) -> tuple[Matrix, Matrix, Matrix, Matrix, Matrix]:
    """``(scale, shear, angles, translate, perspective)`` of an affine 4x4 matrix, the inverse
    of :func:`compose_matrix` (angles static xyz). ValueError for a singular matrix;
    NotImplementedError for a perspective one."""
    m = np.array(matrix, dtype=float, copy=True).T
    if abs(m[3, 3]) < _EPS:
        raise ValueError("the matrix cannot be decomposed: M[3, 3] is 0")
    m /= m[3, 3]
    if np.any(abs(m[:3, 3]) > _EPS):
        raise NotImplementedError(
            "tf.transformations.decompose_matrix of a perspective matrix is not offered"
        )
    perspective = np.array([0.0, 0.0, 0.0, 1.0])
    translate = m[3, :3].copy()
    rows = m[:3, :3].copy()
    if abs(np.linalg.det(rows)) < _EPS:
        raise ValueError("the matrix cannot be decomposed: it is singular")
    # Gram-Schmidt on the rows: scales, then shears against the rows before
    scale = np.zeros(3)
    shear = np.zeros(3)
    scale[0] = vector_norm(rows[0])
    rows[0] /= scale[0]
    shear[0] = rows[0] @ rows[1]
    rows[1] -= rows[0] * shear[0]
    scale[1] = vector_norm(rows[1])
    rows[1] /= scale[1]
    shear[0] /= scale[1]
    shear[1] = rows[0] @ rows[2]
    rows[2] -= rows[0] * shear[1]
    shear[2] = rows[1] @ rows[2]
    rows[2] -= rows[1] * shear[2]
    scale[2] = vector_norm(rows[2])
    rows[2] /= scale[2]
    shear[1:] /= scale[2]
    if rows[0] @ np.cross(rows[1], rows[2]) < 0:  # a reflection: one negative scale
        scale *= -1
        rows *= -1
    angles = np.array(euler_from_matrix(rows.T, "sxyz"))
    return scale, shear, angles, translate, perspective


def inverse_matrix(matrix: ArrayLike) -> Matrix:
    """The inverse of a square matrix."""
    return np.linalg.inv(np.asarray(matrix, dtype=float))


def concatenate_matrices(*matrices: ArrayLike) -> Matrix:
    """``matrices[0] @ matrices[1] @ ...`` (the identity for none)."""
    m = np.identity(4)
    for each in matrices:
        m = m @ np.asarray(each, dtype=float)
    return m


def is_same_transform(matrix0: ArrayLike, matrix1: ArrayLike) -> bool:
    """Whether two homogeneous matrices are one transform (each divided by its M[3, 3])."""
    a = np.array(matrix0, dtype=float, copy=True)
    b = np.array(matrix1, dtype=float, copy=True)
    return bool(np.allclose(a / a[3, 3], b / b[3, 3]))


# -- quaternions [x, y, z, w] ---------------------------------------------------------------------
def quaternion_about_axis(angle: float, axis: ArrayLike) -> Matrix:
    """The quaternion of a rotation by ``angle`` [rad] about ``axis``."""
    q = np.zeros(4)
    a = np.asarray(axis, dtype=float)[:3]
    length = vector_norm(a)
    if length > _EPS:
        q[:3] = a * (math.sin(angle / 2.0) / length)
    q[3] = math.cos(angle / 2.0)
    return q


def quaternion_matrix(quaternion: ArrayLike) -> Matrix:
    """The 4x4 rotation of quaternion ``[x, y, z, w]`` (normalised first; the identity for
    a zero quaternion)."""
    q = np.array(quaternion, dtype=float, copy=True)[:4]
    n = q @ q
    if n < _EPS:
        return np.identity(4)
    x, y, z, w = q * math.sqrt(2.0 / n)
    m = np.identity(4)
    m[:3, :3] = [
        [1.0 - y * y - z * z, x * y - z * w, x * z + y * w],
        [x * y + z * w, 1.0 - x * x - z * z, y * z - x * w],
        [x * z - y * w, y * z + x * w, 1.0 - x * x - y * y],
    ]
    return m


def quaternion_from_matrix(matrix: ArrayLike) -> Matrix:
    """The quaternion ``[x, y, z, w]`` of the rotation of a 3x3 or 4x4 matrix."""
    r = np.array(matrix, dtype=float, copy=False)[:3, :3]
    trace = float(np.trace(r))
    q = np.empty(4)
    if trace > 0.0:
        s = 2.0 * math.sqrt(1.0 + trace)  # 4 w
        q[3] = s / 4.0
        q[0] = (r[2, 1] - r[1, 2]) / s
        q[1] = (r[0, 2] - r[2, 0]) / s
        q[2] = (r[1, 0] - r[0, 1]) / s
        return q
    i = int(np.argmax(np.diag(r)))
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2.0 * math.sqrt(max(0.0, 1.0 + r[i, i] - r[j, j] - r[k, k]))  # 4 q_i
    q[i] = s / 4.0
    q[j] = (r[j, i] + r[i, j]) / s
    q[k] = (r[k, i] + r[i, k]) / s
    q[3] = (r[k, j] - r[j, k]) / s
    return q


def quaternion_multiply(quaternion1: ArrayLike, quaternion0: ArrayLike) -> Matrix:
    """The Hamilton product ``q1 * q0``: the rotation ``q0`` followed by ``q1``."""
    x1, y1, z1, w1 = np.asarray(quaternion1, dtype=float)[:4]
    x0, y0, z0, w0 = np.asarray(quaternion0, dtype=float)[:4]
    return np.array(
        [
            w1 * x0 + x1 * w0 + y1 * z0 - z1 * y0,
            w1 * y0 - x1 * z0 + y1 * w0 + z1 * x0,
            w1 * z0 + x1 * y0 - y1 * x0 + z1 * w0,
            w1 * w0 - x1 * x0 - y1 * y0 - z1 * z0,
        ]
    )


def quaternion_conjugate(quaternion: ArrayLike) -> Matrix:
    """``[-x, -y, -z, w]``."""
    q = np.array(quaternion, dtype=float, copy=True)[:4]
    q[:3] *= -1.0
    return q


def quaternion_inverse(quaternion: ArrayLike) -> Matrix:
    """The inverse: the conjugate over the squared norm."""
    q = np.asarray(quaternion, dtype=float)[:4]
    return quaternion_conjugate(q) / float(q @ q)


def quaternion_slerp(
    quat0: ArrayLike,
    quat1: ArrayLike,
    fraction: float,
    spin: int = 0,
    shortestpath: bool = True,
) -> Matrix:
    """The spherical linear interpolation from ``quat0`` (fraction 0) to ``quat1`` (1),
    the short way round unless ``shortestpath`` is False, ``spin`` extra half turns."""
    q0 = unit_vector(np.asarray(quat0, dtype=float)[:4])
    q1 = unit_vector(np.asarray(quat1, dtype=float)[:4])
    if fraction == 0.0:
        return q0
    if fraction == 1.0:
        return q1
    d = float(q0 @ q1)
    if abs(abs(d) - 1.0) < _EPS:
        return q0
    if shortestpath and d < 0.0:
        d, q1 = -d, -q1
    angle = math.acos(max(-1.0, min(1.0, d))) + spin * math.pi
    if abs(angle) < _EPS:
        return q0
    isin = 1.0 / math.sin(angle)
    return (math.sin((1.0 - fraction) * angle) * isin) * q0 + (
        math.sin(fraction * angle) * isin
    ) * q1


def random_quaternion(rand: Sequence[float] | None = None) -> Matrix:
    """A rotation drawn uniformly (Shoemake's method) from three numbers in [0, 1)."""
    r = np.random.rand(3) if rand is None else np.asarray(rand, dtype=float)[:3]
    r1, r2 = math.sqrt(1.0 - r[0]), math.sqrt(r[0])
    t1, t2 = 2.0 * math.pi * r[1], 2.0 * math.pi * r[2]
    return np.array([math.sin(t1) * r1, math.cos(t1) * r1, math.sin(t2) * r2, math.cos(t2) * r2])


def random_rotation_matrix(rand: Sequence[float] | None = None) -> Matrix:
    """The 4x4 matrix of :func:`random_quaternion`."""
    return quaternion_matrix(random_quaternion(rand))


# -- vectors --------------------------------------------------------------------------------------
def vector_norm(data: ArrayLike, axis: int | None = None, out: Any = None) -> Any:
    """The Euclidean length of ``data``, along ``axis`` if given."""
    if out is not None:
        _not_offered("vector_norm(out=...)")
    a = np.asarray(data, dtype=float)
    if axis is None:
        return float(math.sqrt(float(np.sum(a * a))))
    return np.sqrt(np.sum(a * a, axis=axis))


def unit_vector(data: ArrayLike, axis: int | None = None, out: Any = None) -> Matrix:
    """``data`` divided by its length (along ``axis`` if given)."""
    if out is not None:
        _not_offered("unit_vector(out=...)")
    a = np.array(data, dtype=float, copy=True)
    if axis is None:
        length = math.sqrt(float(np.sum(a * a)))
        return a / length
    lengths: Matrix = np.expand_dims(np.sqrt(np.sum(a * a, axis=axis)), axis)
    return a / lengths


def _not_offered(what: str) -> NoReturn:
    raise NotImplementedError(f"tf.transformations.{what} is not offered by robomodel's tf")


_NOT_OFFERED = (
    "reflection_matrix", "reflection_from_matrix", "scale_from_matrix", "projection_matrix",
    "projection_from_matrix", "clip_matrix", "shear_matrix", "shear_from_matrix",
    "orthogonalization_matrix", "superimposition_matrix", "random_vector", "Arcball",
    "arcball_map_to_sphere", "arcball_constrain_to_axis", "arcball_nearest_axis",
)  # fmt: skip


def __getattr__(name: str) -> Any:
    if name in _NOT_OFFERED:

        def not_offered(*args: Any, **kwargs: Any) -> NoReturn:
            _not_offered(f"{name}()")

        not_offered.__name__ = name
        return not_offered
    raise AttributeError(f"module 'tf.transformations' has no attribute '{name}'")
