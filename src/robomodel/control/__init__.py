"""Control: a ros2_control-compatible controller framework without ROS.

``ResourceManager(hardware_from_robot(robot))`` holds the hardware; ``ControllerManager`` loads
controllers (from a ROS 2 or ROS 1 controller YAML via :func:`load_controller_config`), switches
them and runs the read -> update -> write loop, stepped (:meth:`ControllerManager.step`) or on a
timer (:meth:`ControllerManager.start`). See ``docs/control.md``.

The names are re-exported lazily (PEP 562), so that a process that only talks to a controller
manager (``robomodel.control.client``: the spawner, the ``controller_manager`` script) does not
load the controllers, the hardware and the manager.
"""

from __future__ import annotations

from robomodel._lazy import lazy_exports

TYPE_CHECKING = False  # typing.TYPE_CHECKING without importing typing (mypy knows the name)
if TYPE_CHECKING:
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

_MODULE_OF: dict[str, str] = {
    "ROS1_TYPES": "robomodel.control.config",
    "ControllerConfig": "robomodel.control.config",
    "ControllerSpec": "robomodel.control.config",
    "load_controller_config": "robomodel.control.config",
    "ConfigError": "robomodel.control.exceptions",
    "ControlError": "robomodel.control.exceptions",
    "ControllerStateError": "robomodel.control.exceptions",
    "UnknownControllerError": "robomodel.control.exceptions",
    "ControllerManager": "robomodel.control.manager",
    "Strictness": "robomodel.control.manager",
    "AntiWindup": "robomodel.control.pid",
    "Gains": "robomodel.control.pid",
    "Pid": "robomodel.control.pid",
    "PidKilted": "robomodel.control.pid",
    "ControlSystem": "robomodel.control.system",
}


__getattr__, __dir__ = lazy_exports(__name__, _MODULE_OF, globals(), __all__)
