"""RViz's Odometry display (odometry_display.cpp): a trail of arrows, "Keep" N.

Each message's pose is placed through TF at its stamp when it arrives and stays there; a pose
within both "Position Tolerance" and "Angle Tolerance" of the last kept one is skipped; the
oldest arrows go beyond "Keep" (0: all). The shape options sit below "Shape" and the
covariance's below "Covariance", as RViz 2 saves them.

What is kept is bounded however long the robot drives: Keep arrows (and their covariance
shapes), one scene node for all the arrows, and at most :data:`~robomodel.viewer.limits.MAX_ODOMETRY_PENDING` messages between
two draws (the newest; a simulation faster than real time publishes more).
"""

from __future__ import annotations

import collections
from typing import Any

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
from robomodel.viewer.displays.geometry import ArrowTrail, poses_from_msgs
from robomodel.viewer.limits import MAX_ODOMETRY_PENDING

__all__ = ["OdometryDisplay"]


def _nested(option: Option) -> Option:
    """``Shape`` -> ``Shape/Value``, ``Color`` -> ``Shape/Color``: RViz 2's Odometry saves
    ``Shape: {Value: Arrow, Color: ..., ...}``."""
    name = "Shape/Value" if option.name == "Shape" else f"Shape/{option.name}"
    return Option(name, option.default, option.kind, option.choices,
                  option.minimum, option.maximum, option.help)  # fmt: skip


@register_display
class OdometryDisplay(Display):
    """RViz's Odometry display with its options and defaults."""

    class_name = "Odometry"
    message_types = ("nav_msgs/msg/Odometry",)
    options = (
        Option("Topic", "", OptionKind.TOPIC),
        Option("Queue Size", 5, OptionKind.INT, minimum=0, help="Incoming message queue"),
        Option("Position Tolerance", 0.1, OptionKind.FLOAT, minimum=0.0),
        Option("Angle Tolerance", 0.1, OptionKind.FLOAT, minimum=0.0),
        Option("Keep", 100, OptionKind.INT, minimum=0, help="0 means keep all of them"),
        *(_nested(o) for o in ARROW_OPTIONS),
        *COVARIANCE_OPTIONS,
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.trail = self._new_trail()
        self._pending: collections.deque[Any] = collections.deque(maxlen=MAX_ODOMETRY_PENDING)
        self._covariances: collections.deque[str] = collections.deque()
        self._seq = 0
        self._problem = ""

    def _new_trail(self) -> ArrowTrail:
        v = self.values
        return ArrowTrail(float(v["Position Tolerance"]), float(v["Angle Tolerance"]), int(v["Keep"]))  # fmt: skip

    def on_message(self, msg: Any) -> None:
        self._pending.append(msg)

    def on_option_changed(self, name: str) -> None:
        if name in ("Position Tolerance", "Angle Tolerance", "Keep"):
            self.trail.position_tolerance_m = float(self.values["Position Tolerance"])
            self.trail.angle_tolerance_rad = float(self.values["Angle Tolerance"])
            self.trail.keep = int(self.values["Keep"])
            self.trail.trim()
            self._trim_covariances()
            self._draw_arrows()
            return
        self.reset()  # RViz: shape and colour changes apply to new arrows; start afresh

    def reset(self) -> None:
        super().reset()
        self.trail = self._new_trail()
        self._covariances.clear()

    def _shape_values(self) -> dict[str, Any]:
        values = {k.removeprefix("Shape/"): v for k, v in self.values.items()}
        values["Shape"] = values["Value"]
        return values

    def draw(self, lookup: FrameLookup) -> DisplayStatus:
        pending, self._pending = self._pending, collections.deque(maxlen=MAX_ODOMETRY_PENDING)
        changed = False
        for msg in pending:
            changed |= self._take(msg, lookup)
        if changed:
            self._draw_arrows()
        if self._problem:
            return DisplayStatus.error(self._problem)
        waiting = self.topic_status()
        return waiting or DisplayStatus.ok(f"{len(self.trail.poses)} arrows kept")

    def _take(self, msg: Any, lookup: FrameLookup) -> bool:
        placement = place(lookup, msg.header)
        if placement.T_fixed_frame is None:
            self._problem = placement.reason  # RViz drops such a message
            return False
        self._problem = ""
        pose = msg.pose.pose
        xyz = (pose.position.x, pose.position.y, pose.position.z)
        o = pose.orientation
        T_frame_pose = poses_from_msgs([pose])[0]
        if not self.trail.offer(xyz, (o.x, o.y, o.z, o.w), placement.T_fixed_frame @ T_frame_pose):
            return False
        self._seq += 1
        key = f"covariance{self._seq}"
        draw_covariance(self, key, placement.T_fixed_frame, T_frame_pose, msg.pose.covariance, self.values)  # fmt: skip
        self._covariances.append(key)
        self._trim_covariances()
        return True

    def _trim_covariances(self) -> None:
        while len(self._covariances) > len(self.trail.poses):
            key = self._covariances.popleft()
            for node_key in (key, *(f"{key}_orientation{i}" for i in range(3))):
                self.remove_node(node_key)

    def _draw_arrows(self) -> None:
        draw_poses(self, "arrows", self.trail.matrices(), self._shape_values())
