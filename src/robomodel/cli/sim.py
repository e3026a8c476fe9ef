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
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from robomodel.cli._bus import add_bus_arguments, context_from_args
from robomodel.cli._common import (
    add_frame_rate_argument,
    add_package_options,
    package_index_from_args,
    split_inputs,
)
from robomodel.cli._ports import add_port_argument
from robomodel.cli._sim_robots import AddedRobot, RobotRequest, add_robots, attach
from robomodel.cli._verbs import verb_help
from robomodel.errors import RobomodelError

if TYPE_CHECKING:
    from robomodel.control.system import ControlSystem
    from robomodel.runtime import Context
    from robomodel.sim import Simulation
    from robomodel.sim.bus import SimBridge
    from robomodel.sim.scripted import OdomWatcher
    from robomodel.sim.world import World

__all__ = ["parse_rate", "register"]


def register(subparsers: Any) -> None:
    p = subparsers.add_parser("sim", help=verb_help("sim"))
    p.add_argument(
        "inputs",
        nargs="+",
        metavar="FILE|name:=value",
        help=".urdf or .xacro files (one robot each) and xacro arguments name:=value (for every "
        "file)",
    )
    add_package_options(p, mappings=False)
    p.add_argument("--world", metavar="W.world", help="SDF world file (default: ground + sun)")
    p.add_argument(
        "--controllers",
        action="append",
        default=[],
        metavar="C.yaml",
        help="controller YAML (ROS 2 or ROS 1): one for every robot, or one per FILE in order",
    )
    p.add_argument(
        "--spawn",
        nargs="+",
        type=float,
        action="append",
        default=[],
        metavar="V",
        help="spawn pose x y z R P Y [m, rad] (as spawn_entity -x -y -z -R -P -Y; missing = 0); "
        "one per FILE, in order",
    )
    p.add_argument(
        "--prefix",
        action="append",
        default=[],
        metavar="P",
        help="frame prefix of each FILE, in order (its bodies, robot_state_publisher's "
        "frame_prefix, the viewer; verbatim, e.g. r1_); required with several robots",
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
        help="publish this constant Twist [m/s, rad/s] to the diff-drive controller (of every "
        "robot that has one) at 10 Hz",
    )
    p.add_argument("--cmd-vel-topic", default=None, help="topic for --cmd-vel (default: found)")
    p.add_argument("--report", choices=("json",), help="print a JSON summary at the end")
    add_port_argument(p, "the viewer's HTTP port")
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


def _namespace(prefix: str, number: int) -> str:
    """ROS 2 multi-robot: a robot's nodes in a namespace named after its prefix (``r1_`` ->
    ``/r1``), ``/robot<N>`` when the prefix makes no valid name (``1_``)."""
    cleaned = "".join(c if c.isalnum() else "_" for c in prefix).strip("_")
    return "/" + cleaned if cleaned and cleaned[0].isalpha() else f"/robot{number + 1}"


def robot_requests(args: argparse.Namespace) -> tuple[list[RobotRequest], dict[str, str]]:
    """The robots named on the command line and the xacro arguments shared by all of them.

    One robot: ``--prefix``, ``--spawn`` and ``--controllers`` as before. Several robots (as
    several ``spawn_entity`` calls): one ``--prefix`` each (distinct), one ``--spawn`` each (two
    robots at one pose would start inside each other) and one ``--controllers`` for all or one
    each.
    """
    files, mappings = split_inputs(args.inputs, "sim")
    n = len(files)
    prefixes, spawns, configs = list(args.prefix), list(args.spawn), list(args.controllers)
    for option, given in (("--prefix", prefixes), ("--spawn", spawns)):
        if len(given) > n:
            raise RobomodelError(
                f"{len(given)} {option} options for {n} robot(s); give one per FILE"
            )
    if n > 1:
        if len(prefixes) != n or len(set(prefixes)) != n:
            raise RobomodelError(
                f"{n} robots need {n} distinct --prefix options (frame prefixes, e.g. "
                "--prefix r1_ --prefix r2_), one per FILE in order"
            )
        if len(spawns) != n:
            raise RobomodelError(
                f"{n} robots need {n} --spawn poses, one per FILE in order (at one pose they "
                "would start inside each other)"
            )
    if len(configs) not in (0, 1, n):
        raise RobomodelError(
            f"{len(configs)} --controllers files for {n} robot(s): give one for all or one per FILE"
        )
    prefixes += [""] * (n - len(prefixes))
    spawns += [[]] * (n - len(spawns))
    configs = configs * n if len(configs) == 1 else configs or [None] * n
    requests = []
    for k, (path, prefix, spawn, config) in enumerate(
        zip(files, prefixes, spawns, configs, strict=True)
    ):
        xyz, rpy = _spawn(spawn)
        namespace = _namespace(prefix, k) if n > 1 else "/"
        requests.append(RobotRequest(path, prefix, xyz, rpy, config, namespace))
    return requests, mappings


def _run(args: argparse.Namespace) -> int:
    from robomodel.runtime import ManualClock
    from robomodel.sim import Simulation, default_world, read_world
    from robomodel.sim.bus import SimBridge

    world = read_world(args.world) if args.world else default_world()
    factor = parse_rate(args.rate, world.real_time_factor)
    requests, mappings = robot_requests(args)
    index = package_index_from_args(args)
    for request in requests:  # every robot's workspace, as colcon's install space would
        index = index.with_workspace_of(request.path)
    sim = Simulation(world, package_index=index)
    robots = add_robots(sim, requests, mappings, index)
    with context_from_args(args, clock=ManualClock(), announce="robomodel sim") as context:
        systems, watchers = attach(args, sim, robots, context)
        bridge = SimBridge(sim, context)
        bridge.paused = args.paused
        viewer = None if args.headless else _sim_viewer(args, world, requests, mappings)
        _announce(args, sim, world, robots, systems, context)
        wall_s = 0.0
        try:
            with contextlib.suppress(KeyboardInterrupt):
                wall_s = _loop(sim, bridge, args.duration, factor)
        finally:
            for system in systems:
                if system is not None:
                    system.manager.shutdown()
            bridge.close()
            if viewer is not None:
                viewer.close()
        if args.report == "json":
            reports = [
                {
                    "prefix": added.request.prefix,
                    **_report(sim, added.built.root_body, odom, wall_s),
                }
                for added, odom in zip(robots, watchers, strict=True)
            ]
            first = {k: v for k, v in reports[0].items() if k != "prefix"}
            print(json.dumps({**first, "robots": reports} if len(robots) > 1 else first))
    return 0


def _sim_viewer(
    args: argparse.Namespace,
    world: World,
    requests: Sequence[RobotRequest],
    mappings: dict[str, str],
) -> Any:
    """The viewer of a simulation: RViz's Fixed Frame "world", the world's objects drawn."""
    from robomodel.cli.control import _start_viewer

    try:
        from robomodel.sim.scenery import scenery_of

        scenery = scenery_of(world)
    except ImportError:  # no viewer extra: _start_viewer says so
        scenery = ()
    return _start_viewer(
        args,
        fixed_frame="world",
        scenery=scenery,
        sources=[(r.path, mappings, r.prefix) for r in requests],
    )


def _announce(
    args: argparse.Namespace,
    sim: Simulation,
    world: World,
    robots: Sequence[AddedRobot],
    systems: Sequence[ControlSystem | None],
    context: Context,
) -> None:
    several = len(robots) > 1
    names = ", ".join(
        f"'{added.robot.name}'" + (f" ({added.request.prefix})" if added.request.prefix else "")
        for added in robots
    )
    controllers = [
        c["name"] for system in systems if system for c in system.manager.list_controllers()
    ]
    print(
        f"robomodel sim: world '{world.name}' at {sim.timestep_s * 1e3:g} ms steps, "
        f"robot{'s' if several else ''} {names}"
        + (f", controllers: {', '.join(controllers)}" if controllers else "")
        + f"; rate {args.rate}; bus {context.transport.name}"
        + ("" if args.duration else "; Ctrl-C stops"),
        file=sys.stderr,
    )


def _loop(
    sim: Simulation, bridge: SimBridge, duration_s: float | None, factor: float | None
) -> float:
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


def _report(
    sim: Simulation, root_body: str, odom: OdomWatcher | None, wall_s: float
) -> dict[str, Any]:
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
    pose = odom.pose() if odom is not None else None
    if pose is not None:
        report["odom_xy"] = [pose[0], pose[1]]
        report["odom_yaw"] = pose[2]
    return report
