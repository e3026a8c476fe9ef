"""RViz's Pose, PoseWithCovariance and PoseArray displays.

Each draws the newest message's pose(s), placed through TF at the message's stamp in the
fixed frame (pose_display.cpp, pose_with_covariance_display.cpp, pose_array_display.cpp);
the scene is only re-sent when the placement or the message changed.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from robomodel.viewer.displays._placed import place
from robomodel.viewer.displays._pose_shapes import (
    ARROW_OPTIONS,
    COVARIANCE_OPTIONS,
    draw_covariance,
    draw_poses,
)
from robomodel.viewer.displays.base import (
    Display,
    DisplayStatus,
    FrameLookup,
    Option,
    OptionKind,
    register_display,
)
from robomodel.viewer.displays.geometry import poses_from_msgs

__all__ = ["PoseArrayDisplay", "PoseDisplay", "PoseWithCovarianceDisplay"]

_TOPIC = Option("Topic", "", OptionKind.TOPIC)
_ARRAY_SHAPES = ("Arrow (Flat)", "Arrow (3D)", "Axes")
_QUEUE = Option("Queue Size", 5, OptionKind.INT, minimum=0, help="Incoming message queue")


class _LatestPoseDisplay(Display):
    """The newest message, drawn once per change of message or placement."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.msg: Any = None
        self._drawn: tuple[int, bytes] | None = None

    def on_message(self, msg: Any) -> None:
        self.msg = msg

    def on_option_changed(self, name: str) -> None:
        if name == "Topic":
            self.msg, self.messages_received = None, 0
        self.remove_nodes()
        self._drawn = None

    def reset(self) -> None:
        super().reset()
        self._drawn = None

    def on_renamed(self) -> None:
        self._drawn = None

    def draw(self, lookup: FrameLookup) -> DisplayStatus:
        msg = self.msg
        waiting = self.topic_status()
        if msg is None:
            return waiting or DisplayStatus.ok()
        placement = place(lookup, msg.header)
        if placement.T_fixed_frame is None:
            self.remove_nodes()
            self._drawn = None
            return DisplayStatus.error(placement.reason)
        key = (id(msg), placement.T_fixed_frame.tobytes())
        if key != self._drawn:
            self._drawn = key
            self.draw_message(msg, placement.T_fixed_frame)
        return DisplayStatus.ok(f"{self.messages_received} messages received")

    def draw_message(self, msg: Any, T_fixed_frame: np.ndarray) -> None:
        """Draw ``msg`` whose frame is at ``T_fixed_frame``."""
        raise NotImplementedError


@register_display
class PoseDisplay(_LatestPoseDisplay):
    """RViz's Pose display (geometry_msgs/PoseStamped) as an arrow or axes."""

    class_name = "Pose"
    message_types = ("geometry_msgs/msg/PoseStamped",)
    options = (_TOPIC, _QUEUE, *ARROW_OPTIONS)

    def draw_message(self, msg: Any, T_fixed_frame: np.ndarray) -> None:
        Ts = T_fixed_frame @ poses_from_msgs([msg.pose])
        draw_poses(self, "pose", Ts, self.values)


@register_display
class PoseWithCovarianceDisplay(_LatestPoseDisplay):
    """RViz's PoseWithCovariance display (geometry_msgs/PoseWithCovarianceStamped): the
    pose, its position covariance's ellipsoid and its orientation covariance's discs."""

    class_name = "PoseWithCovariance"
    message_types = ("geometry_msgs/msg/PoseWithCovarianceStamped",)
    options = (_TOPIC, _QUEUE, *ARROW_OPTIONS, *COVARIANCE_OPTIONS)

    def draw_message(self, msg: Any, T_fixed_frame: np.ndarray) -> None:
        T_frame_pose = poses_from_msgs([msg.pose.pose])[0]
        draw_poses(self, "pose", (T_fixed_frame @ T_frame_pose)[None], self.values)
        draw_covariance(self, "covariance", T_fixed_frame, T_frame_pose, msg.pose.covariance, self.values)  # fmt: skip


@register_display
class PoseArrayDisplay(_LatestPoseDisplay):
    """RViz's PoseArray display: flat arrows (default), 3D arrows or axes."""

    class_name = "PoseArray"
    message_types = ("geometry_msgs/msg/PoseArray",)
    options = (
        _TOPIC,
        _QUEUE,
        Option("Shape", "Arrow (Flat)", OptionKind.CHOICE, choices=_ARRAY_SHAPES),
        Option("Color", "255; 25; 0", OptionKind.COLOR, help="Color to draw the arrows."),
        Option("Alpha", 1.0, OptionKind.FLOAT, minimum=0.0, maximum=1.0),
        Option("Arrow Length", 0.3, OptionKind.FLOAT, minimum=0.0),
        Option("Head Radius", 0.03, OptionKind.FLOAT, minimum=0.0),
        Option("Head Length", 0.07, OptionKind.FLOAT, minimum=0.0),
        Option("Shaft Radius", 0.01, OptionKind.FLOAT, minimum=0.0),
        Option("Shaft Length", 0.23, OptionKind.FLOAT, minimum=0.0),
        Option("Axes Length", 0.3, OptionKind.FLOAT, minimum=0.0),
        Option("Axes Radius", 0.01, OptionKind.FLOAT, minimum=0.0),
    )

    def draw_message(self, msg: Any, T_fixed_frame: np.ndarray) -> None:
        Ts = T_fixed_frame @ poses_from_msgs(list(msg.poses))
        draw_poses(self, "poses", Ts, self.values)
