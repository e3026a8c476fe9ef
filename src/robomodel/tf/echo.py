"""tf2_echo's output block (``tf2_ros/src/tf2_echo.cpp``), character for character."""

from __future__ import annotations

import math

import numpy as np

from robomodel.kinematics.se3 import rpy_from_matrix
from robomodel.tf.message import TransformStamped

__all__ = ["format_echo", "format_failure"]


def _fixed(values: list[float]) -> str:
    return ", ".join(f"{v:.3f}" for v in values)


def _tf2_matrix(q: list[float]) -> list[list[float]]:
    """``tf2::Matrix3x3::setRotation`` with its operation order (signed zeros included)."""
    x, y, z, w = q
    s = 2.0 / (x * x + y * y + z * z + w * w)
    xs, ys, zs = x * s, y * s, z * s
    wx, wy, wz = w * xs, w * ys, w * zs
    xx, xy, xz = x * xs, x * ys, x * zs
    yy, yz, zz = y * ys, y * zs, z * zs
    return [
        [1.0 - (yy + zz), xy - wz, xz + wy],
        [xy + wz, 1.0 - (xx + zz), yz - wx],
        [xz - wy, yz + wx, 1.0 - (xx + yy)],
    ]


def format_echo(transform: TransformStamped) -> str:
    """What tf2_echo prints for one lookup (precision 3, fixed; RPY from getEulerYPR)."""
    t = list(transform.translation_m)
    q = list(transform.rotation_xyzw)
    R = np.array(_tf2_matrix(q))
    roll, pitch, yaw = (float(v) for v in rpy_from_matrix(R))
    deg = 180.0 / math.pi
    lines = [
        f"At time {transform.sec}.{transform.nanosec}",
        f"- Translation: [{_fixed(t)}]",
        f"- Rotation: in Quaternion [{_fixed(q)}]",
        f"- Rotation: in RPY (radian) [{_fixed([roll, pitch, yaw])}]",
        f"- Rotation: in RPY (degree) [{_fixed([roll * deg, pitch * deg, yaw * deg])}]",
        "- Matrix:",
    ]
    for i in range(3):
        row = [float(R[i, 0]), float(R[i, 1]), float(R[i, 2]), t[i]]
        lines.append("".join(f" {v:6.3f}" for v in row))
    lines.append("".join(f" {v:6.3f}" for v in (0.0, 0.0, 0.0, 1.0)))
    return "\n".join(lines) + "\n"


def format_failure(now_s: float, what: str, frames: str) -> str:
    """tf2_echo's block when the lookup throws."""
    return (
        f"Failure at {now_s:.3f}\nException thrown:{what}\nThe current list of frames is:\n"
        f"{frames}\n"
    )
