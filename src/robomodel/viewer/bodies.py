"""Transforms of floating and planar joints from the joint panel's pose inputs.

robot_state_publisher publishes nothing for a floating joint and a fixed identity for a planar
one (kdl_parser turns both into fixed joints); the viewer publishes what the controls say.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from robomodel.description.model import Joint, JointType
from robomodel.description.model.pose import matrix_from_xyz_rpy
from robomodel.viewer.joint_panel import BodyPose

__all__ = ["body_transform"]


def _rotation_about(axis: NDArray[np.float64], angle_rad: float) -> NDArray[np.float64]:
    x, y, z = axis
    c, s, C = math.cos(angle_rad), math.sin(angle_rad), 1.0 - math.cos(angle_rad)
    return np.array(
        [
            [c + x * x * C, x * y * C - z * s, x * z * C + y * s],
            [y * x * C + z * s, c + y * y * C, y * z * C - x * s],
            [z * x * C - y * s, z * y * C + x * s, c + z * z * C],
        ]
    )


def _plane_basis(normal: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    helper = np.array([1.0, 0.0, 0.0]) if abs(normal[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    u = np.cross(normal, helper)
    u /= np.linalg.norm(u)
    return u, np.cross(normal, u)


def body_transform(joint: Joint, pose: BodyPose) -> NDArray[np.float64]:
    """``T_parent_child`` of a floating or planar joint at ``pose`` (after its ``<origin>``).

    A planar joint moves in the plane normal to its axis (x, y along an orthonormal basis of
    that plane) and turns about the axis by ``pose.rpy_rad[2]``.
    """
    T_parent_joint = joint.origin.matrix()
    if joint.type is JointType.PLANAR:
        axis = np.asarray(joint.axis, dtype=np.float64)
        norm = float(np.linalg.norm(axis))
        normal = axis / norm if norm > 0 else np.array([0.0, 0.0, 1.0])
        u, v = _plane_basis(normal)
        motion = np.eye(4)
        motion[:3, :3] = _rotation_about(normal, pose.rpy_rad[2])
        motion[:3, 3] = pose.xyz_m[0] * u + pose.xyz_m[1] * v
    else:
        motion = matrix_from_xyz_rpy(pose.xyz_m, pose.rpy_rad)
    return T_parent_joint @ motion
