"""Gazebo nodes of a ROS 2 launch file: gazebo_ros (Gazebo Classic: ``gzserver``, ``gzclient``,
``spawn_entity.py``) and ros_gz_sim (Gazebo Sim: ``gz_sim``, ``create``), onto robomodel's
simulator.

robomodel's ``gazebo_ros`` and ``ros_gz_sim`` packages (``launch/share``) provide
``gazebo.launch.py`` / ``gz_sim.launch.py`` with the real ones' arguments (``world``, ``pause``,
``gui``, ``server``, ``verbose``; ``gz_args``), which start these nodes. The server is
:class:`~robomodel.sim.server.SimServer`; a spawned robot with the gazebo_ros2_control (or
gz_ros2_control) plugin gets a controller manager in its namespace with the controllers of the
plugin's ``<parameters>`` file, which spawners then load.
"""

from __future__ import annotations

import threading
import time
from typing import Any

from robomodel._files import UserFileError, read_user_text
from robomodel.errors import RobomodelError
from robomodel.launch.nodes.base import NodeContext, RunningNode, ThreadNode, register
from robomodel.launch.nodes.gazebo import parse_server_args, start_sim_server, world_viewer
from robomodel.launch.nodes.state import ViewerPart

__all__ = ["parse_entity_args"]


def _words(args: tuple[str, ...]) -> list[str]:
    return [w for arg in args for w in arg.split()]


@register(
    "ros2",
    "gazebo_ros",
    "gzserver",
    purpose="robomodel's simulator (MuJoCo) with /spawn_entity and a controller manager per "
    "robot with gazebo_ros2_control",
)
def gzserver(ctx: NodeContext) -> RunningNode:
    paused, world = parse_server_args(_words(ctx.spec.args))
    return start_sim_server(ctx, paused, world)


@register(
    "ros2",
    "ros_gz_sim",
    "gz_sim",
    purpose="robomodel's simulator for gz_sim.launch.py's gz_args (-r, -s, WORLD)",
)
def gz_sim(ctx: NodeContext) -> RunningNode:
    words = _words(ctx.spec.args)
    paused, world = parse_server_args(words)
    if "-s" not in words:  # gz sim runs its GUI unless -s (server only)
        world_viewer(ctx)
    return start_sim_server(ctx, paused or "-r" not in words, world)


register("ros2", "gazebo_ros", "gzclient", purpose="the browser viewer, fixed frame 'world'")(
    world_viewer
)
register("ros2", "ros_gz_sim", "gz_gui", purpose="the browser viewer, fixed frame 'world'")(
    world_viewer
)


@register(
    "ros2",
    "ros_gz_bridge",
    "parameter_bridge",
    purpose="nothing to bridge: robomodel's simulator publishes on the bus itself",
)
def parameter_bridge(ctx: NodeContext) -> RunningNode:
    return ViewerPart()


_POSE = {"-x": 0, "-y": 1, "-z": 2, "-R": 3, "-P": 4, "-Y": 5}
_VALUE = {"-entity", "-name", "-topic", "-file", "-string", "-robot_namespace", "-timeout",
          "-reference_frame", "-world", "-spawn_service_timeout", "-database",
          "-gazebo_namespace"}  # fmt: skip


def parse_entity_args(args: tuple[str, ...]) -> dict[str, Any]:
    """spawn_entity.py's / ros_gz_sim create's options as a dict (``pose`` [6], ``entity``,
    ``topic``/``file``/``string``, ``robot_namespace``, ``timeout``, ``unpause``)."""
    words = list(args)
    if "--ros-args" in words:
        words = words[: words.index("--ros-args")]
    out: dict[str, Any] = {"pose": [0.0] * 6, "unpause": False}
    i = 0
    while i < len(words):
        word = words[i]
        if word in _POSE or word in _VALUE:
            if i + 1 >= len(words):
                raise RobomodelError(f"{word} needs a value")
            value = words[i + 1]
            if word in _POSE:
                try:
                    out["pose"][_POSE[word]] = float(value)
                except ValueError:
                    raise RobomodelError(f"{word} needs a number, got '{value}'") from None
            else:
                out[word.lstrip("-")] = value
            i += 2
        elif word in ("-unpause", "-stdin", "-b", "-allow_renaming"):
            out[word.lstrip("-")] = True
            i += 1
        else:
            raise RobomodelError(f"unknown option '{word}'")
    out["entity"] = out.pop("entity", None) or out.pop("name", None)
    if not out["entity"]:
        raise RobomodelError("give the entity's name (-entity NAME, or -name for create)")
    if not any(k in out for k in ("topic", "file", "string")):
        raise RobomodelError("give the description: -topic T, -file F or -string XML")
    return out


def _description(ctx: NodeContext, options: dict[str, Any], stopping: threading.Event) -> str:
    if "string" in options:
        return str(options["string"])
    if "file" in options:
        try:
            return read_user_text(options["file"], what="model file")
        except UserFileError as exc:
            raise RobomodelError(str(exc)) from None
    from robomodel.launch.nodes.ros2_nodes import robot_description_of

    topic = str(options["topic"])
    if topic.strip("/").rsplit("/", 1)[-1] == "robot_description":
        try:  # what the launch's robot_state_publisher publishes there
            return robot_description_of(ctx, {})
        except RobomodelError:
            pass
    return _wait_for_string(ctx, topic, stopping, float(options.get("timeout", 30.0)))


def _wait_for_string(
    ctx: NodeContext, topic: str, stopping: threading.Event, timeout_s: float
) -> str:
    from robomodel.runtime.msg import String
    from robomodel.runtime.qos import latched

    box: list[str] = []
    got = threading.Event()

    def on_message(msg: Any) -> None:
        box.append(msg.data)
        got.set()

    node = ctx.runtime.create_node(
        (ctx.spec.name or "spawn_entity") + "_listener", ctx.namespace, remappings=ctx.remappings
    )
    node.create_subscription(String, topic, on_message, latched())
    deadline = time.monotonic() + timeout_s
    try:
        while not got.wait(0.1):
            if stopping.is_set() or time.monotonic() > deadline:
                raise RobomodelError(f"no robot description arrived on {topic}")
        return box[0]
    finally:
        node.destroy()


def _spawn(ctx: NodeContext) -> RunningNode:
    options = parse_entity_args(ctx.spec.args)

    def work(node: ThreadNode) -> int:
        from robomodel.launch.nodes.gazebo import pose_message
        from robomodel.runtime.msg.types import gazebo_msgs, std_srvs

        xml = _description(ctx, options, node.stopping)
        pose = options["pose"]
        request = gazebo_msgs.SpawnEntity_Request(
            name=options["entity"],
            xml=xml,
            robot_namespace=options.get("robot_namespace", ctx.namespace),
            initial_pose=pose_message(tuple(pose[:3]), tuple(pose[3:])),
        )
        deadline = time.monotonic() + float(options.get("spawn_service_timeout", 30.0))
        while not node.stopping.is_set():
            try:
                reply = ctx.runtime.call_service(
                    "/spawn_entity", gazebo_msgs.SpawnEntity, request, 30.0
                )
            except RobomodelError:
                if time.monotonic() > deadline:
                    ctx.log(
                        "Service /spawn_entity unavailable. Was Gazebo started with GazeboRosFactory?"
                    )
                    return 1
                time.sleep(0.2)
                continue
            ctx.log(reply.status_message)
            if reply.success and options["unpause"]:
                ctx.runtime.call_service("/unpause_physics", std_srvs.Empty, None, 10.0)
            return 0 if reply.success else 1
        return 0

    return ThreadNode(f"spawn {ctx.spec.fqn}", work, ctx.log)


register(
    "ros2",
    "gazebo_ros",
    "spawn_entity.py",
    purpose="spawns -topic/-file/-string as -entity into robomodel's simulator",
)(_spawn)
register(
    "ros2",
    "ros_gz_sim",
    "create",
    purpose="spawns -topic/-file/-string as -name into robomodel's simulator",
)(_spawn)
