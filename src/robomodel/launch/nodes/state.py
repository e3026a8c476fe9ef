"""robot_state_publisher and joint_state_publisher nodes of a launch file.

ROS 1 semantics (robot_state_publisher 1.15, joint_state_publisher 1.15): the description is
the ``robot_description`` found by searchParam from the node's namespace; private parameters
``~publish_frequency`` (50 Hz in ROS 1), ``~tf_prefix`` (or a searched ``tf_prefix``),
``~ignore_timestamp``; joint_state_publisher's ``~rate``, ``~source_list``, ``~zeros``,
``~use_gui`` (the old way to ask for sliders: they are the viewer's). Remaps apply as they do
to the real nodes (e.g. ``joint_states`` -> ``/rrbot/joint_states``).
"""

from __future__ import annotations

from typing import Any

from robomodel.errors import RobomodelError
from robomodel.launch.nodes.base import NodeContext, RunningNode, register

__all__ = ["InProcessNode", "description_of", "slider_request"]


class InProcessNode:
    """A robomodel runtime node running in the launch process."""

    def __init__(self, component: Any) -> None:
        self.component = component
        self._code: int | None = None

    def stop(self) -> None:
        if self._code is None:
            self._code = 0
            node = getattr(self.component, "node", None)
            if node is not None:
                node.destroy()

    def exit_code(self) -> int | None:
        return self._code


def description_of(ctx: NodeContext, param: str = "robot_description") -> str:
    """The URDF text a node finds with searchParam, or a clear error naming where it looked."""
    found = ctx.search(param)
    if found is None:
        raise RobomodelError(
            f"{ctx.spec.fqn}: parameter '{param}' is not set in {ctx.spec.namespace} or any "
            f'parent namespace; set it with <param name="{param}" ...> in the launch file'
        )
    value = ctx.params.get(found)
    if not isinstance(value, str):
        raise RobomodelError(f"{ctx.spec.fqn}: parameter '{found}' is not a string")
    return value


def _prefix(ctx: NodeContext) -> str:
    found = ctx.param("~tf_prefix")
    if found is None:
        path = ctx.search("tf_prefix")
        found = ctx.params.get(path) if path else ""
    text = str(found or "").strip("/")
    return f"{text}/" if text else ""


@register(
    "ros1",
    "robot_state_publisher",
    "robot_state_publisher",
    "state_publisher",
    purpose="robomodel's robot_state_publisher (URDF + /joint_states -> /tf, /tf_static)",
)
def robot_state_publisher(ctx: NodeContext) -> RunningNode:
    from robomodel.runtime.nodes.robot_state_publisher import RobotStatePublisher

    parameters = {
        "publish_frequency": float(ctx.param("~publish_frequency", 50.0)),
        "ignore_timestamp": bool(ctx.param("~ignore_timestamp", False)),
        "frame_prefix": _prefix(ctx),
        "use_sim_time": ctx.use_sim_time,
    }
    rsp = RobotStatePublisher(
        ctx.runtime,
        description_of(ctx),
        name=ctx.spec.name or "robot_state_publisher",
        namespace=ctx.namespace,
        parameters=parameters,
        remappings=ctx.remappings,
    )
    robot = ctx.viewer.robot(ctx.namespace)
    robot.description_param = robot.description_param or ctx.search("robot_description")
    robot.frame_prefix = str(parameters["frame_prefix"])
    return InProcessNode(rsp)


@register(
    "ros1",
    "joint_state_publisher",
    "joint_state_publisher",
    purpose="robomodel's joint_state_publisher (use_gui: the viewer's sliders)",
)
def joint_state_publisher(ctx: NodeContext) -> RunningNode:
    if bool(ctx.param("~use_gui", False)) or bool(ctx.param("use_gui", False)):
        return _sliders(ctx)  # the old joint_state_publisher showed the GUI itself
    from robomodel.description import read_urdf
    from robomodel.runtime.nodes.joint_state_publisher import JointStatePublisher

    robot = read_urdf(description_of(ctx).encode()).robot
    parameters: dict[str, Any] = {
        "rate": float(ctx.param("~rate", 10.0)),
        "use_sim_time": ctx.use_sim_time,
    }
    sources = ctx.param("~source_list")
    if sources:
        parameters["source_list"] = [str(s) for s in sources]
    zeros = ctx.param("~zeros")
    if isinstance(zeros, dict):
        parameters.update({f"zeros.{k}": float(v) for k, v in zeros.items()})
    for name in ("publish_default_positions", "publish_default_velocities", "use_mimic_tags"):
        value = ctx.param("~" + name)
        if value is not None:
            parameters[name] = bool(value)
    jsp = JointStatePublisher(
        ctx.runtime,
        robot,
        name=ctx.spec.name or "joint_state_publisher",
        namespace=ctx.namespace,
        parameters=parameters,
        remappings=ctx.remappings,
    )
    return InProcessNode(jsp)


class ViewerPart:
    """A node whose role the launch's viewer plays; it runs as long as the launch."""

    def __init__(self) -> None:
        self._code: int | None = None

    def stop(self) -> None:
        self._code = 0

    def exit_code(self) -> int | None:
        return self._code


def slider_request(ctx: NodeContext, *, description_text: str | None = None) -> RunningNode:
    """joint_state_publisher_gui's role (both dialects): the viewer's sliders for the robot of
    the node's namespace, publishing on the node's resolved ``joint_states``."""
    request = ctx.viewer
    request.sliders = True
    request.requested_by.append(ctx.spec.fqn)
    request.namespace = ctx.namespace
    request.joint_states_topic = ctx.resolve_name("joint_states")
    robot = request.robot(ctx.namespace)
    robot.joint_states_topic = request.joint_states_topic
    robot.slider_node_name = ctx.spec.name or ctx.spec.executable
    if description_text is not None:
        robot.description_text = robot.description_text or description_text
        request.robot_description_text = request.robot_description_text or description_text
    found = ctx.search("robot_description") if ctx.spec.dialect == "ros1" else None
    if found:
        request.robot_description_param = request.robot_description_param or found
        robot.description_param = robot.description_param or found
    return ViewerPart()


def _sliders(ctx: NodeContext) -> RunningNode:
    return slider_request(ctx)


@register(
    "ros1",
    "joint_state_publisher_gui",
    "joint_state_publisher_gui",
    purpose="the viewer's joint sliders (joint_state_publisher_gui)",
)
def joint_state_publisher_gui(ctx: NodeContext) -> RunningNode:
    return _sliders(ctx)
