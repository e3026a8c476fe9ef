"""``robomodel sim``: the seeds' Gazebo launch (world + spawn + gazebo_ros_control + RSP + RViz).

Physics on MuJoCo, the description's hardware on the simulator, the controllers of
``--controllers`` spawned, robot_state_publisher, sensors and ground truth on the bus, and the
browser viewer unless ``--headless``. Time on the bus is sim time (every node's clock follows
the physics, as ``use_sim_time`` with /clock). ``--cmd-vel`` and ``--report json`` make
scripted runs::

    robomodel sim simplebot.urdf.xacro --controllers ctrl.yaml --headless --duration 5 \\
        --rate max --cmd-vel "0.2 0 0" --report json
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import sys
import time
from typing import Any

from robomodel.cli._bus import add_bus_arguments
from robomodel.cli._common import (
    add_description_arguments,
    add_frame_rate_argument,
    load_from_args,
)
from robomodel.errors import RobomodelError

__all__ = ["parse_rate", "register", "scenery_of"]


def register(subparsers: Any) -> None:
    p = subparsers.add_parser(
        "sim", help="simulate a robot (Gazebo's role, on MuJoCo) with its controllers"
    )
    add_description_arguments(p)
    p.add_argument("--world", metavar="W.world", help="SDF world file (default: ground + sun)")
    p.add_argument("--controllers", metavar="C.yaml", help="controller YAML (ROS 2 or ROS 1)")
    p.add_argument(
        "--spawn",
        nargs="+",
        type=float,
        default=[],
        metavar="V",
        help="spawn pose x y z R P Y [m, rad] (as spawn_entity -x -y -z -R -P -Y; missing = 0)",
    )
    p.add_argument(
        "--prefix",
        default="",
        help="frame prefix of the robot (its bodies, robot_state_publisher's frame_prefix, the "
        "viewer; verbatim, e.g. r1_)",
    )
    p.add_argument(
        "--rate",
        default="realtime",
        help="realtime (the world's real_time_factor), max (as fast as possible) or a factor",
    )
    p.add_argument("--headless", action="store_true", help="no viewer")
    p.add_argument(
        "--no-browser", action="store_true", help="start the viewer but do not open a browser"
    )
    p.add_argument("--paused", action="store_true", help="start paused (gazebo -u)")
    p.add_argument("--duration", type=float, default=None, help="stop after S s of sim time")
    p.add_argument(
        "--cmd-vel",
        metavar='"VX VY WZ"',
        help="publish this constant Twist [m/s, rad/s] to the diff-drive controller at 10 Hz",
    )
    p.add_argument("--cmd-vel-topic", default=None, help="topic for --cmd-vel (default: found)")
    p.add_argument("--report", choices=("json",), help="print a JSON summary at the end")
    p.add_argument("--port", type=int, default=8080, help="the viewer's HTTP port (0: any)")
    add_frame_rate_argument(p)
    add_bus_arguments(p)
    p.set_defaults(func=_run)


def parse_rate(text: str, world_factor: float) -> float | None:
    """``realtime`` -> the world's factor, ``max`` -> None (unpaced), else a positive factor."""
    if text == "realtime":
        return world_factor
    if text == "max":
        return None
    try:
        factor = float(text)
    except ValueError:
        raise RobomodelError(f"--rate must be realtime, max or a number, got '{text}'") from None
    if not (factor > 0 and math.isfinite(factor)):
        raise RobomodelError(f"--rate factor must be positive, got {factor}")
    return factor


def _spawn(values: list[float]) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
    if len(values) > 6:
        raise RobomodelError(f"--spawn takes up to 6 numbers (x y z R P Y), got {len(values)}")
    v = [*values, *([0.0] * (6 - len(values)))]
    return (v[0], v[1], v[2]), (v[3], v[4], v[5])


def _cmd_vel(text: str) -> tuple[float, float, float]:
    try:
        values = [float(v) for v in text.replace(",", " ").split()]
    except ValueError:
        values = []
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise RobomodelError(f'--cmd-vel takes "VX VY WZ" (3 numbers), got {text!r}')
    return values[0], values[1], values[2]


def scenery_of(world: Any) -> tuple[Any, ...]:
    """The world's boxes, cylinders and spheres as the viewer's scenery.

    Static shapes are posed in ``world``; moving ones (mass > 0) in the TF frame the simulator
    publishes for them. Planes are left out: the viewer's grid is the ground.
    """
    from robomodel.sim.build.scene import shape_body_name
    from robomodel.sim.world import ShapeKind
    from robomodel.viewer.scenery import SceneryShape

    shapes = []
    for i, shape in enumerate(world.shapes):
        if shape.kind is ShapeKind.PLANE:
            continue
        name = shape_body_name(shape, i)
        moving = shape.mass_kg > 0
        x, y, z, roll, pitch, yaw = shape.pose
        shapes.append(
            SceneryShape(
                name=name,
                frame=name if moving else "world",
                kind=shape.kind.value,
                size_m=shape.size,
                xyz_m=(0.0, 0.0, 0.0) if moving else (x, y, z),
                rpy_rad=(0.0, 0.0, 0.0) if moving else (roll, pitch, yaw),
                rgba=shape.rgba,
            )
        )
    return tuple(shapes)


def _run(args: argparse.Namespace) -> int:
    from robomodel.cli.control import _start_viewer
    from robomodel.description.urdf.writer import urdf_to_string
    from robomodel.runtime import Context, ManualClock
    from robomodel.runtime.nodes.robot_state_publisher import RobotStatePublisher
    from robomodel.sim import Placement, Simulation, default_world, read_world
    from robomodel.sim.bus import SimBridge
    from robomodel.sim.scripted import CmdVelDriver, OdomWatcher

    world = read_world(args.world) if args.world else default_world()
    factor = parse_rate(args.rate, world.real_time_factor)
    xyz, rpy = _spawn(args.spawn)
    cmd = _cmd_vel(args.cmd_vel) if args.cmd_vel else None
    result, loaded, index = load_from_args(args)
    robot = result.robot
    sim = Simulation(world, package_index=index)
    built = sim.add_robot(
        robot, placement=Placement(args.prefix, xyz, rpy), base_dir=loaded.base_dir
    )
    with Context(args.bus, clock=ManualClock(), domain_id=args.domain_id, connect=args.connect, listen=args.listen) as context:  # fmt: skip
        system = None
        namespace = "/"
        if args.controllers:
            system = sim.control(args.controllers, prefix=args.prefix, context=context)
            namespace = system.manager.namespace
        bridge = SimBridge(sim, context)
        RobotStatePublisher(
            context,
            urdf_to_string(robot),
            namespace=namespace,
            parameters={"frame_prefix": args.prefix},  # ROS 2 multi-robot: frames P<link>
        )
        odom = OdomWatcher.attach(system, context) if system is not None else None
        if cmd is not None:
            CmdVelDriver.attach(sim, system, context, cmd, topic=args.cmd_vel_topic)
        bridge.paused = args.paused
        viewer = None
        if not args.headless:  # RViz's Fixed Frame "world", the world's objects drawn
            try:
                scenery = scenery_of(world)
            except ImportError:  # no viewer extra: _start_viewer says so
                scenery = ()
            viewer = _start_viewer(args, fixed_frame="world", scenery=scenery)
        print(
            f"robomodel sim: world '{world.name}' at {sim.timestep_s * 1e3:g} ms steps, "
            f"robot '{robot.name}'"
            + (f", controllers: {', '.join(c['name'] for c in system.manager.list_controllers())}" if system else "")
            + f"; rate {args.rate}; bus {context.transport.name}"
            + ("" if args.duration else "; Ctrl-C stops"),
            file=sys.stderr,
        )  # fmt: skip
        wall_s = 0.0
        try:
            with contextlib.suppress(KeyboardInterrupt):
                wall_s = _loop(sim, bridge, args.duration, factor)
        finally:
            if system is not None:
                system.manager.shutdown()
            bridge.close()
            if viewer is not None:
                viewer.close()
        if args.report == "json":
            print(json.dumps(_report(sim, built.root_body, odom, wall_s)))
    return 0


def _loop(sim: Any, bridge: Any, duration_s: float | None, factor: float | None) -> float:
    """Step until ``duration_s`` (or forever); returns the wall time spent running [s].

    Pacing is against the start of the run (re-anchored after a pause), so sleeping per chunk
    does not accumulate error.
    """
    chunk_s = 0.01
    wall = 0.0
    anchor: tuple[float, float] | None = None  # (wall, sim) when pacing started
    while duration_s is None or sim.time_s < duration_s - 1e-9:
        if bridge.paused:
            anchor = None
            bridge.poll()
            if bridge.pending_steps:  # /gazebo/step while paused
                steps, bridge.pending_steps = bridge.pending_steps, 0
                start = time.perf_counter()
                sim.step(steps)
                wall += time.perf_counter() - start
            else:
                time.sleep(0.02)
            continue
        start = time.perf_counter()
        if anchor is None:
            anchor = (start, sim.time_s)
        step_s = chunk_s if duration_s is None else min(chunk_s, duration_s - sim.time_s)
        sim.run(step_s)
        if factor is not None:
            delay = anchor[0] + (sim.time_s - anchor[1]) / factor - time.perf_counter()
            if delay > 0:
                time.sleep(delay)
        wall += time.perf_counter() - start
    return wall


def _report(sim: Any, root_body: str, odom: Any, wall_s: float) -> dict[str, Any]:
    from robomodel.sim.sensors.ground_truth import yaw_of

    body = sim.data.body(root_body)
    x, y = float(body.xpos[0]), float(body.xpos[1])
    report: dict[str, Any] = {
        "ground_truth_xy": [x, y],
        "ground_truth_yaw": yaw_of(body.xquat),
        "odom_xy": None,
        "odom_yaw": None,
        "sim_time_s": sim.time_s,
        "wall_time_s": wall_s,
        "real_time_factor": sim.time_s / wall_s if wall_s > 0 else None,
    }
    if odom is not None and odom.last is not None:
        pose = odom.last.pose.pose
        q = pose.orientation
        report["odom_xy"] = [pose.position.x, pose.position.y]
        report["odom_yaw"] = math.atan2(
            2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z)
        )
    return report
