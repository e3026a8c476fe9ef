"""Geometry of RViz's pose-like displays: arrows, flat arrows, covariance ellipsoids, wrenches,
paths and the Odometry display's arrow trail, as numpy arrays in the message's frame.

Shapes follow rviz_rendering and rviz_default_plugins (ROS 2 rviz): an arrow points along its
pose's +x (rviz_rendering/objects/arrow.cpp, set by the Pose display); PoseArray's "Arrow
(Flat)" is three lines, shaft and two head strokes at 0.75 length and +-0.2 length
(pose_array/flat_arrows_array.cpp); a covariance ellipsoid's semi-axes are the standard
deviations along the covariance's eigenvectors (covariance_visual.cpp: a unit-diameter sphere
scaled by 2 sqrt(eigenvalue)); a wrench's arrows are RViz's default arrow (shaft 1, head 0.3,
diameters 0.1 and 0.2) scaled by (|v| * scale, width, width), the torque with 7/8 of a circle
at half its length (wrench_visual.cpp).
"""

from __future__ import annotations

import collections
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel.description.rigid import conjugate_xyzw, qmul_xyzw

__all__ = [
    "ArrowTrail",
    "WrenchShapes",
    "arrow_segments",
    "covariance_ellipsoid",
    "flat_arrow_segments",
    "matrix_from_xyz_xyzw",
    "pose_matrices",
    "poses_from_msgs",
    "quaternion_angular_distance",
    "transform_points",
    "wrench_shapes",
]


def matrix_from_xyz_xyzw(xyz: Sequence[float], xyzw: Sequence[float]) -> NDArray[np.float64]:
    """A 4x4 pose from a position [m] and a quaternion ``xyzw`` (normalised; zero -> identity)."""
    T: NDArray[np.float64] = pose_matrices(np.asarray([xyz], float), np.asarray([xyzw], float))[0]
    return T


def pose_matrices(xyz: NDArray[np.float64], xyzw: NDArray[np.float64]) -> NDArray[np.float64]:
    """4x4 poses (n, 4, 4) from positions (n, 3) [m] and quaternions ``xyzw`` (n, 4)."""
    q = np.asarray(xyzw, dtype=np.float64).reshape(-1, 4)
    norm = np.linalg.norm(q, axis=1, keepdims=True)
    q = np.where(norm > 0, q / np.where(norm > 0, norm, 1.0), [0.0, 0.0, 0.0, 1.0])
    x, y, z, w = q.T
    T = np.zeros((q.shape[0], 4, 4))
    T[:, 0, 0], T[:, 0, 1], T[:, 0, 2] = 1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)  # fmt: skip
    T[:, 1, 0], T[:, 1, 1], T[:, 1, 2] = 2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)  # fmt: skip
    T[:, 2, 0], T[:, 2, 1], T[:, 2, 2] = 2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)  # fmt: skip
    T[:, :3, 3] = np.asarray(xyz, dtype=np.float64).reshape(-1, 3)
    T[:, 3, 3] = 1.0
    return T


def poses_from_msgs(poses: Sequence[Any]) -> NDArray[np.float64]:
    """4x4 matrices (n, 4, 4) of geometry_msgs/Pose messages."""
    xyz = np.array([(p.position.x, p.position.y, p.position.z) for p in poses], float)
    xyzw = np.array(
        [(p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w) for p in poses],
        float,
    )
    return pose_matrices(xyz.reshape(-1, 3), xyzw.reshape(-1, 4))


def transform_points(T: NDArray[np.float64], points: NDArray[np.floating[Any]]) -> NDArray[np.float64]:  # fmt: skip
    """``T @ p`` for points (..., 3)."""
    p = np.asarray(points, dtype=np.float64)
    out: NDArray[np.float64] = p @ T[:3, :3].T + T[:3, 3]
    return out


def arrow_segments(Ts: NDArray[np.float64], length_m: float) -> NDArray[np.float64]:
    """(n, 2, 3) start and tip of arrows ``length_m`` long along each pose's +x."""
    starts = Ts[:, :3, 3]
    return np.stack([starts, starts + Ts[:, :3, 0] * length_m], axis=1)


def flat_arrow_segments(Ts: NDArray[np.float64], length_m: float) -> NDArray[np.float64]:
    """(3n, 2, 3) line segments of PoseArray's "Arrow (Flat)": shaft and two head strokes."""
    local = np.array([[length_m, 0, 0], [0.75 * length_m, 0.2 * length_m, 0],
                      [0.75 * length_m, -0.2 * length_m, 0]])  # fmt: skip
    tips = Ts[:, :3, :3] @ local.T  # (n, 3, 3): columns are the three points
    base = Ts[:, :3, 3]
    tip, left, right = (base + tips[:, :, k] for k in range(3))
    segments = np.stack(
        [np.stack([base, tip], 1), np.stack([tip, left], 1), np.stack([tip, right], 1)], axis=1
    )
    return segments.reshape(-1, 2, 3)


def covariance_ellipsoid(cov: NDArray[np.floating[Any]], scale: float = 1.0) -> tuple[NDArray[np.float64], NDArray[np.float64]]:  # fmt: skip
    """The position covariance's ellipsoid: rotation (3, 3) with the axes as columns (right
    handed) and semi-axes (3,) = ``scale * sqrt(eigenvalue)`` [m].

    Args:
        cov: The 6x6 pose covariance (row-major, 36 values) or its 3x3 position block.
        scale: RViz's Covariance > Position > "Scale".
    """
    c = np.asarray(cov, dtype=np.float64)
    c = c.reshape(6, 6)[:3, :3] if c.size == 36 else c.reshape(3, 3)
    values, vectors = np.linalg.eigh((c + c.T) / 2.0)
    if np.linalg.det(vectors) < 0:  # RViz's makeRightHanded swaps the first two
        vectors = vectors[:, [1, 0, 2]]
        values = values[[1, 0, 2]]
    return vectors, scale * np.sqrt(np.maximum(values, 0.0))


@dataclass(frozen=True, slots=True)
class WrenchShapes:
    """A wrench's arrows in its frame; an arrow is None when not longer than the width (RViz).

    Attributes:
        force, torque: (2, 3) start and tip [m], or None.
        torque_circle: (29, 3) polyline around the torque arrow, or None.
        shaft_radius_m, head_radius_m: Arrow radii [m].
        force_head_m, torque_head_m: Head lengths [m].
    """

    force: NDArray[np.float64] | None
    torque: NDArray[np.float64] | None
    torque_circle: NDArray[np.float64] | None
    shaft_radius_m: float
    head_radius_m: float
    force_head_m: float
    torque_head_m: float


def _rotation_z_to(direction: NDArray[np.float64]) -> NDArray[np.float64]:
    """The shortest rotation taking +z to ``direction`` (Ogre getRotationTo)."""
    d = direction / np.linalg.norm(direction)
    z = np.array([0.0, 0.0, 1.0])
    axis = np.cross(z, d)
    s, c = np.linalg.norm(axis), float(z @ d)
    if s < 1e-12:
        return np.eye(3) if c > 0 else np.diag([1.0, -1.0, -1.0])
    k = axis / s
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    R: NDArray[np.float64] = np.eye(3) + s * K + (1 - c) * (K @ K)
    return R


def wrench_shapes(
    force: Sequence[float],
    torque: Sequence[float],
    *,
    force_scale: float = 2.0,
    torque_scale: float = 2.0,
    width: float = 0.5,
) -> WrenchShapes:
    """RViz's WrenchVisual for one wrench ("Force Arrow Scale", "Torque Arrow Scale", "Arrow
    Width"), in the wrench's frame with the origin at the frame's origin."""
    f, t = np.asarray(force, float), np.asarray(torque, float)
    f_len, t_len = float(np.linalg.norm(f)) * force_scale, float(np.linalg.norm(t)) * torque_scale
    force_arrow = torque_arrow = circle = None
    if f_len > width:
        force_arrow = np.stack([np.zeros(3), f / np.linalg.norm(f) * 1.3 * f_len])
    if t_len > width:
        torque_arrow = np.stack([np.zeros(3), t / np.linalg.norm(t) * 1.3 * t_len])
        angles = np.arange(4, 33) * 2 * math.pi / 32
        radius, height = t_len / 4, np.full(angles.size, t_len / 2)
        ring = np.stack([radius * np.cos(angles), radius * np.sin(angles), height], axis=1)
        circle = ring @ _rotation_z_to(t).T
    return WrenchShapes(force_arrow, torque_arrow, circle, 0.05 * width, 0.1 * width, 0.3 * f_len, 0.3 * t_len)  # fmt: skip


def quaternion_angular_distance(a_xyzw: Sequence[float], b_xyzw: Sequence[float]) -> float:
    """RViz's ogreQuaternionAngularDistance: the rotation angle of ``a * conj(b)`` [rad]."""
    ax, ay, az, aw = a_xyzw
    bx, by, bz, bw = b_xyzw
    x, y, z, w = qmul_xyzw((ax, ay, az, aw), conjugate_xyzw((bx, by, bz, bw)))
    return 2.0 * math.atan2(math.sqrt(x * x + y * y + z * z), abs(w))


class ArrowTrail:
    """The Odometry display's arrows: a pose is kept when it moved at least "Position
    Tolerance" [m] or turned "Angle Tolerance" [rad] from the last kept one; at most "Keep"
    (0: all) are kept, oldest dropped (odometry_display.cpp)."""

    def __init__(self, position_tolerance_m: float = 0.1, angle_tolerance_rad: float = 0.1, keep: int = 100) -> None:  # fmt: skip
        self.position_tolerance_m = position_tolerance_m
        self.angle_tolerance_rad = angle_tolerance_rad
        self.keep = keep
        self.poses: collections.deque[NDArray[np.float64]] = collections.deque()
        self._last: tuple[tuple[float, ...], tuple[float, ...]] | None = None

    def offer(self, xyz: Sequence[float], xyzw: Sequence[float], T_fixed_pose: NDArray[np.float64]) -> bool:  # fmt: skip
        """Keep ``T_fixed_pose`` unless the message pose (``xyz``, ``xyzw``, in its own
        frame) is within both tolerances of the last kept one; return whether it was kept."""
        if self._last is not None:
            near = math.dist(self._last[0], xyz) < self.position_tolerance_m
            same = quaternion_angular_distance(self._last[1], xyzw) < self.angle_tolerance_rad
            if near and same:
                return False
        self._last = (tuple(xyz), tuple(xyzw))
        self.poses.append(np.array(T_fixed_pose, dtype=np.float64))
        self.trim()
        return True

    def trim(self) -> None:
        """Drop the oldest poses beyond ``keep`` (0 keeps all)."""
        while self.keep > 0 and len(self.poses) > self.keep:
            self.poses.popleft()

    def clear(self) -> None:
        self.poses.clear()
        self._last = None

    def matrices(self) -> NDArray[np.float64]:
        """The kept poses (n, 4, 4) in the fixed frame."""
        return np.stack(list(self.poses)) if self.poses else np.zeros((0, 4, 4))
