"""The controller interface (ros2_control ``controller_interface::ControllerInterface``).

The controller manager owns the lifecycle and the loop; a controller implements small hooks:
:meth:`~ControllerInterface.on_init` (read parameters), :meth:`~ControllerInterface.on_configure`
(create topics), :meth:`~ControllerInterface.on_activate` (interfaces are assigned: resolve
them), :meth:`~ControllerInterface.on_deactivate`, :meth:`~ControllerInterface.on_cleanup`, and
:meth:`~ControllerInterface.update` called every cycle while active. Interfaces are declared by
:meth:`~ControllerInterface.command_interface_configuration` and
:meth:`~ControllerInterface.state_interface_configuration`.
"""

from __future__ import annotations

import enum
from abc import ABC, abstractmethod
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

from robomodel.control.controllers.exceptions import ControllerError
from robomodel.control.hardware.base import ReturnType
from robomodel.control.hardware.interfaces import LoanedInterface

if TYPE_CHECKING:
    from robomodel.description.model import Robot
    from robomodel.runtime.node import Node

__all__ = [
    "ControllerInterface",
    "ControllerState",
    "InterfaceConfiguration",
    "InterfaceSelection",
    "ReturnType",
]

_MISSING = object()


class ControllerState(enum.Enum):
    """Lifecycle primary states (controller_manager_msgs/ControllerState strings)."""

    UNCONFIGURED = "unconfigured"
    INACTIVE = "inactive"
    ACTIVE = "active"
    FINALIZED = "finalized"


class InterfaceSelection(enum.Enum):
    """controller_interface ``interface_configuration_type``."""

    ALL = "all"
    INDIVIDUAL = "individual"
    NONE = "none"


@dataclass(frozen=True, slots=True)
class InterfaceConfiguration:
    """Which interfaces a controller needs: all, none, or an ordered list of full names."""

    selection: InterfaceSelection
    names: tuple[str, ...] = ()

    @classmethod
    def individual(cls, names: Sequence[str]) -> InterfaceConfiguration:
        return cls(InterfaceSelection.INDIVIDUAL, tuple(names))

    @classmethod
    def all(cls) -> InterfaceConfiguration:
        return cls(InterfaceSelection.ALL)

    @classmethod
    def none(cls) -> InterfaceConfiguration:
        return cls(InterfaceSelection.NONE)


class ControllerInterface(ABC):
    """Base of every controller (see the module docstring).

    Attributes set by the manager before :meth:`on_init`: ``name``, ``params`` (flattened dotted
    keys: ``pid.p``, ``linear.x.max_velocity``), ``node`` (this controller's node, named after
    it; ``None`` when run without a bus), ``robot`` (the description, if known),
    ``update_rate_hz``. At activation ``command_interfaces`` and ``state_interfaces`` hold the
    loaned interfaces in the order the configuration listed them.
    """

    type_name: ClassVar[str] = ""

    def __init__(self) -> None:
        self.name = ""
        self.params: dict[str, Any] = {}
        self.node: Node | None = None
        self.robot: Robot | None = None
        self.update_rate_hz = 0
        self.state = ControllerState.UNCONFIGURED
        self.command_interfaces: list[LoanedInterface] = []
        self.state_interfaces: list[LoanedInterface] = []

    # -- parameters -----------------------------------------------------------------------------
    def param(self, name: str, default: Any = _MISSING) -> Any:
        """The parameter ``name``; without ``default`` a missing one is an error."""
        if name in self.params:
            return self.params[name]
        if default is _MISSING:
            raise ControllerError(f"controller '{self.name}': parameter '{name}' is required")
        return default

    def param_float(self, name: str, default: float | None = None) -> float:
        value = self.param(name) if default is None else self.param(name, default)
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ControllerError(
                f"controller '{self.name}': parameter '{name}' must be a number, got {value!r}"
            )
        return float(value)

    def param_list(self, name: str, default: Sequence[str] | None = None) -> list[str]:
        value = self.param(name) if default is None else self.param(name, list(default))
        if isinstance(value, str):
            return [value]
        if not isinstance(value, (list, tuple)):
            raise ControllerError(
                f"controller '{self.name}': parameter '{name}' must be a list, got {value!r}"
            )
        return [str(v) for v in value]

    # -- driven by the manager ------------------------------------------------------------------
    def init(
        self,
        name: str,
        params: Mapping[str, Any],
        *,
        node: Node | None = None,
        robot: Robot | None = None,
        update_rate_hz: int = 100,
    ) -> None:
        self.name = name
        self.params = dict(params)
        self.node = node
        self.robot = robot
        self.update_rate_hz = update_rate_hz
        self.on_init()

    def assign_interfaces(
        self, commands: list[LoanedInterface], states: list[LoanedInterface]
    ) -> None:
        self.command_interfaces = commands
        self.state_interfaces = states

    def release_interfaces(self) -> None:
        self.command_interfaces = []
        self.state_interfaces = []

    # -- hooks ------------------------------------------------------------------------------------
    def on_init(self) -> None:  # noqa: B027
        """Read and check parameters (raise :class:`ControllerError` to refuse)."""

    def on_configure(self) -> None:  # noqa: B027
        """Create publishers and subscriptions; parameters may be re-read."""

    def on_activate(self) -> None:  # noqa: B027
        """Interfaces are assigned: resolve slots, take the current state as the command."""

    def on_deactivate(self) -> None:  # noqa: B027
        """Stop commanding."""

    def on_cleanup(self) -> None:  # noqa: B027
        """Undo :meth:`on_configure`."""

    @abstractmethod
    def command_interface_configuration(self) -> InterfaceConfiguration:
        """The command interfaces to claim (exclusively)."""

    @abstractmethod
    def state_interface_configuration(self) -> InterfaceConfiguration:
        """The state interfaces to read."""

    @abstractmethod
    def update(self, time_s: float, period_s: float) -> ReturnType:
        """One control cycle; return :attr:`ReturnType.ERROR` to be deactivated."""
