"""ROS 1 ``effort_controllers/JointPositionController``: a PID from position error to effort.

ros_controllers effort_controllers/src/joint_position_controller.cpp: parameters ``joint`` and
``pid/{p, i, d, i_clamp, i_clamp_min, i_clamp_max, antiwindup}``; topic ``command``
(std_msgs/Float64). ``starting()`` takes the current position as the command and resets the
PID; ``update()`` clamps the command to the URDF limits, takes the error as the shortest angular
distance (continuous joints; revolute: with large limits) or ``cmd − pos`` (prismatic) and
writes ``pid.computeCommand(error, period)`` to the joint's effort.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Mapping
from typing import Any

from robomodel.control.controllers.base import (
    ControllerInterface,
    InterfaceConfiguration,
    ReturnType,
)
from robomodel.control.controllers.exceptions import ControllerError
from robomodel.control.exceptions import ConfigError
from robomodel.control.pid import Gains, Pid
from robomodel.description.model import JointType
from robomodel.runtime.msg import Float64, Header, JointControllerState, Time
from robomodel.runtime.node import Publisher
from robomodel.runtime.params import SetResult

__all__ = ["JointPositionController", "shortest_angular_distance"]

log = logging.getLogger("robomodel.control")

_OK = ReturnType.OK
_TWO_PI = 2.0 * math.pi
_GAIN_NAMES = ("p", "i", "d", "i_clamp", "i_clamp_min", "i_clamp_max", "antiwindup")


def _normalize_angle(a: float) -> float:
    """angles::normalize_angle: into (-pi, pi]."""
    a = math.fmod(math.fmod(a, _TWO_PI) + _TWO_PI, _TWO_PI)
    return a - _TWO_PI if a > math.pi else a


def shortest_angular_distance(from_rad: float, to_rad: float) -> float:
    """angles::shortest_angular_distance."""
    return _normalize_angle(to_rad - from_rad)


class JointPositionController(ControllerInterface):
    """See the module docstring. The command is also settable with :meth:`set_command`."""

    type_name = "effort_controllers/JointPositionController"

    def on_init(self) -> None:
        self.joint = str(self.param("joint"))
        prefix = "pid." if any(k.startswith("pid.") for k in self.params) else ""
        if not prefix and "p" not in self.params:
            raise ControllerError(
                f"controller '{self.name}': PID gains missing; give pid: {{p: ..., i: ..., d: ...}}"
            )
        self.pid = Pid(Gains.from_params(self.params, prefix))
        self._gain_prefix = prefix
        if self.node is not None:  # dynamic_reconfigure: gains set on the node apply live
            self.node.parameters.add_set_callback(self._check_gains)
            self.node.parameters.add_post_set_callback(self._apply_gains)
        known = (
            "p",
            "i",
            "d",
            "i_clamp",
            "i_clamp_min",
            "i_clamp_max",
            "antiwindup",
            "publish_state",
        )
        for key in self.params:
            if prefix and key.startswith(prefix) and key[len(prefix) :] not in known:
                sub = key[len(prefix) :]
                hint = [k for k in known if k.lower() == sub.lower()]
                log.warning(
                    "%s: unknown PID parameter '%s' is ignored, as ROS 1 does%s",
                    self.name,
                    key,
                    f" (did you mean '{prefix}{hint[0]}'?)" if hint else "",
                )
        self.lower, self.upper, self.continuous = -math.inf, math.inf, False
        if self.robot is not None and self.robot.has_joint(self.joint):
            j = self.robot.joint(self.joint)
            self.continuous = j.type is JointType.CONTINUOUS
            if j.type in (JointType.REVOLUTE, JointType.PRISMATIC) and j.limit is not None:
                self.lower, self.upper = j.limit.lower_or_default, j.limit.upper_or_default
            self.prismatic = j.type is JointType.PRISMATIC
        else:
            self.prismatic = False
        self.command = math.nan
        self._rejected = 0
        self._state_pub: Publisher[JointControllerState] | None = None
        self._loop_count = 0

    def _gain_keys(self, changes: Mapping[str, Any]) -> bool:
        prefix = self._gain_prefix
        return any(k.startswith(prefix) and k[len(prefix) :] in _GAIN_NAMES for k in changes)

    def _check_gains(self, changes: Mapping[str, Any]) -> SetResult:
        """Refuse gains that are not numbers before they are stored."""
        if not self._gain_keys(changes):
            return SetResult(True)
        assert self.node is not None
        try:
            Gains.from_params({**self.node.parameters.items(), **changes}, self._gain_prefix)
        except ConfigError as exc:
            return SetResult(False, str(exc))
        return SetResult(True)

    def _apply_gains(self, changes: Mapping[str, Any]) -> None:
        """New gains take effect at the next update; the integral is kept (setGains)."""
        if self._gain_keys(changes):
            assert self.node is not None
            self.pid.set_gains(Gains.from_params(self.node.parameters.items(), self._gain_prefix))

    def on_configure(self) -> None:
        if self.node is not None:
            self._sub = self.node.create_subscription(Float64, "~/command", self._on_command, 10)
            self._state_pub = self.node.create_publisher(JointControllerState, "~/state", 1)

    def on_cleanup(self) -> None:
        sub = getattr(self, "_sub", None)
        if sub is not None:
            sub.destroy()
        if self._state_pub is not None:
            self._state_pub.destroy()
            self._state_pub = None

    def _on_command(self, msg: Any) -> None:
        self.set_command(float(msg.data))

    def set_command(self, position: float) -> None:
        """A new set point [rad or m]; non-finite values are rejected (last good one held)."""
        if not math.isfinite(position):
            self._rejected += 1
            if self._rejected & (self._rejected - 1) == 0:
                log.warning("%s: command %s rejected (not finite)", self.name, position)
            return
        self.command = position

    def command_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.individual([f"{self.joint}/effort"])

    def state_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.individual([f"{self.joint}/position"])

    def on_activate(self) -> None:
        self._effort = self.command_interfaces[0]
        self._position = self.state_interfaces[0]
        self._cmd_values, self._cmd_slot = self._effort.table, self._effort.slot
        self._state_values, self._state_slot = self._position.table, self._position.slot
        pos = self._position.get()
        self.command = min(max(pos, self.lower), self.upper)  # starting(): hold where it is
        self._last_pos = pos
        self.pid.reset()

    def update(self, time_s: float, period_s: float) -> ReturnType:
        cmd = self.command
        if cmd < self.lower:
            cmd = self.lower
        elif cmd > self.upper:
            cmd = self.upper
        pos = self._state_values[self._state_slot]
        # continuous: shortest angular distance; revolute (shortest_angular_distance_with_large_
        # limits ~ plain difference) and prismatic: cmd - pos
        error = shortest_angular_distance(pos, cmd) if self.continuous else cmd - pos
        effort = self.pid.compute(error, period_s)
        self._cmd_values[self._cmd_slot] = effort
        count = self._loop_count + 1
        self._loop_count = count
        if count % 10 == 0 and self._state_pub is not None:  # ROS 1: every 10th
            self._publish_state(time_s, period_s, cmd, pos, error, effort)
        self._last_pos = pos
        return _OK

    def _publish_state(
        self, time_s: float, period_s: float, cmd: float, pos: float, error: float, effort: float
    ) -> None:
        assert self._state_pub is not None
        g = self.pid.gains
        sec = math.floor(time_s)
        self._state_pub.publish(
            JointControllerState(
                Header(Time(int(sec), int((time_s - sec) * 1e9))),
                set_point=cmd,
                process_value=pos,
                process_value_dot=(pos - self._last_pos) / period_s if period_s > 0 else 0.0,
                error=error,
                time_step=period_s,
                command=effort,
                p=g.p,
                i=g.i,
                d=g.d,
                i_clamp=g.i_max,
                antiwindup=g.antiwindup,
            )
        )
