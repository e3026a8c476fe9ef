"""RViz's RobotModel display: which of the viewer's robots are drawn, and how.

The viewer loads its robots itself (the files on its command line, a launch's descriptions, or
a description topic) and runs their robot_state_publishers; a RobotModel display draws the
robots its description names, as RViz's draws the robot of its Description Topic (RViz 2,
``rviz_default_plugins/RobotModel``) or of its Robot Description parameter (RViz 1,
``rviz/RobotModel``: the option is written under that key; robot_state_publisher publishes the
parameter's text on the topic of the same name, so one name serves both). A topic no robot of
the viewer's is described on is followed for the display (:mod:`robomodel.viewer.topic_robots`).
A robot no enabled RobotModel display names is not drawn, as in RViz; when several name it,
the last one's options count (later displays draw over earlier ones). Description Source
``File`` names a description file instead: one the viewer loaded, or another that is then
loaded for the display (:mod:`robomodel.viewer.topic_robots`).

Options and defaults are RViz 2's (robot_model_display.cpp): Alpha, Visual Enabled, Collision
Enabled, TF Prefix, Update Interval, Description Source / File / Topic. Link ``L`` is placed
at TF frame ``<TF Prefix>/L`` (see ``RobotSession.frame_prefix``), at most once per Update
Interval (:class:`LinkUpdates`).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from types import MappingProxyType
from typing import Any

from robomodel.viewer.displays.base import (
    Display,
    DisplayStatus,
    FrameLookup,
    Option,
    OptionKind,
    register_display,
)

__all__ = ["LinkUpdates", "RobotModelDisplay", "show_robots", "topic_name"]


def topic_name(name: str) -> str:
    """A description topic or parameter name as a global name (relative names resolve in the
    root namespace, where the viewer's node is)."""
    return "/" + name.strip().strip("/")


@register_display
class RobotModelDisplay(Display):
    """RViz's RobotModel display with its options and defaults."""

    class_name = "RobotModel"
    options = (
        Option("Alpha", 1.0, OptionKind.FLOAT, minimum=0.0, maximum=1.0,
               help="Amount of transparency to apply to the links."),
        Option("Collision Enabled", False, OptionKind.BOOL,
               help="Whether to display the collision representation of the robot."),
        Option("Description File", "", OptionKind.TEXT, help="Path to the robot description."),
        Option("Description Source", "Topic", OptionKind.CHOICE, choices=("Topic", "File")),
        Option("Description Topic", "/robot_description", OptionKind.TOPIC,
               help="Topic (RViz 1: parameter) holding the robot description"),
        Option("TF Prefix", "", OptionKind.TEXT,
               help="Robot Model normally assumes the link name is the same as the tf frame name. "
               "This option allows you to set a prefix."),
        Option("Update Interval", 0.0, OptionKind.FLOAT, minimum=0.0,
               help="Interval at which to update the links, in seconds. 0 means to update every "
               "update cycle."),
        Option("Visual Enabled", True, OptionKind.BOOL,
               help="Whether to display the visual representation of the robot."),
    )  # fmt: skip
    ros1_keys = MappingProxyType({"Description Topic": "Robot Description"})
    ros2_only = frozenset({"Description File", "Description Source"})

    def describes(self, session: Any) -> bool:
        """Whether this display names ``session``'s robot (its topic or its file)."""
        if self.option("Description Source") == "File":
            path, theirs = str(self.option("Description File")), str(session.source.path)
            if not path.strip() or not theirs:  # a robot from a topic has no file
                return False
            try:
                return os.path.samefile(path, theirs)
            except OSError:  # a file missing (yet): the same name, so its error is shown here
                return os.path.abspath(path) == os.path.abspath(theirs)
        return topic_name(str(self.option("Description Topic"))) in session.description_names

    def _robots(self) -> Sequence[Any]:
        robots = self.context.robots
        return tuple(robots()) if robots is not None else ()

    def draw(self, lookup: FrameLookup) -> DisplayStatus:
        sessions = self._robots()
        mine = [s for s in sessions if self.describes(s)]
        if not mine:
            return DisplayStatus.warn(self._nothing_text(sessions))
        failed = [s for s in mine if s.failure is not None]
        if failed:
            return DisplayStatus.error(f"URDF: {failed[0].failure.message}")
        if any(s.robot is None for s in mine):
            return DisplayStatus.warn(f"Waiting for the robot description on {self._source()}")
        for session in mine:
            frame = _unplaced_frame(session)
            if frame is not None:  # rviz_default_plugins robot/tf_link_updater.cpp's status
                fixed = self.context.fixed_frame()
                return DisplayStatus.error(f"No transform from [{frame}] to [{fixed}]")
        return DisplayStatus.ok(f"Showing {', '.join(s.label for s in mine)}")

    def _source(self) -> str:
        if self.option("Description Source") == "File":
            return f"file [{self.option('Description File')}]"
        return f"[{topic_name(str(self.option('Description Topic')))}]"

    def _nothing_text(self, sessions: Sequence[Any]) -> str:
        have = ", ".join(sorted({s.description_topic for s in sessions})) or "none"
        return (
            f"No robot described on {self._source()}; the viewer's robots are described on {have}"
        )


def _unplaced_frame(session: Any) -> str | None:
    """The first link frame of ``session`` that TF could not place at its last placement: its
    root when TF lacks it, else the first link missing below it. (A tree TF has that is not
    connected to the fixed frame is drawn beside it, named in the viewer's status.)"""
    poses = session.last_poses
    if poses is None:
        return None
    if not poses.root_in_tf:
        return str(session.root_frame)
    return str(poses.missing[0]) if poses.missing else None


class LinkUpdates:
    """When a robot's links are placed again, as RViz's RobotModel updates them
    (robot_model_display.cpp, ``update``): every update cycle at an Update Interval of 0
    (below 0.0001 s), else once the interval has passed since the last placement, and at once
    for a new fixed frame or a new drawing (RViz's ``has_new_transforms_``).

    Attributes:
        interval_s: The Update Interval [s] of the display that draws the robot.
        placements: How many times the links were placed.
    """

    def __init__(self) -> None:
        self.interval_s = 0.0
        self.placements = 0
        self._last_s: float | None = None
        self._fixed_frame: str | None = None

    def due(self, now_s: float, fixed_frame: str) -> bool:
        """Whether to place the links at ``now_s`` (a monotonic clock [s])."""
        if self.interval_s < 0.0001 or self._last_s is None or fixed_frame != self._fixed_frame:
            return True
        return now_s - self._last_s >= self.interval_s

    def next_s(self) -> float:
        """When the links are next due [s] (after a placement)."""
        return (self._last_s or 0.0) + self.interval_s

    def placed(self, now_s: float, fixed_frame: str) -> None:
        self._last_s, self._fixed_frame = now_s, fixed_frame
        self.placements += 1

    def reset(self) -> None:
        """Place the links at the next update (a new drawing of the robot)."""
        self._last_s = None


def show_robots(displays: Sequence[Display], sessions: Sequence[Any]) -> None:
    """Draw each robot as the last enabled RobotModel display that names it says (Alpha,
    Visual and Collision Enabled, TF Prefix, Update Interval), and hide the robots none names
    (loop thread)."""
    models = [d for d in displays if isinstance(d, RobotModelDisplay) and d.enabled]
    for session in sessions:
        owner = next((d for d in reversed(models) if d.describes(session)), None)
        session.tf_prefix = str(owner.option("TF Prefix")) if owner is not None else None
        session.link_updates.interval_s = (
            float(owner.option("Update Interval")) if owner is not None else 0.0
        )
        drawing = session.display
        if drawing is None:
            continue
        if drawing.shown != (owner is not None):
            drawing.set_shown(owner is not None)
        if owner is None:
            continue
        alpha = float(owner.option("Alpha"))
        if drawing.alpha != alpha:
            drawing.set_alpha(alpha)
        if drawing.show_visual != owner.option("Visual Enabled"):
            drawing.set_visual_enabled(bool(owner.option("Visual Enabled")))
        if drawing.show_collision != owner.option("Collision Enabled"):
            drawing.set_collision_enabled(bool(owner.option("Collision Enabled")))
