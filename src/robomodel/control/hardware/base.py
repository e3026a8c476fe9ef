"""The hardware component interface (ros2_control ``hardware_interface::SystemInterface``).

A component exports state and command interfaces; the resource manager gives it slots in the
shared value tables. :meth:`HardwareComponent.read` fills its state slots from the device (or
the simulation); :meth:`HardwareComponent.write` sends its command slots. Mock hardware and the
simulator implement this interface.
"""

from __future__ import annotations

import enum
from abc import ABC, abstractmethod
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import ClassVar

from robomodel.control.hardware.interfaces import InterfaceDescription, ValueTable

__all__ = [
    "ComponentInfo",
    "HardwareComponent",
    "HardwareInfo",
    "HardwareState",
    "ReturnType",
]


class ReturnType(enum.Enum):
    """What ``read``/``write``/``update`` report (hardware_interface::return_type)."""

    OK = "ok"
    ERROR = "error"
    DEACTIVATE = "deactivate"


class HardwareState(enum.Enum):
    """Lifecycle of a hardware component (lifecycle_of_a_hardware_component.rst)."""

    UNCONFIGURED = "unconfigured"
    INACTIVE = "inactive"
    ACTIVE = "active"
    FINALIZED = "finalized"


@dataclass(frozen=True, slots=True)
class ComponentInfo:
    """A ``<joint>``, ``<sensor>`` or ``<gpio>`` of a hardware component."""

    name: str
    command_interfaces: tuple[InterfaceDescription, ...] = ()
    state_interfaces: tuple[InterfaceDescription, ...] = ()
    params: tuple[tuple[str, str], ...] = ()


@dataclass(frozen=True, slots=True)
class HardwareInfo:
    """Everything a hardware component is built from (one ``<ros2_control>`` block).

    Attributes:
        name: The block's ``name``.
        type: ``system``, ``actuator`` or ``sensor``.
        plugin: ``mock_components/GenericSystem``, ...
        params: ``<hardware><param>`` values (strings, as in ros2_control).
        source: ``file:line`` of the block, for messages.
    """

    name: str
    type: str = "system"
    plugin: str = "mock_components/GenericSystem"
    params: Mapping[str, str] = field(default_factory=dict)
    joints: tuple[ComponentInfo, ...] = ()
    sensors: tuple[ComponentInfo, ...] = ()
    gpios: tuple[ComponentInfo, ...] = ()
    source: str = ""


class HardwareComponent(ABC):
    """Base of every hardware component.

    Subclasses implement :meth:`read` and :meth:`write` (and may override the lifecycle hooks
    and the command-mode switch). After :meth:`bind`, ``self.states`` and ``self.commands``
    are the shared value lists and :meth:`state_slot`/:meth:`command_slot` give slot numbers.
    """

    plugin_name: ClassVar[str] = ""

    def __init__(self, info: HardwareInfo) -> None:
        self.info = info
        self.name = info.name
        self.state = HardwareState.UNCONFIGURED
        self.states: list[float] = []
        self.commands: list[float] = []
        self._state_slots: dict[str, int] = {}
        self._command_slots: dict[str, int] = {}

    # -- exported interfaces ----------------------------------------------------------------
    def export_state_interfaces(self) -> list[InterfaceDescription]:
        """State interfaces of all joints, sensors and GPIOs, in URDF order."""
        items = (*self.info.joints, *self.info.sensors, *self.info.gpios)
        return [d for c in items for d in c.state_interfaces]

    def export_command_interfaces(self) -> list[InterfaceDescription]:
        """Command interfaces of all joints and GPIOs, in URDF order."""
        items = (*self.info.joints, *self.info.sensors, *self.info.gpios)
        return [d for c in items for d in c.command_interfaces]

    def bind(self, states: ValueTable, commands: ValueTable) -> None:
        """Register this component's interfaces in the shared tables (the resource manager)."""
        self.states = states.values
        self.commands = commands.values
        for d in self.export_state_interfaces():
            init = d.initial_value
            self._state_slots[d.name] = states.add(
                d.name, init if init is not None else _nan_for(d)
            )
        for d in self.export_command_interfaces():
            init = d.initial_value
            self._command_slots[d.name] = commands.add(
                d.name, init if init is not None else _nan_for(d)
            )

    def state_slot(self, name: str) -> int:
        return self._state_slots[name]

    def command_slot(self, name: str) -> int:
        return self._command_slots[name]

    def has_state(self, name: str) -> bool:
        return name in self._state_slots

    def has_command(self, name: str) -> bool:
        return name in self._command_slots

    @property
    def command_interface_names(self) -> tuple[str, ...]:
        return tuple(self._command_slots)

    @property
    def state_interface_names(self) -> tuple[str, ...]:
        return tuple(self._state_slots)

    # -- lifecycle hooks (override as needed) -------------------------------------------------
    def on_configure(self) -> None:  # noqa: B027
        """Called on unconfigured -> inactive; state interfaces become readable."""

    def on_activate(self) -> None:  # noqa: B027
        """Called on inactive -> active; command interfaces become available."""

    def on_deactivate(self) -> None:  # noqa: B027
        """Called on active -> inactive."""

    def prepare_command_mode_switch(self, start: Sequence[str], stop: Sequence[str]) -> bool:
        """Accept (True) or veto (False) a change of the claimed command interfaces."""
        return True

    def perform_command_mode_switch(self, start: Sequence[str], stop: Sequence[str]) -> None:  # noqa: B027
        """Apply a change of the claimed command interfaces (called in the loop)."""

    # -- the loop ---------------------------------------------------------------------------
    @abstractmethod
    def read(self, time_s: float, period_s: float) -> ReturnType:
        """Update the state slots."""

    @abstractmethod
    def write(self, time_s: float, period_s: float) -> ReturnType:
        """Send the command slots."""

    # -- driven by the resource manager -------------------------------------------------------
    def configure(self) -> None:
        if self.state is HardwareState.UNCONFIGURED:
            self.on_configure()
            self.state = HardwareState.INACTIVE

    def activate(self) -> None:
        self.configure()
        if self.state is HardwareState.INACTIVE:
            self.on_activate()
            self.state = HardwareState.ACTIVE

    def deactivate(self) -> None:
        if self.state is HardwareState.ACTIVE:
            self.on_deactivate()
            self.state = HardwareState.INACTIVE


def _nan_for(d: InterfaceDescription) -> float:
    from robomodel.control.hardware.interfaces import default_value

    return default_value(d.data_type)
