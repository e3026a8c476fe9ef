"""Control: a ros2_control-compatible controller framework without ROS.

``ResourceManager(hardware_from_robot(robot))`` holds the hardware; ``ControllerManager`` loads
controllers (from a ROS 2 or ROS 1 controller YAML via :func:`load_controller_config`), switches
them and runs the read -> update -> write loop, stepped (:meth:`ControllerManager.step`) or on a
timer (:meth:`ControllerManager.start`). See ``docs/control.md``.
"""

from robomodel.control.config import (
    ROS1_TYPES,
    ControllerConfig,
    ControllerSpec,
    load_controller_config,
)
from robomodel.control.exceptions import (
    ConfigError,
    ControlError,
    ControllerStateError,
    UnknownControllerError,
)
from robomodel.control.manager import ControllerManager, Strictness
from robomodel.control.pid import AntiWindup, Gains, Pid, PidKilted
from robomodel.control.system import ControlSystem

__all__ = [
    "ROS1_TYPES",
    "AntiWindup",
    "ConfigError",
    "ControlError",
    "ControlSystem",
    "ControllerConfig",
    "ControllerManager",
    "ControllerSpec",
    "ControllerStateError",
    "Gains",
    "Pid",
    "PidKilted",
    "Strictness",
    "UnknownControllerError",
    "load_controller_config",
]
