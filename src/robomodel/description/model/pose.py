"""The ``<origin>`` element: a pose given as xyz and rpy, or (URDF 1.1) a quaternion."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from robomodel.description.rigid import quat_xyzw_from_rpy, rpy_from_quat_xyzw

if TYPE_CHECKING:
    import numpy as np
    from numpy.typing import NDArray

__all__ = ["Origin", "matrix_from_xyz_rpy", "quat_xyzw_from_rpy", "rpy_from_quat_xyzw"]


@dataclass(frozen=True, slots=True)
class Origin:
    """A pose. ``xyz_m`` [m]; ``rpy_rad`` fixed-axis roll, pitch, yaw [rad], R = Rz·Ry·Rx.

    When the file gave ``quat_xyzw`` (URDF 1.1), it is kept and takes precedence over rpy.
    """

    xyz_m: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy_rad: tuple[float, float, float] = (0.0, 0.0, 0.0)
    quat_xyzw: tuple[float, float, float, float] | None = None

    @property
    def is_identity(self) -> bool:
        return (
            self.xyz_m == (0.0, 0.0, 0.0)
            and self.rpy_rad == (0.0, 0.0, 0.0)
            and self.quat_xyzw is None
        )

    def quaternion_xyzw(self) -> tuple[float, float, float, float]:
        """The normalised rotation quaternion, as urdfdom stores it."""
        if self.quat_xyzw is not None:
            x, y, z, w = self.quat_xyzw
            norm = math.sqrt(x * x + y * y + z * z + w * w)
            if norm == 0.0:
                return (0.0, 0.0, 0.0, 1.0)
            return (x / norm, y / norm, z / norm, w / norm)
        return quat_xyzw_from_rpy(*self.rpy_rad)

    def matrix(self) -> NDArray[np.float64]:
        """The 4x4 homogeneous transform of this pose."""
        import numpy as np  # not at the top: parsing and checking a URDF never need numpy

        if self.quat_xyzw is None:
            return matrix_from_xyz_rpy(self.xyz_m, self.rpy_rad)
        x, y, z, w = self.quaternion_xyzw()
        T = np.eye(4)
        T[:3, :3] = [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
        T[:3, 3] = self.xyz_m
        return T


def matrix_from_xyz_rpy(
    xyz: tuple[float, float, float], rpy: tuple[float, float, float]
) -> NDArray[np.float64]:
    """4x4 transform from translation [m] and fixed-axis roll, pitch, yaw [rad]."""
    import numpy as np

    r, p, y = rpy
    cr, sr = math.cos(r), math.sin(r)
    cp, sp = math.cos(p), math.sin(p)
    cy, sy = math.cos(y), math.sin(y)
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr, xyz[0]],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr, xyz[1]],
            [-sp, cp * sr, cp * cr, xyz[2]],
            [0.0, 0.0, 0.0, 1.0],
        ]
    )
