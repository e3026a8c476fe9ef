"""``geometry_msgs/TransformStamped`` as a frozen dataclass, and tf2's time display."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from robomodel.kinematics.se3 import matrix_from_quat_xyzw, quat_xyzw_from_matrix

__all__ = ["TransformStamped", "display_time"]


def display_time(stamp_ns: int) -> str:
    """tf2's ``displayTimePoint``: seconds with 6 decimals."""
    return f"{stamp_ns / 1e9:.6f}"


@dataclass(frozen=True, slots=True)
class TransformStamped:
    """The pose of ``child_frame_id`` in ``frame_id`` at ``stamp_ns`` [ns since the epoch].

    ``translation_m`` [m] and ``rotation_xyzw`` (a unit quaternion) as in the ROS message.
    """

    frame_id: str
    child_frame_id: str
    translation_m: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rotation_xyzw: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0)
    stamp_ns: int = 0

    @property
    def sec(self) -> int:
        return self.stamp_ns // 1_000_000_000

    @property
    def nanosec(self) -> int:
        return self.stamp_ns % 1_000_000_000

    def matrix(self) -> NDArray[np.float64]:
        """``T_frame_child`` as a 4x4 matrix."""
        T = np.eye(4)
        T[:3, :3] = matrix_from_quat_xyzw(self.rotation_xyzw)
        T[:3, 3] = self.translation_m
        return T

    @classmethod
    def from_matrix(
        cls, frame_id: str, child_frame_id: str, T: NDArray[np.float64], stamp_ns: int = 0
    ) -> TransformStamped:
        """Build from a 4x4 transform ``T_frame_child``."""
        q = quat_xyzw_from_matrix(T[:3, :3])
        t = T[:3, 3]
        return cls(
            frame_id,
            child_frame_id,
            (float(t[0]), float(t[1]), float(t[2])),
            (float(q[0]), float(q[1]), float(q[2]), float(q[3])),
            stamp_ns,
        )
