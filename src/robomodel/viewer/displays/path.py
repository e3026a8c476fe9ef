"""RViz's Path display (path_display.cpp): a line through the poses, placed through TF.

The path is drawn in its ``header.frame_id`` at the stamp (the poses' own headers are not
used, as in RViz), moved by "Offset", the last "Buffer Length" paths kept. "Lines" are drawn
2 pixels wide, "Billboards" "Line Width" metres wide; "Pose Style" adds axes or arrows at the
poses.
"""

from __future__ import annotations

import collections
from typing import Any

import numpy as np

from robomodel.viewer._poses import wxyz_from_matrices, wxyz_xyz_from_matrix
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
from robomodel.viewer.displays.geometry import arrow_segments, poses_from_msgs

__all__ = ["PathDisplay"]


@register_display
class PathDisplay(Display):
    """RViz's Path display with its options and defaults."""

    class_name = "Path"
    message_types = ("nav_msgs/msg/Path",)
    options = (
        Option("Topic", "", OptionKind.TOPIC),
        Option("Queue Size", 5, OptionKind.INT, minimum=0, help="Incoming message queue"),
        Option("Line Style", "Lines", OptionKind.CHOICE, choices=("Lines", "Billboards")),
        Option("Line Width", 0.03, OptionKind.FLOAT, minimum=0.001),
        Option("Color", "25; 255; 0", OptionKind.COLOR, help="Color to draw the path."),
        Option("Alpha", 1.0, OptionKind.FLOAT, minimum=0.0, maximum=1.0),
        Option("Buffer Length", 1, OptionKind.INT, minimum=1, help="Number of paths to display."),
        Option("Offset/X", 0.0, OptionKind.FLOAT),
        Option("Offset/Y", 0.0, OptionKind.FLOAT),
        Option("Offset/Z", 0.0, OptionKind.FLOAT),
        Option("Pose Style", "None", OptionKind.CHOICE, choices=("None", "Axes", "Arrows")),
        Option("Length", 0.3, OptionKind.FLOAT, minimum=0.0, help="Length of the axes."),
        Option("Radius", 0.03, OptionKind.FLOAT, minimum=0.0, help="Radius of the axes."),
        Option("Pose Color", "255; 85; 255", OptionKind.COLOR),
        Option("Shaft Length", 0.1, OptionKind.FLOAT, minimum=0.0),
        Option("Head Length", 0.2, OptionKind.FLOAT, minimum=0.0),
        Option("Shaft Diameter", 0.1, OptionKind.FLOAT, minimum=0.0),
        Option("Head Diameter", 0.3, OptionKind.FLOAT, minimum=0.0),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._pending: Any = None
        self._paths: collections.deque[str] = collections.deque()
        self._seq = 0
        self._problem = ""

    def on_message(self, msg: Any) -> None:
        self._pending = msg

    def on_option_changed(self, name: str) -> None:
        self.reset()

    def reset(self) -> None:
        super().reset()
        self._paths.clear()

    def draw(self, lookup: FrameLookup) -> DisplayStatus:
        msg, self._pending = self._pending, None
        if msg is not None:
            self._problem = self._take(msg, lookup)
        if self._problem:
            return DisplayStatus.error(self._problem)
        return self.topic_status() or DisplayStatus.ok(f"{self.messages_received} messages received")  # fmt: skip

    def _take(self, msg: Any, lookup: FrameLookup) -> str:
        Ts = poses_from_msgs([p.pose for p in msg.poses])  # PoseStamped: frames unused
        if not np.isfinite(Ts).all():
            return "Message contained invalid floating point values (nans or infs)"
        placement = place(lookup, msg.header)
        if placement.T_fixed_frame is None:
            return placement.reason
        T = placement.T_fixed_frame.copy()
        T[:3, 3] += [float(self.values[f"Offset/{a}"]) for a in "XYZ"]
        self._seq += 1
        key = f"path{self._seq}"
        self._draw_path(key, Ts, T)
        self._paths.append(key)
        while len(self._paths) > int(self.values["Buffer Length"]):
            old = self._paths.popleft()
            for suffix in ("", "_poses"):
                self.remove_node(old + suffix)
        return ""

    def _draw_path(self, key: str, Ts: np.ndarray, T_fixed_frame: np.ndarray) -> None:
        v = self.values
        wxyz, xyz = wxyz_xyz_from_matrix(T_fixed_frame)
        if Ts.shape[0] >= 2:
            points = Ts[:, :3, 3]
            billboards = v["Line Style"] == "Billboards"
            self.add_node(key, "line_segments", points=np.stack([points[:-1], points[1:]], axis=1),
                          colors=color_rgb(v["Color"]),
                          thickness=float(v["Line Width"]) if billboards else 2.0,
                          thickness_units="world" if billboards else "screen",
                          wxyz=wxyz, position=xyz)  # fmt: skip
        style = v["Pose Style"]
        if style == "Axes" and Ts.shape[0]:
            self.add_node(f"{key}_poses", "batched_axes", batched_wxyzs=wxyz_from_matrices(Ts[:, :3, :3]),
                          batched_positions=Ts[:, :3, 3], axes_length=float(v["Length"]),
                          axes_radius=float(v["Radius"]), wxyz=wxyz, position=xyz)  # fmt: skip
        elif style == "Arrows" and Ts.shape[0]:
            head = float(v["Head Length"])
            self.add_node(f"{key}_poses", "arrows", points=arrow_segments(Ts, float(v["Shaft Length"]) + head),
                          colors=color_rgb(v["Pose Color"]), shaft_radius=float(v["Shaft Diameter"]) / 2,
                          head_radius=float(v["Head Diameter"]) / 2, head_length=head,
                          wxyz=wxyz, position=xyz)  # fmt: skip
