"""Errors of the hardware layer."""

from __future__ import annotations

from robomodel.control.exceptions import ControlError
from robomodel.errors import describe_unknown

__all__ = ["HardwareError", "InterfaceClaimedError", "UnknownInterfaceError"]


class HardwareError(ControlError):
    """A hardware component that cannot be built or run."""


class UnknownInterfaceError(HardwareError, KeyError):
    """An interface name that no hardware component exports."""

    def __init__(self, kind: str, name: str, available: tuple[str, ...]) -> None:
        self.kind = kind
        self.name = name
        self.available = available
        super().__init__(
            describe_unknown(f"no {kind} interface", name, available, f"{kind} interfaces are")
        )

    def __str__(self) -> str:
        return str(self.args[0])


class InterfaceClaimedError(HardwareError):
    """A command interface that another controller already owns (claiming is exclusive)."""

    def __init__(self, name: str, owner: str) -> None:
        self.name = name
        self.owner = owner
        super().__init__(
            f"command interface '{name}' is already claimed by controller '{owner}'; "
            "deactivate that controller first (or switch both in one request)"
        )
