"""The hardware layer: interfaces, the resource manager, components and mock hardware."""

from robomodel.control.hardware.base import (
    ComponentInfo,
    HardwareComponent,
    HardwareInfo,
    HardwareState,
    ReturnType,
)
from robomodel.control.hardware.exceptions import (
    HardwareError,
    InterfaceClaimedError,
    UnknownInterfaceError,
)
from robomodel.control.hardware.interfaces import (
    ACCELERATION,
    EFFORT,
    POSITION,
    VELOCITY,
    InterfaceDescription,
    LoanedInterface,
    ValueTable,
)
from robomodel.control.hardware.mock import GenericSystem
from robomodel.control.hardware.resource_manager import ResourceManager
from robomodel.control.hardware.urdf import (
    HARDWARE_PLUGINS,
    hardware_from_robot,
    hardware_infos_from_robot,
    register_hardware_plugin,
)

__all__ = [
    "ACCELERATION",
    "EFFORT",
    "HARDWARE_PLUGINS",
    "POSITION",
    "VELOCITY",
    "ComponentInfo",
    "GenericSystem",
    "HardwareComponent",
    "HardwareError",
    "HardwareInfo",
    "HardwareState",
    "InterfaceClaimedError",
    "InterfaceDescription",
    "LoanedInterface",
    "ResourceManager",
    "ReturnType",
    "UnknownInterfaceError",
    "ValueTable",
    "hardware_from_robot",
    "hardware_infos_from_robot",
    "register_hardware_plugin",
]
