"""gazebo_ros nodes of a ROS 1 launch file: ``gzserver`` (robomodel's simulator), ``gzclient``
(the browser viewer) and ``spawn_model``.

``gzserver [-u] [-e engine] [--verbose] [-r] WORLD`` runs a :class:`~robomodel.sim.server.SimServer`
in the launch process, driven by the launch's loop (physics, controllers and bus callbacks in
one thread), with a controller manager per spawned robot that has the ``gazebo_ros_control``
plugin, in its ``robotNamespace`` (or the spawner's namespace, as gazebo_ros sets it).
Controller parameters come from the ROS 1 parameter server (``<namespace>/<controller>``), as
the plugin's controller_manager reads them. ``spawn_model`` (gazebo_ros 2.9's script, every
option) reads the description from ``-param`` or ``-file`` and calls
``/gazebo/spawn_urdf_model`` from its own thread, as the script does from its process.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from robomodel._files import UserFileError, read_user_text
from robomodel.errors import RobomodelError
from robomodel.launch.nodes.base import NodeContext, RunningNode, ThreadNode, register

__all__ = [
    "SpawnArgs",
    "parse_server_args",
    "parse_spawn_args",
    "resolve_world",
    "start_sim_server",
    "world_viewer",
]

_SHARE = Path(__file__).resolve().parent.parent / "share" / "gazebo_ros"


def resolve_world(name: str, *, cwd: str | None = None) -> str | None:
    """The world file gzserver would open: a path, or a name relative to
    ``GAZEBO_RESOURCE_PATH`` (plus robomodel's ``worlds/empty.world``); None for the default."""
    if not name:
        return None
    path = Path(name) if os.path.isabs(name) else Path(cwd or os.getcwd()) / name
    if path.is_file():
        return str(path)
    roots = [r for r in os.environ.get("GAZEBO_RESOURCE_PATH", "").split(":") if r]
    for root in (*roots, str(_SHARE)):
        candidate = Path(root) / name
        if candidate.is_file():
            return str(candidate)
    raise RobomodelError(
        f"gzserver: cannot find world '{name}' (not a file, and not under GAZEBO_RESOURCE_PATH "
        f"or robomodel's gazebo_ros worlds: {', '.join(_bundled_worlds())}); give the path of "
        "an SDF world"
    )


def _bundled_worlds() -> list[str]:
    return sorted(f"worlds/{p.name}" for p in (_SHARE / "worlds").glob("*.world"))


def parse_server_args(words: list[str]) -> tuple[bool, str]:
    """``(paused, world)`` from gzserver's (ROS 1 and 2) or ``gz sim``'s arguments."""
    paused, world, skip = False, "", False
    for word in words:
        if skip:
            skip = False
        elif word in ("-u", "--pause"):
            paused = True
        elif word in ("-s", "-e", "-v", "--physics", "--iterations", "--seed"):
            skip = True  # e.g. the engine: MuJoCo is the engine whatever Gazebo's was
        elif word.startswith("-"):
            continue  # --verbose, -r, --record_path=..., -g: nothing changes here
        else:
            world = word
    return paused, world


def start_sim_server(
    ctx: NodeContext, paused: bool, name: str, *, spec_source: Any = None
) -> RunningNode:
    """The launch's one simulation server on world ``name`` (see :func:`resolve_world`)."""
    from robomodel.sim import default_world, read_world
    from robomodel.sim.server import SimServer

    if ctx.shared.sim_server is not None:
        raise RobomodelError("a simulator already runs in this launch")
    if name in ("empty.sdf", "empty.world"):  # Gazebo's own empty worlds
        name = ""
    path = resolve_world(name)
    world = read_world(path) if path else default_world()
    server = SimServer(
        world,
        context=ctx.runtime,
        package_index=ctx.shared.package_index,
        paused=paused,
        real_time_factor=world.real_time_factor,
        spec_source=spec_source,
        ros_version=1 if ctx.spec.dialect == "ros1" else 2,  # the launch's gazebo_ros
    )
    ctx.shared.sim_server = server
    ctx.log(
        f"world '{world.name}' ({path or 'the default ground and sun'}) at "
        f"{world.timestep_s * 1e3:g} ms steps{', paused' if paused else ''}"
    )
    from robomodel.launch.nodes.gazebo_hint import spawn_hint

    return SimServerNode(server, hint=spawn_hint(ctx), log=ctx.log)


class SimServerNode:
    """The running gzserver: the launch loop calls :meth:`drive`. ``hint`` is logged once if
    the world is still without robots after a while (:mod:`~robomodel.launch.nodes.gazebo_hint`)."""

    def __init__(self, server: Any, *, hint: str | None = None, log: Any = None) -> None:
        from robomodel.launch.nodes.gazebo_hint import HINT_AFTER_S

        self.server = server
        self._code: int | None = None
        self._hint = hint
        self._hint_at = time.monotonic() + HINT_AFTER_S
        self._log = log

    def drive(self, duration_s: float) -> None:
        if self._code is None:
            self.server.drive(duration_s)
        if self._hint is not None and (self.server.robots or time.monotonic() >= self._hint_at):
            if not self.server.robots and self._log is not None:
                self._log(self._hint)
            self._hint = None

    def stop(self) -> None:
        if self._code is None:
            self._code = 0
            self.server.close()

    def exit_code(self) -> int | None:
        return self._code


@register(
    "ros1",
    "gazebo_ros",
    "gzserver",
    "debug",
    purpose="robomodel's simulator (MuJoCo) with /gazebo/spawn_urdf_model and a controller "
    "manager per robot with gazebo_ros_control",
)
def gzserver(ctx: NodeContext) -> RunningNode:
    from robomodel.launch.nodes.controllers import ros1_spec_source

    paused, name = parse_server_args(list(ctx.spec.args))
    return start_sim_server(ctx, paused, name, spec_source=ros1_spec_source(ctx.params))


@register(
    "ros1",
    "gazebo_ros",
    "gzclient",
    purpose="the browser viewer, fixed frame 'world'",
)
def gzclient(ctx: NodeContext) -> RunningNode:
    part = world_viewer(ctx)
    found = ctx.search("robot_description")  # ROS 1: the description is a parameter
    if found:
        request = ctx.viewer
        request.robot_description_param = request.robot_description_param or found
    return part


def world_viewer(ctx: NodeContext) -> RunningNode:
    """The simulator's client: the launch's viewer, fixed frame 'world' unless set."""
    from robomodel.launch.nodes.state import ViewerPart

    request = ctx.viewer
    request.requested_by.append(ctx.spec.fqn)
    request.fixed_frame = request.fixed_frame or "world"
    return ViewerPart()


@dataclass(frozen=True, slots=True)
class SpawnArgs:
    """spawn_model's command line."""

    model: str
    format: str  # "urdf" or "sdf"
    param: str | None = None
    file: str | None = None
    xyz_m: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy_rad: tuple[float, float, float] = (0.0, 0.0, 0.0)
    joints: dict[str, float] = field(default_factory=dict)
    unpause: bool = False
    robot_namespace: str | None = None
    gazebo_namespace: str = "/gazebo"
    timeout_s: float = 60.0
    wait: str | None = None


_POSE = {"-x": 0, "-y": 1, "-z": 2, "-R": 3, "-P": 4, "-Y": 5}
_VALUE = {"-param", "-file", "-model", "-robot_namespace", "-gazebo_namespace", "-timeout",
          "-wait", "-reference_frame", "-database", "-package_to_model"}  # fmt: skip


def parse_spawn_args(args: tuple[str, ...]) -> SpawnArgs:
    """spawn_model's options (gazebo_ros 2.9 ``spawn_model``), with its error messages.

    Raises:
        RobomodelError: a missing or unknown option, a value that is not a number.
    """
    pose = [0.0] * 6
    joints: dict[str, float] = {}
    values: dict[str, str] = {}
    flags: set[str] = set()
    i = 0
    while i < len(args):
        token = args[i]
        if token in _POSE or token in _VALUE:
            if i + 1 >= len(args):
                raise RobomodelError(f"spawn_model: {token} needs a value")
            value = args[i + 1]
            if token in _POSE:
                pose[_POSE[token]] = _number(token, value)
            else:
                values[token] = value
            i += 2
        elif token == "-J":
            if i + 2 >= len(args):
                raise RobomodelError("spawn_model: -J needs a joint name and a position")
            joints[args[i + 1]] = _number("-J " + args[i + 1], args[i + 2])
            i += 3
        elif token in ("-urdf", "-sdf", "-trimesh", "-unpause", "-b", "-package_to_model"):
            flags.add(token)
            i += 1
        elif token.startswith("__"):  # __name:=, __log:= added by roslaunch
            i += 1
        else:
            raise RobomodelError(
                f"spawn_model: unknown option '{token}'; options are -urdf -sdf -param -file "
                "-model -x -y -z -R -P -Y -J -unpause -wait -robot_namespace -gazebo_namespace "
                "-reference_frame -timeout"
            )
    if "-model" not in values:
        raise RobomodelError("spawn_model: you must specify model name (-model NAME)")
    if ("-urdf" in flags) == ("-sdf" in flags):
        raise RobomodelError("spawn_model: give exactly one of -urdf and -sdf")
    if ("-param" in values) == ("-file" in values):
        raise RobomodelError("spawn_model: give exactly one of -param NAME and -file PATH")
    if "-database" in values:
        raise RobomodelError("spawn_model: -database needs Gazebo's model database")
    return SpawnArgs(
        model=values["-model"],
        format="urdf" if "-urdf" in flags else "sdf",
        param=values.get("-param"),
        file=values.get("-file"),
        xyz_m=(pose[0], pose[1], pose[2]),
        rpy_rad=(pose[3], pose[4], pose[5]),
        joints=joints,
        unpause="-unpause" in flags,
        robot_namespace=values.get("-robot_namespace"),
        gazebo_namespace="/" + values.get("-gazebo_namespace", "/gazebo").strip("/"),
        timeout_s=_number("-timeout", values["-timeout"]) if "-timeout" in values else 60.0,
        wait=values.get("-wait"),
    )


def _number(option: str, text: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise RobomodelError(f"spawn_model: {option} needs a number, got '{text}'") from None


@register(
    "ros1",
    "gazebo_ros",
    "spawn_model",
    purpose="spawns the URDF of -param/-file into robomodel's simulator",
)
def spawn_model(ctx: NodeContext) -> RunningNode:
    # imported here: every launch and `robomodel run` registers this module's nodes
    from robomodel.runtime.msg.types.gazebo_msgs import SpawnModel, SpawnModel_Request

    options = parse_spawn_args(ctx.spec.args)
    if options.param is not None:
        key = ctx.resolve(options.param)
        if not ctx.params.has(key):
            raise RobomodelError(f"spawn_model: parameter {key} is not set")
        xml = str(ctx.params.get(key))
    else:
        assert options.file is not None
        try:
            xml = read_user_text(options.file, what="model file")
        except UserFileError as exc:
            raise RobomodelError(f"spawn_model: {exc}") from None
    request = SpawnModel_Request(
        model_name=options.model,
        model_xml=xml,
        robot_namespace=options.robot_namespace or ctx.namespace,
        initial_pose=pose_message(options.xyz_m, options.rpy_rad),
    )
    service = f"{options.gazebo_namespace}/spawn_{options.format}_model"

    def work(node: ThreadNode) -> int:
        deadline = time.monotonic() + options.timeout_s
        ctx.log(f"Waiting for service {service}")
        while not node.stopping.is_set():
            try:
                reply = ctx.runtime.call_service(service, SpawnModel, request, timeout_s=30.0)
            except RobomodelError:
                if time.monotonic() > deadline:
                    ctx.log(f"Timeout waiting for service {service}")
                    return 1
                time.sleep(0.2)
                continue
            ctx.log(f"Spawn status: {reply.status_message}")
            if not reply.success:
                return 1
            return _after_spawn(ctx, options)
        return 0

    source = f"ros parameter {options.param}" if options.param else f"file {options.file}"
    ctx.log(f"Loading model XML from {source}")
    return ThreadNode(f"spawn_model {ctx.spec.fqn}", work, ctx.log)


def pose_message(xyz_m: tuple[float, float, float], rpy_rad: tuple[float, float, float]) -> Any:
    """A geometry_msgs/Pose from a position and roll, pitch, yaw."""
    from robomodel.description.model.pose import quat_xyzw_from_rpy
    from robomodel.runtime.msg.types.geometry_msgs import Point, Pose, Quaternion

    qx, qy, qz, qw = quat_xyzw_from_rpy(*rpy_rad)
    return Pose(Point(*xyz_m), Quaternion(qx, qy, qz, qw))


def _after_spawn(ctx: NodeContext, options: SpawnArgs) -> int:
    """spawn_model's ``-J`` (``set_model_configuration``) and ``-unpause``."""
    from robomodel.runtime.msg.types import gazebo_msgs, std_srvs

    code = 0
    if options.joints:
        request = gazebo_msgs.SetModelConfiguration_Request(
            model_name=options.model,
            joint_names=list(options.joints),
            joint_positions=[float(v) for v in options.joints.values()],
        )
        service = f"{options.gazebo_namespace}/set_model_configuration"
        reply = ctx.runtime.call_service(service, gazebo_msgs.SetModelConfiguration, request, 10.0)
        ctx.log(f"SetModelConfiguration: {reply.status_message}")
        code = 0 if reply.success else 1
    if options.unpause:
        ctx.runtime.call_service(
            f"{options.gazebo_namespace}/unpause_physics", std_srvs.Empty, None, 10.0
        )
    return code
