"""The TF display: axes for every frame (one batched node) and optional names.

As RViz's TF display: Show Axes, Show Names, Marker Scale; frames are drawn where they are in
the fixed frame, and frames with no transform to it are not drawn.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["TFDisplay"]

# RViz's TF axes are 0.1 m long at Marker Scale 1 (rviz_rendering::Axes(…, 0.1, 0.01)).
_AXES_LENGTH_M = 0.1
_AXES_RADIUS_M = 0.004


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
        self._axes: Any = None
        self._labels: dict[str, Any] = {}
        self._wxyz = np.zeros((0, 4))
        self._xyz = np.zeros((0, 3))
        self._visible = np.zeros(0, dtype=bool)
        self._dirty = True
        self._axes_count = 0

    def update(
        self,
        frames: tuple[str, ...],
        wxyz: NDArray[np.float64],
        xyz: NDArray[np.float64],
        visible: NDArray[np.bool_],
    ) -> None:
        """Draw ``frames`` at the given poses in the fixed frame; send only when changed."""
        if frames != self.frames:
            self._rebuild_labels(frames)
            self.frames = frames
            self._dirty = True
        changed = self._dirty or not (
            np.array_equal(visible, self._visible)
            and np.allclose(wxyz, self._wxyz, atol=1e-7)
            and np.allclose(xyz, self._xyz, atol=1e-6)
        )
        if not changed:
            return
        self._wxyz, self._xyz, self._visible = wxyz.copy(), xyz.copy(), visible.copy()
        self._dirty = False
        self._send_axes()
        if self.show_names:
            self._send_labels()

    def _send_axes(self, *, recreate: bool = False) -> None:
        shown = self._visible & self.show_axes
        count = int(shown.sum())
        if self._axes is not None and (recreate or count != self._axes_count):
            self._axes.remove()
            self._axes = None
        if count == 0:
            return
        if self._axes is None:
            self._axes = self.scene.add_batched_axes(
                f"{self.root}/axes",
                batched_wxyzs=self._wxyz[shown],
                batched_positions=self._xyz[shown],
                axes_length=_AXES_LENGTH_M * self.marker_scale,
                axes_radius=_AXES_RADIUS_M * self.marker_scale,
            )
            self._axes_count = count
        else:
            self._axes.batched_wxyzs = self._wxyz[shown]
            self._axes.batched_positions = self._xyz[shown]

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
        if self._axes is not None:
            self._axes.remove()
            self._axes = None
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
