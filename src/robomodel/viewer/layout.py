"""Where things go on the page: each robot's namespace, unconnected robots, the initial camera."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from robomodel.description.model import Robot
from robomodel.viewer.scenery import SceneryShape
from robomodel.viewer.session import RobotSession, RobotSource

__all__ = ["beside_root_pose", "place_camera", "session_namespace", "zero_pose_extent_m"]


def zero_pose_extent_m(robot: Robot) -> float:
    """Largest distance of a link frame from the root with every joint at zero [m]."""
    tree = robot.tree()
    positions = {tree.root: np.eye(4)}
    extent = 0.0
    for _depth, joint in tree.walk():
        T = positions.get(joint.parent, np.eye(4)) @ joint.origin.matrix()
        positions[joint.child] = T
        extent = max(extent, float(np.linalg.norm(T[:3, 3])))
    return extent


def session_namespace(source: RobotSource, number: int, count: int) -> str:
    """The bus namespace of robot ``number`` of ``count``: ``/`` when alone, else its prefix
    made a valid name (``robot<n>`` when it has none); a launch file's robot keeps its nodes'."""
    if source.namespace is not None:
        return source.namespace
    if count == 1:
        return "/"
    cleaned = "".join(c if c.isalnum() or c == "_" else "_" for c in source.prefix.strip("/"))
    if not cleaned or not cleaned[0].isalpha():
        cleaned = f"robot{number + 1}" if not cleaned else f"r{cleaned}"
    return "/" + cleaned


def beside_root_pose(
    session: RobotSession,
    sessions: Sequence[RobotSession],
    fixed_frame: str,
    extents_m: Mapping[int, float],
) -> np.ndarray:
    """Where an unconnected robot goes: side by side along -y (to the left in the default
    view, away from the panel), ordered as given.

    Args:
        session: The robot to place.
        sessions: Every robot; the one whose root is ``fixed_frame`` stays at the origin.
        fixed_frame: The viewer's Fixed Frame.
        extents_m: Robot number -> its extent [m] once known; spacing is the largest.
    """
    anchor = next((s.number for s in sessions if s.root_frame == fixed_frame), 0)
    spacing = max([1.0, *(2.0 * e + 0.5 for e in extents_m.values())])
    T = np.eye(4)
    T[1, 3] = -(session.number - anchor) * spacing
    return T


def place_camera(
    server: Any, robot: Robot | None, robot_count: int, scenery: Sequence[SceneryShape]
) -> None:
    """Set ``server``'s initial camera to RViz's orbit view (yaw 5.5, pitch 0.33 rad), far
    enough to see ``robot`` (the first one loaded) and, in a world, its nearest objects."""
    extent = zero_pose_extent_m(robot) if robot is not None else 0.5
    distance = max(1.0, 3.0 * extent + 0.5) * max(1.0, robot_count**0.5)
    near = [float(np.linalg.norm(s.xyz_m)) for s in scenery if s.frame == "world"]
    yaw, pitch = 5.5, 0.33
    if near:  # a simulated world: from behind the spawn pose, its nearest objects in view
        distance = max(distance, min(1.5 * min(near), 12.0))
        yaw, pitch = 3.7, 0.5
    camera = server.initial_camera
    camera.look_at = (0.0, 0.0, 0.0)
    camera.position = (
        distance * math.cos(pitch) * math.cos(yaw),
        distance * math.cos(pitch) * math.sin(yaw),
        distance * math.sin(pitch),
    )
