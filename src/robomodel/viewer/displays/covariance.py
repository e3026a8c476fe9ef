"""The shapes of RViz's covariance visual: the position ellipsoid and the orientation discs.

Transcribed from rviz_rendering ``objects/covariance_visual.cpp`` (github:ros2/rviz at
f7112b1a):

- 3D pose (any of the z, roll, pitch variances above zero): the position part is a sphere
  scaled by ``2 sqrt(eigenvalue)`` along the eigenvectors of the 3x3 position block
  (``computeShapeScaleAndOrientation3D``), times the position Scale. The orientation part is
  one flat disc (a cylinder 1 mm thick) per axis, ``Offset`` along that axis, showing how the
  axis' tip wobbles: at the x axis (``kRoll``) the pitch/yaw block, at y (``kPitch``) the
  roll/yaw block, at z (``kYaw``) the roll/pitch block (``updateOrientation``); each disc's
  diameters are ``2 tan(Scale * sqrt(eigenvalue))`` [rad -> m, bounded at 89 degrees]
  (``radianScaleToMetricScaleBounded``) times ``Offset``, along the block's eigenvectors laid
  in the disc's plane as the offset nodes orient it (``CovarianceVisual`` constructor:
  roll ``Rx(90) Rz(90)``, pitch ``Ry(90)``, yaw ``Rx(90)``; the cylinder's axis is its y).
- 2D pose (z, roll and pitch variances all zero or below): the position part is the x/y
  ellipse, 1 mm thick; the orientation part is one flat triangle from the pose's origin
  ``Offset`` along its +x, ``2 tan(Scale * sqrt(yaw variance)) * Offset`` wide at its end
  (the ``kYaw2D`` cone, flattened).
- A covariance with a NaN in its first row's position entries is not drawn (``setCovariance``);
  a negative eigenvalue draws the shape with zero size, as RViz hides it.

The orientation shapes are in the pose's frame (Frame "Local") or in the message frame's
axes at the pose's position (Frame "Fixed": RViz's ``fixed_orientation_node_``).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel.viewer._deps import import_trimesh

__all__ = ["CovarianceShapes", "covariance_shapes"]

_MAX_DEGREES = 89.0  # covariance_visual.hpp kMaxDegrees
_THICKNESS_M = 0.001  # "a minimal height ... for better visualization"

Mesh = tuple[NDArray[np.float32], NDArray[np.uint32]]


def _rot(axis: int, degrees: float) -> NDArray[np.float64]:
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    i, j = (axis + 1) % 3, (axis + 2) % 3
    R = np.eye(3)
    R[i, i], R[i, j], R[j, i], R[j, j] = c, -s, s, c
    return R


# (position along the axis, orientation of the offset node, covariance indices of the block)
_DISCS = (
    (np.array([1.0, 0.0, 0.0]), _rot(0, 90) @ _rot(2, 90), (4, 5)),  # roll: pitch, yaw
    (np.array([0.0, 1.0, 0.0]), _rot(1, 90), (3, 5)),  # pitch: roll, yaw
    (np.array([0.0, 0.0, 1.0]), _rot(0, 90), (3, 4)),  # yaw: roll, pitch
)


@dataclass(frozen=True, slots=True)
class CovarianceShapes:
    """One covariance's shapes, in the pose's position.

    Attributes:
        R_frame_ellipsoid: (3, 3) the ellipsoid's axes (columns) in the message frame.
        radii_m: (3,) the ellipsoid's semi-axes [m] (Scale applied).
        orientation: Meshes in the orientation frame (Local: the pose's; Fixed: the message
            frame's axes): roll, pitch and yaw discs for a 3D pose, one triangle for 2D.
        is_2d: Whether RViz reads it as a 2D pose.
    """

    R_frame_ellipsoid: NDArray[np.float64]
    radii_m: NDArray[np.float64]
    orientation: tuple[Mesh, ...]
    is_2d: bool


def _eigen(block: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Eigenvalues and right-handed eigenvectors (columns), as diagonalizeCovariance."""
    values, vectors = np.linalg.eigh((block + block.T) / 2.0)
    if values.min() < 0:  # "Is the covariance matrix correct?": hidden (scale zero)
        return np.zeros(len(values)), np.eye(len(values))
    n = len(values)
    c0 = np.append(vectors[:, 0], [0.0] * (3 - n))
    c1 = np.append(vectors[:, 1], [0.0] * (3 - n))
    c2 = vectors[:, 2] if n == 3 else np.array([0.0, 0.0, 1.0])
    if np.cross(c0, c1) @ c2 < 0:  # makeRightHanded: swap the first two
        vectors, values = vectors[:, [1, 0, *range(2, n)]], values[[1, 0, *range(2, n)]]
    return values, vectors


def _metric(radians: float) -> float:
    """radianScaleToMetricScaleBounded: an angle's full width [rad] -> a width at 1 m."""
    if radians > 2.0 * math.radians(_MAX_DEGREES):
        return 2.0 * math.tan(math.radians(_MAX_DEGREES))
    return 2.0 * math.tan(radians * 0.5)


@functools.cache
def _unit(shape: str) -> Mesh:
    """RViz's unit shapes: a cylinder along y (diameter 1, height 1, centred); a cone along
    -x with its tip at the origin and base (diameter 1) at x = 1 (the kYaw2D cone as placed)."""
    creation = import_trimesh().creation
    if shape == "cylinder":
        mesh = creation.cylinder(radius=0.5, height=1.0, sections=32)
        vertices = np.asarray(mesh.vertices)[:, [0, 2, 1]] * [1.0, -1.0, 1.0]  # z -> y
    else:
        mesh = creation.cone(radius=0.5, height=1.0, sections=32)  # tip at z = 1
        v = np.asarray(mesh.vertices)
        vertices = np.stack([1.0 - v[:, 2], v[:, 1], v[:, 0]], axis=1)  # a rotation
    return vertices.astype(np.float32), np.asarray(mesh.faces, dtype=np.uint32)


def _disc(position: NDArray[np.float64], R_offset: NDArray[np.float64], block: NDArray[np.float64], scale: float, offset: float) -> Mesh:  # fmt: skip
    values, vectors = _eigen(block)
    # computeShapeScaleAndOrientation2D, XZ_PLANE: eigenvector k in the disc's (x, z)
    R_shape = np.array([[vectors[0, 0], 0.0, vectors[0, 1]], [0.0, 1.0, 0.0],
                        [vectors[1, 0], 0.0, vectors[1, 1]]])  # fmt: skip
    sx, sz = (_metric(2.0 * math.sqrt(v) * scale) for v in values)
    vertices, faces = _unit("cylinder")
    local = vertices * np.array([offset * sx, _THICKNESS_M, offset * sz])
    return ((local @ (R_offset @ R_shape).T + offset * position).astype(np.float32), faces)


def covariance_shapes(covariance: Any, *, position_scale: float = 1.0, orientation_scale: float = 1.0, orientation_offset: float = 1.0) -> CovarianceShapes | None:  # fmt: skip
    """RViz's covariance shapes for a 6x6 pose covariance (36 values, row-major; x, y, z,
    roll, pitch, yaw), with the Position Scale and Orientation Scale / Offset options; None
    when RViz would not draw it (NaN)."""
    c = np.asarray(covariance, dtype=np.float64).reshape(6, 6)
    if np.isnan(c[0, :3]).any():
        return None
    is_2d = bool(c[2, 2] <= 0 and c[3, 3] <= 0 and c[4, 4] <= 0)
    if is_2d:
        values, vectors = _eigen(c[:2, :2])
        R = np.eye(3)
        R[:2, :2] = vectors
        radii = np.append(position_scale * np.sqrt(values), _THICKNESS_M / 2)
        width = _metric(2.0 * math.sqrt(max(c[5, 5], 0.0)) * orientation_scale)
        vertices, faces = _unit("cone")
        cone = vertices * np.array([orientation_offset, orientation_offset * width, _THICKNESS_M])
        return CovarianceShapes(R, radii, ((cone.astype(np.float32), faces),), True)
    values, R = _eigen(c[:3, :3])
    discs = tuple(
        _disc(position, R_offset, c[np.ix_(block, block)], orientation_scale, orientation_offset)
        for position, R_offset, block in _DISCS
    )
    return CovarianceShapes(R, position_scale * np.sqrt(values), discs, False)
