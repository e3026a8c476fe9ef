"""The TF display: axes for every frame (one batched node) and optional names.

As RViz's TF display: Show Axes, Show Names, Marker Scale; frames are drawn where they are in
the fixed frame, and frames with no transform to it are not drawn. The axes are three batched
cylinder meshes (x, y, z), so that each frame's axes take their own colour and opacity as the
frame ages (viser's batched axes take neither); viser's labels take no colour or opacity, so a
frame's name is drawn as it is until the frame is hidden.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["TFDisplay"]

# RViz's TF axes are 0.1 m long at Marker Scale 1 (rviz_rendering::Axes(…, 0.1, 0.01)).
_AXES_LENGTH_M = 0.1
_AXES_RADIUS_M = 0.004
_AXIS_NAMES = ("x", "y", "z")
_FRESH_AXES_RGBA = np.array([[1.0, 0, 0, 1], [0, 1.0, 0, 1], [0, 0, 1.0, 1]])


def _axis_mesh(axis: int, length_m: float, radius_m: float, sections: int = 12) -> tuple[NDArray[np.float64], NDArray[np.int64]]:  # fmt: skip
    """A closed cylinder from the origin along ``axis`` (0, 1, 2: x, y, z): vertices and faces,
    wound outwards. Built here rather than with trimesh, whose import (scipy, networkx, shapely)
    would double the start-up of a viewer that draws no mesh file."""
    angles = np.linspace(0.0, 2.0 * np.pi, sections, endpoint=False)
    ring = np.column_stack([radius_m * np.cos(angles), radius_m * np.sin(angles)])
    n = sections
    vertices = np.vstack([
        np.column_stack([ring, np.zeros(n)]),  # 0..n-1: the base ring, at 0
        np.column_stack([ring, np.full(n, length_m)]),  # n..2n-1: the top ring
        [[0.0, 0.0, 0.0], [0.0, 0.0, length_m]],  # 2n, 2n+1: the caps' centres
    ])  # fmt: skip
    i = np.arange(n)
    j = (i + 1) % n
    faces = np.vstack([
        np.column_stack([i, j, j + n]), np.column_stack([i, j + n, i + n]),  # the side
        np.column_stack([np.full(n, 2 * n), j, i]),  # the base, facing -z
        np.column_stack([np.full(n, 2 * n + 1), i + n, j + n]),  # the top, facing +z
    ]).astype(np.int64)  # fmt: skip
    return np.roll(vertices, axis + 1, axis=1), faces  # z -> x (roll 1), z -> y (roll 2)


class TFDisplay:
    """Axes and labels for TF frames below the scene node ``root``."""

    def __init__(
        self,
        scene: Any,
        root: str = "/tf",
        *,
        show_axes: bool = True,
        show_names: bool = False,
        marker_scale: float = 1.0,
    ) -> None:
        self.scene = scene
        self.root = root
        self.show_axes = show_axes
        self.show_names = show_names
        self.marker_scale = marker_scale
        self.frames: tuple[str, ...] = ()
        self._axes: list[Any] = []  # the x, y and z cylinders' batched meshes
        self._labels: dict[str, Any] = {}
        self._wxyz = np.zeros((0, 4))
        self._xyz = np.zeros((0, 3))
        self._visible = np.zeros(0, dtype=bool)
        self._axes_rgba = np.zeros((0, 3, 4))
        self._dirty = True
        self._axes_count = 0

    def update(
        self,
        frames: tuple[str, ...],
        wxyz: NDArray[np.float64],
        xyz: NDArray[np.float64],
        visible: NDArray[np.bool_],
        axes_rgba: NDArray[np.float64] | None = None,
    ) -> None:
        """Draw ``frames`` at the given poses in the fixed frame; send only when changed.

        ``axes_rgba``: shape (n, 3, 4), each frame's x, y and z axis colour (RGBA, 0..1);
        None: red, green and blue, opaque.
        """
        if axes_rgba is None:
            axes_rgba = np.broadcast_to(_FRESH_AXES_RGBA, (len(frames), 3, 4))
        if frames != self.frames:
            self._rebuild_labels(frames)
            self.frames = frames
            self._dirty = True
        changed = self._dirty or not (
            np.array_equal(visible, self._visible)
            and np.allclose(wxyz, self._wxyz, atol=1e-7)
            and np.allclose(xyz, self._xyz, atol=1e-6)
            and np.allclose(axes_rgba, self._axes_rgba, atol=1e-3)
        )
        if not changed:
            return
        self._wxyz, self._xyz, self._visible = wxyz.copy(), xyz.copy(), visible.copy()
        self._axes_rgba = np.array(axes_rgba, dtype=np.float64)
        self._dirty = False
        self._send_axes()
        if self.show_names:
            self._send_labels()

    def _send_axes(self, *, recreate: bool = False) -> None:
        shown = self._visible & self.show_axes
        count = int(shown.sum())
        if self._axes and (recreate or count != self._axes_count):
            self._remove_axes()
        if count == 0:
            return
        rgba = self._axes_rgba[shown]
        colors = np.floor(rgba[..., :3] * 255 + 0.5).astype(np.uint8)
        opacities = rgba[..., 3].astype(np.float32)
        if not self._axes:
            length_m, radius_m = _AXES_LENGTH_M * self.marker_scale, _AXES_RADIUS_M * self.marker_scale  # fmt: skip
            for axis, name in enumerate(_AXIS_NAMES):
                vertices, faces = _axis_mesh(axis, length_m, radius_m)
                self._axes.append(self.scene.add_batched_meshes_simple(
                    f"{self.root}/axes/{name}", vertices, faces,
                    batched_wxyzs=self._wxyz[shown], batched_positions=self._xyz[shown],
                    batched_colors=colors[:, axis], batched_opacities=opacities[:, axis],
                    lod="off", cast_shadow=False, receive_shadow=False,
                ))  # fmt: skip
            self._axes_count = count
            return
        for axis, handle in enumerate(self._axes):
            handle.batched_wxyzs = self._wxyz[shown]
            handle.batched_positions = self._xyz[shown]
            handle.batched_colors = colors[:, axis]
            handle.batched_opacities = opacities[:, axis]

    def _remove_axes(self) -> None:
        for handle in self._axes:
            handle.remove()
        self._axes = []

    def _rebuild_labels(self, frames: tuple[str, ...]) -> None:
        for label in self._labels.values():
            label.remove()
        self._labels = {}
        if self.show_names:
            for i, frame in enumerate(frames):
                self._labels[frame] = self.scene.add_label(
                    f"{self.root}/names/f{i}", frame, visible=False
                )

    def _send_labels(self) -> None:
        for i, frame in enumerate(self.frames):
            label = self._labels.get(frame)
            if label is None:
                continue
            label.position = self._xyz[i]
            label.visible = bool(self._visible[i])

    def remove(self) -> None:
        """Take the axes and names out of the scene (drawn again by the next update)."""
        self._remove_axes()
        for label in self._labels.values():
            label.remove()
        self._labels = {}
        self.frames = ()
        self._dirty = True

    def set_show_axes(self, show: bool) -> None:
        self.show_axes = show
        self._send_axes()

    def set_marker_scale(self, scale: float) -> None:
        self.marker_scale = scale
        self._send_axes(recreate=True)

    def set_show_names(self, show: bool) -> None:
        self.show_names = show
        self._rebuild_labels(self.frames)
        if show:
            self._send_labels()
