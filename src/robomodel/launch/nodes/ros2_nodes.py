"""ROS 2 nodes of a launch file: robot_state_publisher, joint_state_publisher(_gui), rviz2 and
tf2_ros static_transform_publisher (the rqt tools are in :mod:`.viewer`, for both dialects).

Parameters come from the launch file's ``parameters=[...]`` (:mod:`.ros2_params`), remaps and
namespaces as the real nodes would take them. joint_state_publisher (Humble and Jazzy) and the
viewer read ``robot_description`` from their parameter or, without one, from the
``robot_description`` topic that robot_state_publisher publishes: here, from the launch's
robot_state_publisher in the same namespace.
"""

from __future__ import annotations

import contextlib
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.launch.nodes.base import NodeContext, RunningNode, register
from robomodel.launch.nodes.state import InProcessNode, ViewerPart, slider_request
from robomodel.launch.nodes.tf_static import parse_static_transform_args
from robomodel.launch.nodes.viewer import open_rviz_argument

__all__ = ["parse_ros2_static_transform_args", "robot_description_of"]


def robot_description_of(ctx: NodeContext, own: dict[str, Any]) -> str:
    """The URDF of a node: its ``robot_description`` parameter, else the one of the launch's
    robot_state_publisher in the same namespace (what the ``robot_description`` topic carries).
    """
    text = own.get("robot_description")
    if text:
        return str(text)
    from robomodel.launch.nodes.ros2_params import node_parameters

    for spec in ctx.shared.nodes:
        if (spec.dialect, spec.package, spec.executable) != (
            "ros2",
            "robot_state_publisher",
            "robot_state_publisher",
        ):
            continue
        if spec.namespace.rstrip("/") != ctx.spec.namespace.rstrip("/"):
            continue
        found = node_parameters(spec, name="robot_state_publisher").get("robot_description")
        if found:
            return str(found)
    raise RobomodelError(
        f"{ctx.spec.fqn}: no robot_description parameter, and no robot_state_publisher in "
        f"{ctx.namespace} publishes one on the robot_description topic; give the node "
        "parameters=[{'robot_description': ...}]"
    )


@register(
    "ros2",
    "robot_state_publisher",
    "robot_state_publisher",
    purpose="robomodel's robot_state_publisher (robot_description, publish_frequency, "
    "frame_prefix, ignore_timestamp)",
)
def robot_state_publisher(ctx: NodeContext) -> RunningNode:
    from robomodel.runtime.nodes.robot_state_publisher import RobotStatePublisher

    name = ctx.spec.name or "robot_state_publisher"
    params = ctx.ros2_parameters(name)
    if not params.get("robot_description"):
        raise RobomodelError(
            f"{ctx.spec.fqn}: robot_description parameter must not be empty (give "
            "parameters=[{'robot_description': ...}])"
        )
    rsp = RobotStatePublisher(
        ctx.runtime,
        None,
        name=name,
        namespace=ctx.namespace,
        parameters=params,
        remappings=ctx.remappings,
    )
    request = ctx.viewer
    if request.robot_description_text is None:
        request.robot_description_text = str(params["robot_description"])
    robot = request.robot(ctx.namespace)
    robot.description_text = robot.description_text or str(params["robot_description"])
    robot.frame_prefix = str(params.get("frame_prefix", ""))
    return InProcessNode(rsp)


@register(
    "ros2",
    "joint_state_publisher",
    "joint_state_publisher",
    purpose="robomodel's joint_state_publisher",
)
def joint_state_publisher(ctx: NodeContext) -> RunningNode:
    from robomodel.description import read_urdf
    from robomodel.runtime.nodes.joint_state_publisher import JointStatePublisher

    name = ctx.spec.name or "joint_state_publisher"
    params = ctx.ros2_parameters(name)
    robot = read_urdf(robot_description_of(ctx, params)).robot
    params.pop("robot_description", None)
    jsp = JointStatePublisher(
        ctx.runtime,
        robot,
        name=name,
        namespace=ctx.namespace,
        parameters=params,
        remappings=ctx.remappings,
    )
    return InProcessNode(jsp)


@register(
    "ros2",
    "joint_state_publisher_gui",
    "joint_state_publisher_gui",
    purpose="the viewer's joint sliders",
)
def joint_state_publisher_gui(ctx: NodeContext) -> RunningNode:
    params = ctx.ros2_parameters(ctx.spec.name or "joint_state_publisher_gui")
    try:
        text: str | None = robot_description_of(ctx, params)
    except RobomodelError:
        if ctx.viewer.robot_description_text is None:
            raise
        text = None  # the real GUI waits for its robot_description; the viewer shows the others
    return slider_request(ctx, description_text=text)


@register("ros2", "rviz2", "rviz2", purpose="the browser viewer; -d FILE.rviz read")
def rviz2(ctx: NodeContext) -> RunningNode:
    request = ctx.viewer
    request.requested_by.append(ctx.spec.fqn)
    open_rviz_argument(ctx)
    if request.robot_description_text is None:
        # without one, RViz shows no robot until one is published; the runner says so
        with contextlib.suppress(RobomodelError):
            request.robot_description_text = robot_description_of(ctx, {})
    return ViewerPart()


_FLAGS = {
    "--x": 0, "--y": 1, "--z": 2, "--qx": 3, "--qy": 4, "--qz": 5, "--qw": 6,
    "--roll": 7, "--pitch": 8, "--yaw": 9,
}  # fmt: skip


def parse_ros2_static_transform_args(
    args: tuple[str, ...],
) -> tuple[tuple[float, float, float], tuple[float, float, float, float], str, str]:
    """tf2_ros (Humble/Jazzy) ``static_transform_publisher``: the ``--x 1 --frame-id a
    --child-frame-id b`` form (``--qx..--qw`` or ``--roll --pitch --yaw``), or the old
    positional one; ValueError with the usage."""
    words = [a for a in args if a != "--ros-args" and ":=" not in a]
    if not any(w.startswith("--") for w in words):
        xyz, quat, parent, child, _ = parse_static_transform_args(words, with_period=False)
        return xyz, quat, parent, child
    import math

    from robomodel.launch.nodes.tf_static import _quat_from_ypr

    values = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0]
    frames: dict[str, str] = {}
    given: set[int] = set()
    i = 0
    while i < len(words):
        flag = words[i]
        if i + 1 >= len(words):
            raise ValueError(f"{flag} needs a value")
        if flag in _FLAGS:
            values[_FLAGS[flag]] = float(words[i + 1])
            given.add(_FLAGS[flag])
        elif flag in ("--frame-id", "--child-frame-id"):
            frames[flag] = words[i + 1]
        else:
            raise ValueError(f"unknown argument '{flag}'")
        i += 2
    if "--frame-id" not in frames or "--child-frame-id" not in frames:
        raise ValueError("--frame-id and --child-frame-id are required")
    if given & {7, 8, 9}:
        quat = _quat_from_ypr(values[9], values[8], values[7])
    else:
        qx, qy, qz, qw = values[3:7]
        norm = math.sqrt(qx * qx + qy * qy + qz * qz + qw * qw)
        if norm == 0.0:
            raise ValueError("the quaternion is zero")
        quat = (qx / norm, qy / norm, qz / norm, qw / norm)
    return (values[0], values[1], values[2]), quat, frames["--frame-id"], frames["--child-frame-id"]


@register(
    "ros2",
    "tf2_ros",
    "static_transform_publisher",
    purpose="a static transform on /tf_static (both argument forms)",
)
def static_transform_publisher(ctx: NodeContext) -> RunningNode:
    from robomodel.launch.nodes.tf_static import start_transform_publisher

    try:
        xyz, quat, parent, child = parse_ros2_static_transform_args(ctx.spec.args)
    except ValueError as exc:
        raise RobomodelError(f"static_transform_publisher: {exc}") from None
    return start_transform_publisher(ctx, xyz, quat, parent, child)
