"""Scenery: shapes that belong to no robot (a simulated world's walls and obstacles).

Gazebo's window shows the world around the robot; RViz shows it through markers. The viewer
draws each :class:`SceneryShape` in its TF frame (``world`` for static objects, a frame the
simulator publishes for objects that move), re-posed with every update like the robots' links,
and hidden while its frame is not connected to the fixed frame.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel.description.model.pose import matrix_from_xyz_rpy
from robomodel.tf.exceptions import TransformError
from robomodel.viewer._poses import wxyz_xyz_from_matrix
from robomodel.viewer.materials import rgb255

__all__ = ["SceneryDisplay", "SceneryShape"]

_KINDS = ("box", "cylinder", "sphere")


@dataclass(frozen=True, slots=True)
class SceneryShape:
    """One shape of the scenery.

    Attributes:
        name: Unique name (the scene node is ``/scenery/<name>``).
        frame: TF frame the pose is given in.
        kind: ``box``, ``cylinder`` or ``sphere``.
        size_m: box (x, y, z) full size; cylinder (radius, length, 0); sphere (radius, 0, 0).
        xyz_m, rpy_rad: Pose of the shape's centre in ``frame``.
        rgba: Colour in [0, 1].
    """

    name: str
    frame: str
    kind: str
    size_m: tuple[float, float, float]
    xyz_m: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy_rad: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rgba: tuple[float, float, float, float] = (0.6, 0.6, 0.6, 1.0)

    def __post_init__(self) -> None:
        if self.kind not in _KINDS:
            raise ValueError(f"scenery kind must be one of {', '.join(_KINDS)}, got {self.kind!r}")

    def matrix(self) -> NDArray[np.float64]:
        """The shape's pose in its frame (4x4)."""
        return matrix_from_xyz_rpy(self.xyz_m, self.rpy_rad)


class SceneryDisplay:
    """The scene nodes of the scenery and their per-update poses."""

    def __init__(self, scene: Any, shapes: tuple[SceneryShape, ...]) -> None:
        self.shapes = shapes
        self.nodes: list[Any] = []
        self._leaves: list[Any] = []
        self.shown = 0
        self._sent: list[object] = []
        for shape in shapes:
            node = scene.add_frame(f"/scenery/{shape.name}", show_axes=False, visible=False)
            common: dict[str, Any] = {
                "color": rgb255(shape.rgba),
                "opacity": min(max(shape.rgba[3], 0.0), 1.0),
                "cast_shadow": False,
                "receive_shadow": False,
            }
            a, b, c = shape.size_m
            leaf = f"/scenery/{shape.name}/g"
            if shape.kind == "box":
                geometry = scene.add_box(leaf, dimensions=(a, b, c), **common)
            elif shape.kind == "cylinder":
                geometry = scene.add_cylinder(
                    leaf, radius=a, height=b, radial_segments=32, **common
                )
            else:
                geometry = scene.add_icosphere(leaf, radius=a, subdivisions=3, **common)
            self.nodes.append(node)
            self._leaves.append(geometry)
            self._sent.append(None)

    def remove(self) -> None:
        """Take every shape out of the scene."""
        for handle in (*self._leaves, *self.nodes):
            handle.remove()
        self._leaves.clear()
        self.nodes.clear()
        self.shown = 0

    def update(self, buffer: Any, fixed_frame: str) -> None:
        """Pose every shape in ``fixed_frame`` (inside the caller's atomic batch)."""
        frames: dict[str, NDArray[np.float64] | None] = {}
        shown = 0
        for i, (shape, node) in enumerate(zip(self.shapes, self.nodes, strict=True)):
            if shape.frame not in frames:
                frames[shape.frame] = _lookup(buffer, fixed_frame, shape.frame)
            base = frames[shape.frame]
            pose = None if base is None else wxyz_xyz_from_matrix(base @ shape.matrix())
            if pose != self._sent[i]:  # unchanged poses are not sent again
                self._sent[i] = pose
                if pose is None:
                    node.visible = False
                else:
                    node.wxyz, node.position, node.visible = pose[0], pose[1], True
            shown += pose is not None
        self.shown = shown


def _lookup(buffer: Any, fixed_frame: str, frame: str) -> NDArray[np.float64] | None:
    if frame == fixed_frame:
        return np.eye(4)
    try:
        matrix: NDArray[np.float64] = buffer.lookup_transform(fixed_frame, frame).matrix()
    except TransformError:
        return None
    return matrix
