"""Where a ROS 1 type and robomodel's (ROS 2) type of the same name differ.

Everything else maps field by field, by name (std_msgs/Header's ``seq`` is the publisher's
message count; ``time``/``duration`` are builtin_interfaces' Time/Duration).

- ``tf/tfMessage`` is ``tf2_msgs/TFMessage`` (the same definition; old nodes still use it).
- controller_manager_msgs/ControllerState: ROS 1's states ``initialized``/``stopped``/
  ``running`` are ROS 2's ``unconfigured``/``inactive``/``active``; ``claimed_resources``
  (one entry per hardware interface type, its joints as resources) is built from, and read
  back into, ROS 2's ``claimed_interfaces`` (``joint/type``); the interface types are named
  as ROS 1's hardware_interface classes (``effort`` is
  ``hardware_interface::EffortJointInterface``).
- controller_manager_msgs/SwitchController: ROS 1's ``start_controllers``/
  ``stop_controllers``/``start_asap``/``timeout`` (float64 seconds) are ROS 2's
  ``activate_controllers``/``deactivate_controllers``/``activate_asap``/``timeout``
  (a Duration). The strictness values are the same (BEST_EFFORT 1, STRICT 2).
- control_msgs/JointTrajectoryControllerState: ROS 1's ``desired``/``actual``/``error`` are
  Jazzy's ``reference``/``feedback``/``error``.
- sensor_msgs/CameraInfo: ROS 1's ``D``/``K``/``R``/``P`` are ROS 2's ``d``/``k``/``r``/``p``.
- stereo_msgs/DisparityImage: ROS 1's baseline ``T`` is ROS 2's ``t``.
"""

from __future__ import annotations

import math
import types
from typing import Any

from robomodel.runtime.transport.ros1.ros1_codec import Field

__all__ = ["ALIASES", "ros1_hardware_interface", "special_field"]

ALIASES = {"tf/msg/tfMessage": "tf2_msgs/msg/TFMessage"}

_STATES_TO_ROS1 = {"active": "running", "inactive": "stopped", "unconfigured": "initialized"}
_STATES_FROM_ROS1 = {v: k for k, v in _STATES_TO_ROS1.items()}


# ROS 1's joint command interfaces (hardware_interface/joint_command_interface.h)
_HARDWARE_INTERFACES = {
    "position": "hardware_interface::PositionJointInterface",
    "velocity": "hardware_interface::VelocityJointInterface",
    "effort": "hardware_interface::EffortJointInterface",
}
_INTERFACE_KINDS = {v: k for k, v in _HARDWARE_INTERFACES.items()}


def ros1_hardware_interface(kind: str) -> str:
    """ROS 2's command interface type (``effort``) as ROS 1's hardware interface class."""
    return _HARDWARE_INTERFACES.get(kind, kind)


def _resources(claimed: Any) -> list[types.SimpleNamespace]:
    """``["joint1/position", "joint2/position"]`` -> one resource list per interface type."""
    by_kind: dict[str, list[str]] = {}
    for interface in claimed:
        joint, _, kind = str(interface).rpartition("/")
        by_kind.setdefault(ros1_hardware_interface(kind), []).append(joint)
    return [types.SimpleNamespace(hardware_interface=k, resources=v) for k, v in by_kind.items()]


def _interfaces(resources: Any) -> list[str]:
    return [
        f"{r}/{_INTERFACE_KINDS.get(entry.hardware_interface, entry.hardware_interface)}"
        for entry in resources
        for r in entry.resources
    ]


def _seconds(duration: Any) -> float:
    return float(duration.sec) + float(duration.nanosec) * 1e-9


def _duration(seconds: float) -> Any:
    from robomodel.runtime.msg.types.builtin_interfaces import Duration

    if not math.isfinite(seconds):
        return Duration(0, 0)
    sec = math.floor(seconds)
    return Duration(int(sec), round((seconds - sec) * 1e9) % 1_000_000_000)


_SPECIAL = {
    ("controller_manager_msgs/msg/ControllerState", "state"): Field(
        "state", lambda s: _STATES_TO_ROS1.get(s, s), lambda s: _STATES_FROM_ROS1.get(s, s)
    ),
    ("controller_manager_msgs/msg/ControllerState", "claimed_resources"): Field(
        "claimed_interfaces", _resources, _interfaces
    ),
    ("controller_manager_msgs/msg/SwitchControllerRequest", "start_controllers"): Field(
        "activate_controllers"
    ),
    ("controller_manager_msgs/msg/SwitchControllerRequest", "stop_controllers"): Field(
        "deactivate_controllers"
    ),
    ("controller_manager_msgs/msg/SwitchControllerRequest", "start_asap"): Field("activate_asap"),
    ("controller_manager_msgs/msg/SwitchControllerRequest", "timeout"): Field(
        "timeout", _seconds, _duration
    ),
    ("control_msgs/msg/JointTrajectoryControllerState", "desired"): Field("reference"),
    ("control_msgs/msg/JointTrajectoryControllerState", "actual"): Field("feedback"),
    **{("sensor_msgs/msg/CameraInfo", name): Field(name.lower()) for name in "DKRP"},
    ("stereo_msgs/msg/DisparityImage", "T"): Field("t"),
}


def special_field(ros1_type: str, field: str) -> Field | None:
    return _SPECIAL.get((ros1_type, field))
