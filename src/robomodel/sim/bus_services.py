"""The simulator's physics and world services, with their real types, under the names of
gazebo_ros (ROS 1, ``/gazebo/...``) and of gazebo_ros / Gazebo Sim (ROS 2):

========================================================  =================================
``/gazebo/pause_physics``, ``/pause_physics``              std_srvs/srv/Empty
``/gazebo/unpause_physics``, ``/unpause_physics``          std_srvs/srv/Empty
``/gazebo/reset_world``, ``/reset_world``                  std_srvs/srv/Empty
``/gazebo/reset_simulation``, ``/reset_simulation``        std_srvs/srv/Empty
``/gazebo/step``, ``/world/default/control``               ros_gz_interfaces/srv/ControlWorld
``/gazebo/apply_body_wrench``                              gazebo_msgs/srv/ApplyBodyWrench
``/gazebo/set_model_state``                                gazebo_msgs/srv/SetModelState
========================================================  =================================

The ROS 2 names (root-level, and Gazebo Sim's ``/world/default/control``) are offered only on
ROS 2 graphs (:attr:`SimBridge.ros_version` 2), as only ROS 2's gazebo_ros has them; the
``/gazebo/...`` names on both (robomodel's viewer and ``robomodel sim`` use them;
``/gazebo/step`` is robomodel's own).

Requests that change the physics are applied by the simulation loop at its next tick (the
handlers only check them and queue them), so a service call never races a physics step.
Models are named as in Gazebo: a robot's URDF name, or its frame prefix without the slash;
``body_name`` is ``model::link`` or a link name.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Protocol

from robomodel.errors import RobomodelError
from robomodel.runtime.msg.types import gazebo_msgs as gz
from robomodel.runtime.msg.types import ros_gz_interfaces as rgz
from robomodel.runtime.msg.types import std_srvs

if TYPE_CHECKING:
    from robomodel.sim.build.robot import BuiltRobot
    from robomodel.sim.engine import Simulation
    from robomodel.sim.states import WorldStates

__all__ = [
    "ServedBridge",
    "bridge_services",
    "find_robot",
    "rpy_from_quaternion_xyzw",
    "set_model_state",
]


class ServedBridge(Protocol):
    """What gazebo_ros's services use of the :class:`robomodel.sim.bus.SimBridge` that offers
    them (this module's and :mod:`robomodel.sim.state_services`')."""

    paused: bool
    pending_steps: int

    @property
    def sim(self) -> Simulation: ...

    @property
    def ros_version(self) -> int: ...

    @property
    def states(self) -> WorldStates: ...

    def model_name(self, built: BuiltRobot) -> str: ...

    def queue(self, action: Callable[[], None]) -> None: ...

    def apply_wrench(
        self,
        link: str,
        prefix: str,
        force_n: tuple[float, float, float],
        torque_nm: tuple[float, float, float],
        duration_s: float | None,
    ) -> None: ...


def find_robot(bridge: ServedBridge, model_name: str) -> BuiltRobot:
    """The robot Gazebo would call ``model_name`` (its URDF name or its prefix)."""
    robots = bridge.sim.robots
    for built in robots:
        if model_name in (built.robot.name, built.prefix.strip("/"), built.prefix):
            return built
    if not model_name and len(robots) == 1:
        return robots[0]
    models = ", ".join(b.robot.name + (f" (prefix {b.prefix})" if b.prefix else "") for b in robots)
    raise RobomodelError(f"no model named '{model_name}'; models are: {models or '(none)'}")


def rpy_from_quaternion_xyzw(x: float, y: float, z: float, w: float) -> tuple[float, float, float]:
    norm = math.sqrt(x * x + y * y + z * z + w * w) or 1.0
    x, y, z, w = x / norm, y / norm, z / norm, w / norm
    roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
    yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    return roll, pitch, yaw


def _empty(action: Callable[[], None]) -> Callable[[Any], std_srvs.Empty_Response]:
    def handle(_request: Any) -> std_srvs.Empty_Response:
        action()
        return std_srvs.Empty_Response()

    return handle


def _control(bridge: ServedBridge, request: rgz.ControlWorld_Request) -> rgz.ControlWorld_Response:
    """ControlWorld as Gazebo Sim's world control: reset, pause, then step while paused."""
    control = request.world_control
    if control.reset.all or control.reset.time_only or control.reset.model_only:
        bridge.queue(bridge.sim.reset)
    steps = int(control.multi_step) or (1 if control.step else 0)
    if steps:
        bridge.paused = True
        bridge.pending_steps += steps
    else:
        bridge.paused = bool(control.pause)
        if not bridge.paused:
            bridge.pending_steps = 0
    return rgz.ControlWorld_Response(True)


def _wrench(
    bridge: ServedBridge, request: gz.ApplyBodyWrench_Request
) -> gz.ApplyBodyWrench_Response:
    model, _, link = request.body_name.rpartition("::")
    try:
        built = _robot_named(bridge, model) if model else _robot_with_link(bridge, link)
        if request.reference_frame not in ("", "world"):
            raise RobomodelError(
                f"reference_frame '{request.reference_frame}': only the world frame is supported"
            )
        bridge.sim.body_id(link, prefix=built.prefix)
    except RobomodelError as exc:
        return gz.ApplyBodyWrench_Response(False, f"ApplyBodyWrench: {exc}")
    duration_s = request.duration.sec + request.duration.nanosec * 1e-9
    if request.duration.sec == 0 and request.duration.nanosec == 0:
        return gz.ApplyBodyWrench_Response(True, "ApplyBodyWrench: duration 0, nothing applied")
    force, torque = request.wrench.force, request.wrench.torque
    bridge.apply_wrench(
        link,
        built.prefix,
        (force.x, force.y, force.z),
        (torque.x, torque.y, torque.z),
        duration_s if duration_s > 0 else None,
    )
    return gz.ApplyBodyWrench_Response(True, "")


def _robot_with_link(bridge: ServedBridge, link: str) -> BuiltRobot:
    for built in bridge.sim.robots:
        if any(candidate.name == link for candidate in built.robot.links):
            return built
    raise RobomodelError(f"no model has a link named '{link}'")


def set_model_state(
    bridge: ServedBridge, request: gz.SetModelState_Request
) -> gz.SetModelState_Response:
    """Teleport a robot (world frame; the model at rest), by its Gazebo model name, URDF name
    or prefix."""
    state = request.model_state
    try:
        built = _robot_named(bridge, state.model_name)
        if state.reference_frame not in ("", "world", "map", "/map"):
            raise RobomodelError(
                f"reference_frame '{state.reference_frame}': only the world frame is supported"
            )
    except RobomodelError as exc:
        return gz.SetModelState_Response(False, f"SetModelState: {exc}")
    p, q = state.pose.position, state.pose.orientation
    rpy = rpy_from_quaternion_xyzw(q.x, q.y, q.z, q.w)
    prefix = built.prefix
    bridge.queue(lambda: bridge.sim.teleport((p.x, p.y, p.z), rpy, prefix=prefix))
    return gz.SetModelState_Response(True, "SetModelState: set model state done")


def _robot_named(bridge: ServedBridge, model_name: str) -> BuiltRobot:
    for built in bridge.sim.robots:
        if bridge.model_name(built) == model_name:
            return built
    return find_robot(bridge, model_name)


def bridge_services(bridge: ServedBridge) -> list[tuple[str, Any, Callable[[Any], Any]]]:
    """(name, type, handler) of every service the simulation loop offers."""

    def pause() -> None:
        bridge.paused = True

    def unpause() -> None:
        bridge.paused = False
        bridge.pending_steps = 0

    def reset() -> None:
        bridge.queue(bridge.sim.reset)

    empty = [("pause_physics", pause), ("unpause_physics", unpause), ("reset_world", reset),
             ("reset_simulation", reset)]  # fmt: skip
    ros2 = bridge.ros_version == 2
    services: list[tuple[str, Any, Callable[[Any], Any]]] = []
    for name, action in empty:
        for prefix in ("/gazebo/", "/") if ros2 else ("/gazebo/",):
            services.append((prefix + name, std_srvs.Empty, _empty(action)))
    for name in ("/gazebo/step", "/world/default/control") if ros2 else ("/gazebo/step",):
        services.append((name, rgz.ControlWorld, lambda r: _control(bridge, r)))
    services.append(("/gazebo/apply_body_wrench", gz.ApplyBodyWrench, lambda r: _wrench(bridge, r)))
    services.append(
        ("/gazebo/set_model_state", gz.SetModelState, lambda r: set_model_state(bridge, r))
    )
    return services
