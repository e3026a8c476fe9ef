"""RViz's Camera display, as far as a browser scene allows.

RViz's Camera display (camera_display.cpp) renders the scene from the camera's pose with the
image behind ("background") or over it ("overlay"). viser's page has one 3D view, so here the
image is shown in the display's panel, and in the 3D scene on the camera's frustum, placed
through TF at the image's stamp and shaped by its CameraInfo (``image_transport``'s
``<image topic's namespace>/camera_info``). The status says that the scene is not drawn over
the image. Options keep RViz's names and defaults for the config.
"""

from __future__ import annotations

import math
import posixpath
from typing import Any

from robomodel.viewer.displays._placed import combine, place, pose_kwargs
from robomodel.viewer.displays.base import (
    DisplayStatus,
    FrameLookup,
    Option,
    OptionKind,
    SubscriptionSpec,
    register_display,
)
from robomodel.viewer.displays.image_display import IMAGE_OPTIONS, ImageDisplay

__all__ = ["CameraDisplay", "camera_info_topic", "frustum_fov"]

_RENDERING = ("background", "overlay", "background and overlay")
NO_OVERLAY = (
    "the scene is not rendered over the image in the page: the image is in the panel and "
    "on the camera's frustum in the 3D view"
)


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
        self._show_frustum(shape, placement.T_fixed_frame)
        return DisplayStatus.warn(f"{status.text}; {NO_OVERLAY}")
