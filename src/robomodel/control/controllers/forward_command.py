"""forward_command_controller and the group/single-joint position, velocity, effort controllers.

ROS 2 (ros2_controllers forward_controllers_base.cpp): ``~/commands`` std_msgs/Float64MultiArray;
every update writes the last received ``data[i]`` to ``joints[i]/interface_name``; a length
mismatch makes ``update`` return ERROR (humble). ROS 1 (ros_controllers): the group
controllers listen on ``command`` (Float64MultiArray) and the single-joint ones on ``command``
(std_msgs/Float64). Non-finite values are rejected and the last good command is held.
"""

from __future__ import annotations

import logging
import math
from typing import Any, ClassVar

from robomodel.control.controllers.base import (
    ControllerInterface,
    InterfaceConfiguration,
    ReturnType,
)
from robomodel.control.controllers.exceptions import ControllerError
from robomodel.runtime.msg import Float64, Float64MultiArray

__all__ = [
    "EffortGroupController",
    "ForwardCommandController",
    "PositionGroupController",
    "SingleJointForwardController",
    "VelocityGroupController",
]

log = logging.getLogger("robomodel.control")


class ForwardCommandController(ControllerInterface):
    """``forward_command_controller/ForwardCommandController`` (``joints``, ``interface_name``).

    Parameter ``topic`` (robomodel: default ``~/commands``; the ROS 1 mapping sets ``~/command``).
    """

    type_name = "forward_command_controller/ForwardCommandController"
    fixed_interface: ClassVar[str | None] = None

    def on_init(self) -> None:
        self.joints = self.param_list("joints", [])
        if not self.joints:
            raise ControllerError(f"controller '{self.name}': 'joints' parameter is empty")
        self.interface_name = self.fixed_interface or str(self.param("interface_name", ""))
        if not self.interface_name:
            raise ControllerError(f"controller '{self.name}': 'interface_name' is required")
        self.topic = str(self.param("topic", "~/commands"))
        self._command: list[float] | None = None
        self._rejected = 0
        self._slots: list[int] = []
        self._values: list[float] = []

    def on_configure(self) -> None:
        if self.node is not None:
            self._sub = self.node.create_subscription(
                Float64MultiArray, self.topic, self._on_command, 10
            )

    def on_cleanup(self) -> None:
        sub = getattr(self, "_sub", None)
        if sub is not None:
            sub.destroy()

    def set_command(self, data: list[float]) -> None:
        """Take a command as the topic would (non-finite values are rejected)."""
        if not all(math.isfinite(v) for v in data):
            self._rejected += 1
            if self._rejected & (self._rejected - 1) == 0:
                log.warning(
                    "%s: command %s is not finite; the last good command is held (%d times)",
                    self.name,
                    data,
                    self._rejected,
                )
            return
        self._command = list(data)

    def _on_command(self, msg: Any) -> None:
        self.set_command(list(msg.data))

    def command_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.individual(
            [f"{j}/{self.interface_name}" for j in self.joints]
        )

    def state_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.none()

    def on_activate(self) -> None:
        self._slots = [ci.slot for ci in self.command_interfaces]
        self._values = self.command_interfaces[0].table if self.command_interfaces else []
        self._command = None  # as upstream: the command buffer is reset on activation

    def update(self, time_s: float, period_s: float) -> ReturnType:
        command = self._command
        if command is None:
            return ReturnType.OK
        if len(command) != len(self._slots):
            log.error(
                "%s: command has %d values for %d joints", self.name, len(command), len(self._slots)
            )
            return ReturnType.ERROR
        values = self._values
        for slot, v in zip(self._slots, command, strict=True):
            values[slot] = v
        return ReturnType.OK


class PositionGroupController(ForwardCommandController):
    type_name = "position_controllers/JointGroupPositionController"
    fixed_interface = "position"


class VelocityGroupController(ForwardCommandController):
    type_name = "velocity_controllers/JointGroupVelocityController"
    fixed_interface = "velocity"


class EffortGroupController(ForwardCommandController):
    type_name = "effort_controllers/JointGroupEffortController"
    fixed_interface = "effort"


class SingleJointForwardController(ForwardCommandController):
    """ROS 1 ``{position,velocity,effort}_controllers/Joint*Controller``: ``joint``, ``command``.

    Parameter ``interface_name`` is set by the ROS 1 type mapping; ``~/command`` std_msgs/Float64.
    """

    type_name = "robomodel_controllers/SingleJointForwardController"

    def on_init(self) -> None:
        joint = self.param("joint", None)
        if joint is None:
            raise ControllerError(f"controller '{self.name}': parameter 'joint' is required")
        self.params.setdefault("joints", [str(joint)])
        self.params.setdefault("topic", "~/command")
        super().on_init()

    def on_configure(self) -> None:
        if self.node is not None:
            self._sub1 = self.node.create_subscription(Float64, self.topic, self._on_single, 10)

    def _on_single(self, msg: Float64) -> None:
        self.set_command([msg.data])

    def on_cleanup(self) -> None:
        sub = getattr(self, "_sub1", None)
        if sub is not None:
            sub.destroy()
