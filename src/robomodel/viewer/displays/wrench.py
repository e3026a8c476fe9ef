"""RViz's Wrench display (wrench_display.cpp, rviz_rendering's WrenchVisual).

A geometry_msgs/WrenchStamped is drawn at its frame's origin, placed through TF at its stamp:
the force as an arrow, the torque as an arrow with 7/8 of a circle showing the sense of
rotation; an arrow not longer than "Arrow Width" is hidden. "History Length" keeps that many
wrenches. NaN values are refused ("Message contained invalid floating point values") unless
"Accept NaN Values", which draws them as 0.
"""

from __future__ import annotations

import collections
import math
from typing import Any

import numpy as np

from robomodel.viewer.displays._placed import place
from robomodel.viewer.displays.base import (
    Display,
    DisplayStatus,
    FrameLookup,
    Option,
    OptionKind,
    color_rgb,
    register_display,
)
from robomodel.viewer.displays.geometry import transform_points, wrench_shapes

__all__ = ["WrenchDisplay"]

_NAN = "Message contained invalid floating point values (nans or infs)"


@register_display
class WrenchDisplay(Display):
    """RViz's Wrench display with its options and defaults."""

    class_name = "Wrench"
    ros1_class_name = "WrenchStamped"  # rviz/WrenchStamped in RViz 1's plugin_description.xml
    message_types = ("geometry_msgs/msg/WrenchStamped",)
    options = (
        Option("Topic", "", OptionKind.TOPIC),
        Option("Queue Size", 5, OptionKind.INT, minimum=0, help="Incoming message queue"),
        Option("Accept NaN Values", False, OptionKind.BOOL),
        Option("Force Color", "204; 51; 51", OptionKind.COLOR),
        Option("Torque Color", "204; 204; 51", OptionKind.COLOR),
        Option("Alpha", 1.0, OptionKind.FLOAT, minimum=0.0, maximum=1.0),
        Option("Force Arrow Scale", 2.0, OptionKind.FLOAT, minimum=0.0),
        Option("Torque Arrow Scale", 2.0, OptionKind.FLOAT, minimum=0.0),
        Option("Arrow Width", 0.5, OptionKind.FLOAT, minimum=0.0),
        Option("History Length", 1, OptionKind.INT, minimum=1),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._pending: list[Any] = []
        self._visuals: collections.deque[str] = collections.deque()
        self._seq = 0
        self._problem = ""

    def on_message(self, msg: Any) -> None:
        self._pending.append(msg)

    def on_option_changed(self, name: str) -> None:
        self.reset()

    def reset(self) -> None:
        super().reset()
        self._visuals.clear()

    def draw(self, lookup: FrameLookup) -> DisplayStatus:
        pending, self._pending = self._pending, []
        for msg in pending:
            self._problem = self._take(msg, lookup)
        if self._problem:
            return DisplayStatus.error(self._problem)
        return self.topic_status() or DisplayStatus.ok(f"{self.messages_received} messages received")  # fmt: skip

    def _take(self, msg: Any, lookup: FrameLookup) -> str:
        w = msg.wrench
        values = [w.force.x, w.force.y, w.force.z, w.torque.x, w.torque.y, w.torque.z]
        if not all(math.isfinite(v) for v in values):
            if not self.values["Accept NaN Values"]:
                return _NAN
            values = [0.0 if math.isnan(v) else v for v in values]
        placement = place(lookup, msg.header)
        if placement.T_fixed_frame is None:
            return placement.reason
        self._seq += 1
        key = f"wrench{self._seq}"
        self._draw(key, np.array(values), placement.T_fixed_frame)
        self._visuals.append(key)
        while len(self._visuals) > int(self.values["History Length"]):
            old = self._visuals.popleft()
            for part in ("force", "torque", "circle"):
                self.remove_node(f"{old}_{part}")
        return ""

    def _draw(self, key: str, values: np.ndarray, T: np.ndarray) -> None:
        v = self.values
        shapes = wrench_shapes(tuple(values[:3]), tuple(values[3:]), force_scale=float(v["Force Arrow Scale"]),
                               torque_scale=float(v["Torque Arrow Scale"]), width=float(v["Arrow Width"]))  # fmt: skip
        arrow = {"shaft_radius": shapes.shaft_radius_m, "head_radius": shapes.head_radius_m}
        if shapes.force is not None:
            self.add_node(f"{key}_force", "arrows", points=transform_points(T, shapes.force)[None],
                          colors=color_rgb(v["Force Color"]), head_length=shapes.force_head_m, **arrow)  # fmt: skip
        if shapes.torque is not None and shapes.torque_circle is not None:
            torque_rgb = color_rgb(v["Torque Color"])
            self.add_node(f"{key}_torque", "arrows", points=transform_points(T, shapes.torque)[None],
                          colors=torque_rgb, head_length=shapes.torque_head_m, **arrow)  # fmt: skip
            ring = transform_points(T, shapes.torque_circle)
            self.add_node(f"{key}_circle", "line_segments", points=np.stack([ring[:-1], ring[1:]], axis=1),
                          colors=torque_rgb, thickness=max(shapes.shaft_radius_m, 0.005))  # fmt: skip
