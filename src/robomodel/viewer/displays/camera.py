"""RViz's Camera display, as far as a browser scene allows.

RViz's Camera display (camera_display.cpp) renders the scene from the camera's pose with the
image behind ("background") or over it ("overlay"). viser's page has one 3D view, so here the
image is shown in the display's panel, and in the 3D scene on the camera's frustum, placed
through TF at the image's stamp and shaped by its CameraInfo (``image_transport``'s
``<image topic's namespace>/camera_info``); the status says that the scene is not drawn over
the image. The panel's "View through the camera" (robomodel's own control, not an RViz option:
not written to configs) turns the page's 3D view into RViz's Camera view: the page camera
follows the camera frame, and the image is drawn behind and/or over the scene as "Image
Rendering" says, at "Overlay Alpha" (:mod:`~robomodel.viewer.displays.camera_view`, which
says what differs from RViz); the frustum is hidden meanwhile, and turning the control off
gives each page its camera back. Options keep RViz's names and defaults for the config.
"""

from __future__ import annotations

import math
import posixpath
from typing import Any

import numpy as np

from robomodel.viewer.displays._placed import combine, place, pose_kwargs
from robomodel.viewer.displays.base import (
    DisplayStatus,
    FrameLookup,
    Option,
    OptionKind,
    SubscriptionSpec,
    register_display,
)
from robomodel.viewer.displays.camera_view import (
    BACKGROUND_DEPTH_M,
    OVERLAY_DEPTH_M,
    CameraView,
    PageCameras,
    camera_view,
)
from robomodel.viewer.displays.image_display import IMAGE_OPTIONS, ImageDisplay

__all__ = ["VIEW_THROUGH", "CameraDisplay", "camera_info_topic", "frustum_fov"]

_RENDERING = ("background", "overlay", "background and overlay")
NO_OVERLAY = (
    "the scene is not rendered over the image in the page: the image is in the panel and "
    "on the camera's frustum in the 3D view"
)
VIEW_THROUGH = "View through the camera"
VIEWING = "the 3D view looks through the camera"


def context_clients(context: Any) -> Any:
    """The context's connected pages (none for a context without pages)."""
    return context.clients if context.clients is not None else tuple


def camera_info_topic(image_topic: str) -> str:
    """image_transport::getCameraInfoTopic: ``camera_info`` beside the image topic (beside
    the base topic for a transport's ``.../image_raw/compressed``)."""
    base = image_topic.rstrip("/")
    for transport in ("/compressed", "/compressedDepth", "/theora"):
        base = base.removesuffix(transport)
    return posixpath.join(posixpath.dirname(base) or "/", "camera_info")


def frustum_fov(info: Any, zoom: float = 1.0) -> tuple[float, float] | None:
    """``(vertical fov [rad], aspect)`` from a CameraInfo's P (or K), None if unusable."""
    width, height = int(info.width), int(info.height)
    p = list(info.p) if any(info.p) else []
    k = list(info.k)
    fy = p[5] if p else (k[4] if len(k) > 4 else 0.0)
    if width <= 0 or height <= 0 or not fy or not math.isfinite(fy):
        return None
    return 2.0 * math.atan(height / (2.0 * fy * max(zoom, 1e-6))), width / height


@register_display
class CameraDisplay(ImageDisplay):
    """RViz's Camera display: the image, its CameraInfo and where the camera is."""

    class_name = "Camera"
    message_types = ("sensor_msgs/msg/Image", "sensor_msgs/msg/CompressedImage")
    options = (
        Option("Topic", "", OptionKind.TOPIC, help="sensor_msgs/Image topic"),
        Option("Queue Size", 5, OptionKind.INT, minimum=0, help="Incoming message queue"),
        Option("Image Rendering", "background and overlay", OptionKind.CHOICE, choices=_RENDERING),
        Option("Overlay Alpha", 0.5, OptionKind.FLOAT, minimum=0.0, maximum=1.0),
        Option("Zoom Factor", 1.0, OptionKind.FLOAT, minimum=0.0001),
        Option("Far Plane Distance", 100.0, OptionKind.FLOAT, minimum=0.0),
        Option("Visibility", {}, OptionKind.MAP, help="Other displays in the camera view"),
        *IMAGE_OPTIONS,
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.camera_info: Any = None
        self._frustum_key: tuple[float, float] | None = None
        self._frustum_image = -1
        self._frustum_pose: tuple[Any, ...] = ()
        self.viewing = False  # "View through the camera"
        self._view_checkbox: Any = None
        self._pages = PageCameras(context_clients(self.context))
        self._quads: dict[str, tuple[int, tuple[float, float]]] = {}  # key -> (image, size)

    def subscriptions(self) -> tuple[SubscriptionSpec, ...]:
        image = super().subscriptions()
        if not image:
            return ()
        info = SubscriptionSpec(
            camera_info_topic(self.topic),
            "sensor_msgs/msg/CameraInfo",
            self._on_camera_info,
            depth=1,
            key="camera_info",
        )
        return (*image, info)

    def _on_camera_info(self, msg: Any) -> None:
        self.camera_info = msg

    def on_option_changed(self, name: str) -> None:
        super().on_option_changed(name)
        if name == "Topic":
            self.camera_info = None
        self._frustum_key = None
        self._remove_quads()  # redrawn with the new rendering, alpha or zoom

    def build_panel(self, gui: Any) -> None:
        super().build_panel(gui)
        self._view_checkbox = gui.add_checkbox(
            VIEW_THROUGH, self.viewing,
            hint="The 3D view from the camera, the image behind and/or over the scene "
            "(Image Rendering); dragging the view is undone until this is off",
        )  # fmt: skip
        box = self._view_checkbox
        box.on_update(lambda _e: self.context.post(lambda: self.set_view_through(bool(box.value))))  # fmt: skip

    def set_view_through(self, on: bool) -> None:
        """Look through the camera (the next draw moves the pages' cameras), or stop and give
        the pages their cameras back (loop thread)."""
        self.viewing = on
        if self._view_checkbox is not None and bool(self._view_checkbox.value) != on:
            self._view_checkbox.value = on
        if not on:
            self._stop_view()

    def _stop_view(self) -> None:
        self._pages.release()
        self._remove_quads()

    def _remove_quads(self) -> None:
        for key in list(self._quads):
            self.remove_node(key)
        self._quads.clear()

    def on_enabled_changed(self) -> None:
        super().on_enabled_changed()
        if not self.enabled:
            self._stop_view()

    def close(self) -> None:
        self._stop_view()
        super().close()

    def _quad(self, key: str, rgb: Any, depth_m: float, alpha: float | None, view: CameraView) -> None:  # fmt: skip
        """The image as a quad filling the view ``depth_m`` ahead (RGBA at ``alpha``, else
        opaque), updated in place as the frustum is."""
        size = (view.size_per_m[0] * depth_m, view.size_per_m[1] * depth_m)
        image = rgb
        if alpha is not None:  # viser draws images with blending: the PNG's alpha is used
            image = np.dstack([image, np.full(image.shape[:2], round(255 * alpha), np.uint8)])
        node, (shown, old_size) = self.node(key), self._quads.get(key, (-1, (0.0, 0.0)))
        if node is None or not np.allclose(old_size, size):
            node = self.add_node(key, "image", image=image, render_width=size[0],
                                 render_height=size[1], format="png" if alpha is not None else "jpeg",
                                 cast_shadow=False, receive_shadow=False)  # fmt: skip
        elif shown != self.shown and not np.array_equal(node.image, image):
            node.image = image  # an unchanged image is not sent again (the page reloads it)
        self._quads[key] = (self.shown, size)
        axis = np.subtract(view.look_at, view.position)  # look_at is on the optical axis
        position = np.asarray(view.position) + depth_m * axis / np.linalg.norm(axis)
        pose = (view.wxyz, tuple(float(v) for v in position))
        if (tuple(node.wxyz), tuple(node.position)) != pose:  # unmoved: nothing sent
            node.wxyz, node.position = pose

    def _show_view(self, rgb: Any, T_fixed_camera: Any) -> DisplayStatus:
        view = camera_view(T_fixed_camera, self.camera_info, float(self.values["Zoom Factor"]))
        if view is None:
            return DisplayStatus.error("CameraInfo/P has no usable focal length")
        self.remove_node("frustum")  # it would cover the view it is seen from
        self._frustum_key = None
        rendering = str(self.values["Image Rendering"])
        wanted = {"background": rendering != "overlay", "overlay": rendering != "background"}
        for key, depth, alpha in (("background", BACKGROUND_DEPTH_M, None),
                                  ("overlay", OVERLAY_DEPTH_M, float(self.values["Overlay Alpha"]))):  # fmt: skip
            if wanted[key]:
                self._quad(key, rgb, depth, alpha, view)
            elif key in self._quads:
                self.remove_node(key)
                del self._quads[key]
        self._pages.follow(view)
        return DisplayStatus.ok()

    def _show_frustum(self, shape: tuple[float, float], T_fixed_camera: Any) -> None:
        """The frustum with the newest image; updated in place (a re-added node would flicker
        and, re-added faster than the page decodes its image, never show it)."""
        node = self.node("frustum")
        if node is None or self._frustum_key != shape:
            self._frustum_key, self._frustum_pose = shape, ()
            node = self.add_node("frustum", "camera_frustum", fov=shape[0], aspect=shape[1],
                                 scale=0.3, image=self.rgb, format="jpeg")  # fmt: skip
            self._frustum_image = self.shown
        elif self._frustum_image != self.shown:
            node.image = self.rgb
            self._frustum_image = self.shown
        pose = pose_kwargs(T_fixed_camera)
        if (pose["wxyz"], pose["position"]) != self._frustum_pose:
            self._frustum_pose = (pose["wxyz"], pose["position"])
            node.wxyz, node.position = pose["wxyz"], pose["position"]

    def draw(self, lookup: FrameLookup) -> DisplayStatus:
        status = super().draw(lookup)
        if status.level.value == "error" or self.rgb is None or self.header is None:
            return status
        if self.camera_info is None:
            return DisplayStatus.warn(
                f"No CameraInfo received on [{camera_info_topic(self.topic)}]. Topic may not exist."
            )
        shape = frustum_fov(self.camera_info, float(self.values["Zoom Factor"]))
        if shape is None:
            return DisplayStatus.error(
                "Could not determine width/height of image due to malformed CameraInfo "
                "(either width or height is 0)"
            )
        placement = place(lookup, self.header)
        if placement.T_fixed_frame is None:
            self.remove_node("frustum")
            self._frustum_pose = ()
            return combine(None, [placement.reason], "")
        if self.viewing:
            viewed = self._show_view(self.rgb, placement.T_fixed_frame)
            return viewed if viewed.level.value == "error" else DisplayStatus.ok(f"{status.text}; {VIEWING}")  # fmt: skip
        self._stop_view()
        self._show_frustum(shape, placement.T_fixed_frame)
        return DisplayStatus.warn(f"{status.text}; {NO_OVERLAY}")
