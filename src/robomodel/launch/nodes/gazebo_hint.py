"""The hint for a launch that starts Gazebo but spawns nothing (seed 003's ``gazebo.launch.py``).

Gazebo starts an empty world and says nothing; a student then wonders where the robot is.
robomodel's simulator runs the same empty world, and once it has run a little while
(:data:`HINT_AFTER_S` of wall time, time for a spawn from another terminal) with no entity in
it, it prints one line: that no entity was spawned, which launch file starts the world, and
the line that spawns one in that launch's language: gazebo_ros's ``spawn_entity.py`` for ROS 2
(seed 003's other Gazebo launch files), ``spawn_model`` for ROS 1 (seed 001's
``ur_gazebo.launch``). A launch that has a spawner gets no hint: the spawner reports its own
failures.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

__all__ = ["HINT_AFTER_S", "spawn_hint"]

HINT_AFTER_S = 3.0  # [s of wall time] with no entity before the hint
_SPAWNERS = {
    ("ros1", "gazebo_ros", "spawn_model"),
    ("ros2", "gazebo_ros", "spawn_entity.py"),
    ("ros2", "ros_gz_sim", "create"),
}
_SHARE = Path(__file__).resolve().parent.parent / "share"
_ROBOT_NAME = re.compile(r"<robot\b[^>]*?\bname\s*=\s*[\"']([^\"']+)[\"']")


def _launch_file(nodes: tuple[Any, ...]) -> str | None:
    """The user's launch file: the first node's file that is not robomodel's own gazebo_ros
    (whose ``gazebo.launch.py`` / ``empty_world.launch`` the user's file includes)."""
    for spec in nodes:
        path = getattr(spec.location, "path", None)
        if path and not Path(path).resolve().is_relative_to(_SHARE):
            return str(path)
    return None


def _robot_name(ctx: Any) -> str | None:
    """The robot's name in the launch's robot_description, for the example line."""
    text: str | None = None
    try:
        if ctx.spec.dialect == "ros2":
            from robomodel.launch.nodes.ros2_nodes import robot_description_of

            text = robot_description_of(ctx, {})
        else:
            key = ctx.search("robot_description")
            text = str(ctx.params.get(key)) if key else None
    except Exception:  # only a name for the example: any failure leaves the placeholder
        return None
    match = _ROBOT_NAME.search(text or "")
    return match.group(1) if match else None


def spawn_hint(ctx: Any) -> str | None:
    """The hint line for the simulator node of ``ctx``'s launch, or None when the launch
    has a spawner (see the module docstring)."""
    nodes = ctx.shared.nodes
    if any((s.dialect, s.package, s.executable) in _SPAWNERS for s in nodes):
        return None
    where = ctx.shared.launch_file or _launch_file(nodes) or "this launch"
    name = _robot_name(ctx) or "my_robot"
    if ctx.spec.dialect == "ros2":
        how = (
            "Node(package='gazebo_ros', executable='spawn_entity.py', "
            f"arguments=['-topic', 'robot_description', '-entity', '{name}']) (its "
            "robot_state_publisher publishes robot_description)"
        )
    else:
        how = (
            '<node name="spawn_gazebo_model" pkg="gazebo_ros" type="spawn_model" '
            f'args="-urdf -param robot_description -model {name}"/>'
        )
    return (
        f"hint: no entity was spawned: {where} starts Gazebo but spawns no robot, so the world "
        f"stays empty (as in Gazebo); add to it: {how}"
    )
