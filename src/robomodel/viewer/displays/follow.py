"""Displays the viewer adds for the graph's scans and odometry when no RViz config says what
to show (what its Overlays folder did before the displays existed).

``robomodel view``, ``sim`` and ``control run`` without a ``-d`` file (or with one that does
not exist yet) add, once each, a LaserScan display for the first ``sensor_msgs/LaserScan``
topic the graph shows, an Odometry display for the first ``nav_msgs/Odometry`` topic that is
not a simulator's ground truth, and a "Ground truth" Odometry display for the first one that
is (Gazebo's p3d, ``.../ground_truth/odom``), in orange beside the odometry's blue so that
odometry drift shows as two trails parting. A topic a display already shows is not added
again, and a display the user removes stays removed. A config the user opened (``-d``, Open
Config) is shown as RViz shows it: nothing is added.

The Odometry displays added here keep RViz's Shape (Arrow), Keep (100) and tolerances but not
its arrow size: RViz's 1.3 m arrows (shaft 1 m, head 0.3 m, head 0.2 m across), one per 0.1 m
driven, make a fan of cones that hides a small robot such as the course's simplebot. Their
arrows are RViz's shape scaled to half the smallest robot's size (its links' farthest frame
from its root with every joint at zero; 0.05 m to 1.3 m), so that the newest arrow, at the
robot's base, stays within the robot. A display the user adds has RViz's defaults.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

from robomodel.viewer.layout import zero_pose_extent_m

__all__ = ["FOLLOWED", "Followed", "GraphFollower", "trail_arrow_values"]

# RViz's Odometry arrow (odometry_display.cpp): shaft 1 x 0.05 m, head 0.3 x 0.1 m
_RVIZ_ARROW_M = {"Shaft Length": 1.0, "Shaft Radius": 0.05, "Head Length": 0.3, "Head Radius": 0.1}
_RVIZ_ARROW_LENGTH_M = 1.3
_NO_ROBOT_EXTENT_M = 0.5  # no robot loaded yet


def trail_arrow_values(robot_extents_m: Sequence[float]) -> dict[str, float]:
    """The "Shape/..." sizes of an added Odometry display: RViz's arrow scaled to half the
    smallest of ``robot_extents_m`` (see the module docstring), never larger than RViz's."""
    extent = min(robot_extents_m, default=_NO_ROBOT_EXTENT_M)
    length_m = min(_RVIZ_ARROW_LENGTH_M, max(0.05, 0.5 * extent))
    scale = length_m / _RVIZ_ARROW_LENGTH_M
    return {f"Shape/{name}": size * scale for name, size in _RVIZ_ARROW_M.items()}


def _is_ground_truth(topic: str) -> bool:
    return "ground_truth" in topic


@dataclass(frozen=True, slots=True)
class Followed:
    """One display added for the first topic of ``type_name`` that ``accepts`` takes."""

    name: str
    class_name: str
    type_name: str
    accepts: Callable[[str], bool]
    values: Mapping[str, Any] = field(default_factory=lambda: MappingProxyType({}))


# The trails only, as the viewer's overlays drew them: a diff drive's YAML gives 1e6 variances
# for the axes it does not measure (the course's simplebot), whose covariance shapes, one per
# kept arrow, span a kilometre and fill the page (under software WebGL the page stopped
# answering). The user switches Covariance on in the display's options, as in RViz.
_TRAIL_ONLY = {"Covariance/Value": False}
FOLLOWED = (
    Followed("LaserScan", "LaserScan", "sensor_msgs/msg/LaserScan", lambda _topic: True),
    Followed("Odometry", "Odometry", "nav_msgs/msg/Odometry",
             lambda topic: not _is_ground_truth(topic),
             MappingProxyType({"Shape/Color": "40; 200; 255", **_TRAIL_ONLY})),
    Followed("Ground truth", "Odometry", "nav_msgs/msg/Odometry", _is_ground_truth,
             MappingProxyType({"Shape/Color": "255; 150; 0", **_TRAIL_ONLY})),
)  # fmt: skip


class GraphFollower:
    """Adds :data:`FOLLOWED` displays to a Displays panel as their topics appear (called on
    the loop thread after each of the manager's updates).

    Args:
        panel: The :class:`~robomodel.viewer.displays.panel.DisplaysPanel` (its ``topics``
            are the graph's, refreshed by its own thread; ``add`` adds a display and its row).
        followed: What to follow.
    """

    def __init__(self, panel: Any, followed: tuple[Followed, ...] = FOLLOWED) -> None:
        self.panel = panel
        self.waiting = list(followed)
        self.added: dict[str, Any] = {}  # name -> the display added

    def _robot_extents_m(self) -> list[float]:
        robots = self.panel.manager.context.robots
        sessions = robots() if robots is not None else ()
        return [zero_pose_extent_m(s.robot) for s in sessions if s.robot is not None]

    def stop(self) -> None:
        """Add nothing more (a config was opened)."""
        self.waiting.clear()

    def __call__(self) -> None:
        if not self.waiting:
            return
        topics: Mapping[str, frozenset[str]] = self.panel.topics
        for followed in list(self.waiting):
            found = sorted(t for t, types in topics.items()
                           if followed.type_name in types and followed.accepts(t))  # fmt: skip
            if not found:
                continue
            self.waiting.remove(followed)
            if any(d.topic in found for d in self.panel.manager.displays):
                continue  # already shown (by the user or another rule)
            values = {"Topic": found[0], **followed.values}
            if followed.class_name == "Odometry":
                values.update(trail_arrow_values(self._robot_extents_m()))
            display = self.panel.add(followed.class_name, name=followed.name, values=values)
            if display is not None:
                self.added[followed.name] = display
