"""RViz's Map display: a nav_msgs/OccupancyGrid as a textured plane (map_display.cpp).

The texture uses RViz's palettes (:mod:`.occupancy`); the plane is the map's origin pose in its
``header.frame_id``, placed through TF at the current time (RViz's "Use Timestamp" false) or
the map's stamp, and re-placed at every draw so that a moving map frame carries it along. The
map topic's Durability Policy starts as Transient Local so that a latched map (map_server) is
received; map_msgs/OccupancyGridUpdate ("Update Topic") is kept in the config only.
"""

from __future__ import annotations

from types import MappingProxyType
from typing import Any

import numpy as np

from robomodel.viewer.displays._placed import pose_kwargs
from robomodel.viewer.displays.base import (
    Display,
    DisplayStatus,
    FrameLookup,
    Option,
    OptionKind,
    register_display,
    stamp_ns,
)
from robomodel.viewer.displays.image import nearest_upscale
from robomodel.viewer.displays.occupancy import (
    COLOR_SCHEMES,
    GridError,
    grid_rgba,
    grid_texture_pose,
)

__all__ = ["MapDisplay"]


@register_display
class MapDisplay(Display):
    """RViz's Map display with its options and defaults."""

    class_name = "Map"
    message_types = ("nav_msgs/msg/OccupancyGrid",)
    options = (
        Option("Topic", "", OptionKind.TOPIC, help="nav_msgs/OccupancyGrid topic"),
        Option("Queue Size", 5, OptionKind.INT, minimum=0, help="Incoming message queue"),
        Option("Update Topic", "", OptionKind.TOPIC, help="map_msgs/OccupancyGridUpdate topic"),
        Option("Alpha", 0.7, OptionKind.FLOAT, minimum=0.0, maximum=1.0),
        Option("Color Scheme", "map", OptionKind.CHOICE, choices=COLOR_SCHEMES),
        Option("Draw Behind", False, OptionKind.BOOL),
        Option("Use Timestamp", False, OptionKind.BOOL),
        Option("Binary representation", False, OptionKind.BOOL),
        Option("Binary threshold", 100, OptionKind.INT, minimum=0, maximum=100),
    )
    # RViz 2's Map is Volatile, so a map_server map (latched) shows only once the user picks
    # Transient Local; robomodel starts with it, so that the map everyone publishes shows.
    topic_qos_defaults = MappingProxyType({"Durability Policy": "Transient Local"})

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.map: Any = None
        self._new = False
        self._error = ""
        self._placed: bytes = b""
        self._T_frame_centre = np.eye(4)
        self._texture_key: tuple[Any, ...] = ()

    def on_message(self, msg: Any) -> None:
        self.map, self._new = msg, True

    def on_option_changed(self, name: str) -> None:
        if name == "Topic":
            self.map, self.messages_received = None, 0
        self.remove_nodes()
        self._texture_key = ()
        self._new = self.map is not None

    def reset(self) -> None:
        super().reset()
        self.map = None

    def draw(self, lookup: FrameLookup) -> DisplayStatus:
        msg = self.map
        if msg is None:
            self._error = ""
            return self.topic_status() or DisplayStatus.warn("No map received")
        if self._new:
            self._new = False
            problem = self._texture(msg)
            if problem:
                return DisplayStatus.error(problem)
        if self._error:
            return DisplayStatus.error(self._error)
        return self._place(lookup, msg)

    def _texture(self, msg: Any) -> str:
        """Send the map's texture when its content changed (a map republished unchanged, as
        map_server's latched map often is, is not sent again); the error, if any."""
        v = self.values
        info, origin = msg.info, msg.info.origin
        key = (str(msg.header.frame_id), info.width, info.height, info.resolution,
               origin.position.x, origin.position.y, origin.position.z, origin.orientation.x,
               origin.orientation.y, origin.orientation.z, origin.orientation.w,
               bytes(np.asarray(msg.data, dtype=np.int8)),
               v["Color Scheme"], v["Binary representation"], v["Binary threshold"], v["Alpha"])  # fmt: skip
        if key == self._texture_key and self.node("map") is not None:
            return ""
        self._texture_key = key
        self._placed = b""
        try:
            rgba = grid_rgba(msg, color_scheme=str(v["Color Scheme"]),
                             binary=bool(v["Binary representation"]),
                             threshold=int(v["Binary threshold"]), alpha=float(v["Alpha"]))  # fmt: skip
        except GridError as exc:
            self._error = str(exc)
            self.remove_nodes()
            return self._error
        self._error = ""
        self._T_frame_centre, width_m, height_m = grid_texture_pose(msg)
        self.add_node("map", "image", image=nearest_upscale(rgba), render_width=width_m,
                      render_height=height_m, format="png", cast_shadow=False,
                      receive_shadow=False, visible=False)  # fmt: skip
        return ""

    def _place(self, lookup: FrameLookup, msg: Any) -> DisplayStatus:
        node = self.node("map")
        stamp = stamp_ns(msg.header.stamp) if self.values["Use Timestamp"] else 0
        placement = lookup(str(msg.header.frame_id), stamp)
        if placement.T_fixed_frame is None:
            node.visible = False
            self._placed = b""
            return DisplayStatus.error(placement.reason)
        T = placement.T_fixed_frame @ self._T_frame_centre
        if T.tobytes() != self._placed:
            self._placed = T.tobytes()
            kwargs = pose_kwargs(T)
            node.wxyz, node.position, node.visible = kwargs["wxyz"], kwargs["position"], True
        info = msg.info
        return DisplayStatus.ok(
            f"Map OK: {info.width} X {info.height} map @ {info.resolution:g} m/pix"
        )
