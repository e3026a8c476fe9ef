"""``robomodel sim``'s robots: read and added to the simulation, then their controllers,
robot_state_publisher, odometry and scripted ``--cmd-vel`` attached to the bus."""

from __future__ import annotations

import argparse
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from robomodel.errors import RobomodelError

if TYPE_CHECKING:
    from robomodel.control.config import ControllerConfig
    from robomodel.control.system import ControlSystem
    from robomodel.description.model import Robot
    from robomodel.description.packages import PackageIndex
    from robomodel.runtime import Context
    from robomodel.sim import BuiltRobot, Simulation
    from robomodel.sim.scripted import OdomWatcher

__all__ = ["AddedRobot", "RobotRequest", "add_robots", "attach", "prefixed_controllers"]


@dataclass(frozen=True, slots=True)
class RobotRequest:
    """One robot of the command line: its file, frame prefix, spawn pose and controllers.

    Attributes:
        path: The URDF or xacro file.
        prefix: The frame prefix (``r1_``), empty for none.
        xyz_m: Spawn position in the world [m].
        rpy_rad: Spawn orientation, fixed-axis roll, pitch, yaw [rad].
        controllers: The controller file, if any.
        namespace: The namespace of the robot's nodes (``/`` for one robot).
    """

    path: str
    prefix: str
    xyz_m: tuple[float, float, float]
    rpy_rad: tuple[float, float, float]
    controllers: str | None
    namespace: str = "/"


@dataclass(frozen=True, slots=True)
class AddedRobot:
    """A requested robot as read and as added to the simulation."""

    request: RobotRequest
    robot: Robot
    built: BuiltRobot


def prefixed_controllers(path: str, prefix: str) -> ControllerConfig:
    """The controller file for a robot with frame prefix ``prefix``.

    A diff drive names its odometry frames itself (``odom_frame_id``, ``base_frame_id``); with a
    prefix they become ``<prefix>odom`` and ``<prefix>base_link``, so that they meet the
    simulator's ``world -> <prefix>odom`` and robot_state_publisher's ``<prefix><link>`` in one
    tree. A file that sets ``tf_frame_prefix`` or ``tf_frame_prefix_enable`` itself is kept.
    """
    import dataclasses

    from robomodel.control.config import load_controller_config

    config = load_controller_config(path)
    if not prefix:
        return config
    specs = []
    for spec in config.controllers:
        params = dict(spec.params)
        own = {"tf_frame_prefix", "tf_frame_prefix_enable"} & params.keys()
        if spec.type.endswith("DiffDriveController") and not own:
            params["tf_frame_prefix_enable"] = False
            for key, default in (("odom_frame_id", "odom"), ("base_frame_id", "base_link")):
                params[key] = prefix + str(params.get(key, default))
            spec = dataclasses.replace(spec, params=params)
        specs.append(spec)
    return dataclasses.replace(config, controllers=tuple(specs))


def _cmd_vel(text: str) -> tuple[float, float, float]:
    try:
        values = [float(v) for v in text.replace(",", " ").split()]
    except ValueError:
        values = []
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise RobomodelError(f'--cmd-vel takes "VX VY WZ" (3 numbers), got {text!r}')
    return values[0], values[1], values[2]


def add_robots(
    sim: Simulation,
    requests: Sequence[RobotRequest],
    mappings: Mapping[str, str],
    index: PackageIndex,
) -> list[AddedRobot]:
    """Each requested robot read (with the xacro arguments ``mappings``) and added, in order."""
    from robomodel.loading import read_description
    from robomodel.sim import Placement

    robots = []
    for request in requests:
        result, loaded = read_description(request.path, args=mappings, package_index=index)
        placement = Placement(request.prefix, request.xyz_m, request.rpy_rad)
        built = sim.add_robot(result.robot, placement=placement, base_dir=loaded.base_dir)
        robots.append(AddedRobot(request, result.robot, built))
    return robots


def attach(
    args: argparse.Namespace, sim: Simulation, robots: Sequence[AddedRobot], context: Context
) -> tuple[list[ControlSystem | None], list[OdomWatcher | None]]:
    """Each robot's controllers (its controller manager), robot_state_publisher, odometry
    watcher and scripted cmd_vel: the control systems and the watchers, in robot order."""
    from robomodel.description.urdf.writer import urdf_to_string
    from robomodel.runtime.nodes.robot_state_publisher import RobotStatePublisher
    from robomodel.sim.scripted import CmdVelDriver, OdomWatcher, diff_drive_controller

    cmd = _cmd_vel(args.cmd_vel) if args.cmd_vel else None
    several = len(robots) > 1
    systems: list[ControlSystem | None] = []
    watchers: list[OdomWatcher | None] = []
    for added in robots:
        request = added.request
        system = None
        namespace = request.namespace
        if request.controllers:
            system = sim.control(
                prefixed_controllers(request.controllers, request.prefix),
                prefix=request.prefix,
                context=context,
                namespace=namespace if several else None,  # one robot: the file's own
            )
            namespace = system.manager.namespace
        systems.append(system)
        RobotStatePublisher(
            context,
            urdf_to_string(added.robot),
            namespace=namespace,
            parameters={"frame_prefix": request.prefix},  # ROS 2 multi-robot: P<link>
        )
        watchers.append(OdomWatcher.attach(system, context) if system is not None else None)
        if cmd is not None and (not several or diff_drive_controller(system) is not None):
            CmdVelDriver.attach(sim, system, context, cmd, topic=args.cmd_vel_topic)
            if args.cmd_vel_topic:  # one publisher for the one topic given
                cmd = None
    return systems, watchers
