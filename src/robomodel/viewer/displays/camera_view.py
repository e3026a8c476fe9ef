"""The Camera display's "View through the camera": the page's 3D view from the camera frame.

RViz's Camera display (rviz_default_plugins ``camera_display.cpp``, ``updateCamera``) puts its
render window's camera at the image frame's pose at the image's stamp ("convert vision
(Z-forward) frame to ogre frame (Z-out)": a 180 degree turn about x, as Ogre looks down -z),
gives it the projection of the CameraInfo's P scaled by "Zoom Factor", and draws the image as
a screen rectangle in ``RENDER_QUEUE_BACKGROUND`` (behind all geometry) and, with the
"Overlay Alpha" blending, ``RENDER_QUEUE_OVERLAY - 1`` (over it): "Image Rendering"
background, overlay, or background and overlay. viser's page camera already uses the optical
convention (+z forward, +y down, OpenCV), so the camera frame's pose is its pose unturned, and
the two rectangles become image quads in the scene filling the camera's view: one far behind
what the camera sees, one just in front of the camera.

What differs from RViz: the page keeps its own aspect ratio, so the CameraInfo's vertical
field of view is the page's, and the image fills the page's height, centred (RViz shrinks the
zoom to fit the whole image in its window, and offsets for the principal point); geometry more
than :data:`BACKGROUND_DEPTH_M` away is hidden behind the background quad, geometry nearer
than :data:`OVERLAY_DEPTH_M` is drawn over the overlay; the view is that of every page
connected, not of a panel of its own.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel.viewer._poses import wxyz_xyz_from_matrix

__all__ = ["BACKGROUND_DEPTH_M", "OVERLAY_DEPTH_M", "CameraView", "PageCameras", "camera_view"]

BACKGROUND_DEPTH_M = 500.0  # far behind the scene; within viser's far plane (1000 m)
OVERLAY_DEPTH_M = 0.05  # just beyond viser's near plane (0.01 m)
_LOOK_DISTANCE_M = 1.0  # where the orbit controls' look_at goes, ahead of the camera


@dataclass(frozen=True, slots=True)
class CameraView:
    """The page camera that looks through a camera frame, in the fixed frame.

    Attributes:
        position: The camera frame's origin [m].
        wxyz: The camera frame's orientation (optical: +z forward, +y down), viser's camera's.
        fov_rad: The vertical field of view [rad] (the CameraInfo's, over Zoom Factor).
        look_at: A point ahead on the optical axis [m] (viser's orbit target).
        size_per_m: ``(width, height)`` [m] the image covers at 1 m ahead.
    """

    position: tuple[float, float, float]
    wxyz: tuple[float, float, float, float]
    fov_rad: float
    look_at: tuple[float, float, float]
    size_per_m: tuple[float, float]


def _focal_lengths(info: Any) -> tuple[float, float]:
    """``(fx, fy)`` [px] from the CameraInfo's P, or K when P is zero (as RViz reads P)."""
    p = [float(v) for v in info.p]
    if any(p):
        return p[0], p[5]
    k = [float(v) for v in info.k]
    return (k[0], k[4]) if len(k) > 4 else (0.0, 0.0)


def camera_view(T_fixed_camera: NDArray[np.float64], info: Any, zoom: float = 1.0) -> CameraView | None:  # fmt: skip
    """The page camera for a camera frame at ``T_fixed_camera`` with CameraInfo ``info``
    (None if its width, height or focal lengths are unusable)."""
    width, height = int(info.width), int(info.height)
    fx, fy = _focal_lengths(info)
    if width <= 0 or height <= 0 or not (fx > 0 and fy > 0 and math.isfinite(fx * fy)):
        return None
    zoom = max(float(zoom), 1e-6)
    size = (width / (fx * zoom), height / (fy * zoom))
    T = np.asarray(T_fixed_camera, dtype=float)
    wxyz, xyz = wxyz_xyz_from_matrix(T)
    ahead = T[:3, 3] + _LOOK_DISTANCE_M * T[:3, 2]  # the optical axis is +z
    return CameraView(
        position=xyz,
        wxyz=wxyz,
        fov_rad=2.0 * math.atan(size[1] / 2.0),
        look_at=(float(ahead[0]), float(ahead[1]), float(ahead[2])),
        size_per_m=size,
    )


@dataclass(frozen=True, slots=True)
class _SavedCamera:
    """A page camera as the user left it (restored when the view-through stops)."""

    position: NDArray[np.float64]
    look_at: NDArray[np.float64]
    up_direction: NDArray[np.float64]
    fov_rad: float


def _reported(camera: Any) -> bool:
    """Whether the page has reported its camera (viser asserts on reading it before)."""
    try:
        return float(camera.update_timestamp) > 0.0
    except AssertionError:
        return False


def _shows(camera: Any, view: CameraView) -> bool:
    """Whether a page camera already shows ``view`` (within what the page echoes back)."""
    same_turn = abs(float(np.dot(camera.wxyz, view.wxyz))) > 1.0 - 1e-6
    return bool(same_turn and np.allclose(camera.position, view.position, atol=1e-4)
                and abs(camera.fov - view.fov_rad) < 1e-4)  # fmt: skip


class PageCameras:
    """The connected pages' cameras while they look through a camera frame.

    :meth:`follow` is called on each of the display's updates (10 Hz): a page camera that does
    not show the view (the camera frame moved, or the user dragged it) is set to it, so the
    view stays locked to the camera frame; to look around, the user turns the view-through
    off, and :meth:`release` puts each page's camera back where the user had it.

    Args:
        clients: Returns the connected viser clients.
    """

    def __init__(self, clients: Callable[[], Sequence[Any]]) -> None:
        self._clients = clients
        self._saved: dict[int, _SavedCamera] = {}  # client id -> its camera before

    @property
    def following(self) -> bool:
        return bool(self._saved)

    def follow(self, view: CameraView) -> None:
        for client in self._clients():
            camera = client.camera
            if not _reported(camera):
                continue
            if client.client_id not in self._saved:
                self._saved[client.client_id] = _SavedCamera(
                    np.array(camera.position), np.array(camera.look_at),
                    np.array(camera.up_direction), float(camera.fov),
                )  # fmt: skip
            if not _shows(camera, view):
                camera.position = view.position  # first: viser's setter carries look_at along
                camera.wxyz = view.wxyz
                camera.fov = view.fov_rad

    def release(self) -> None:
        saved, self._saved = self._saved, {}
        for client in self._clients():
            before = saved.get(client.client_id)
            if before is None:
                continue
            camera = client.camera
            camera.up_direction = before.up_direction
            camera.position = before.position
            camera.look_at = before.look_at
            camera.fov = before.fov_rad
