"""Errors of the control layer (controller manager, configuration files)."""

from __future__ import annotations

from robomodel.errors import RobomodelError, SourceLocation, describe_unknown

__all__ = ["ConfigError", "ControlError", "ControllerStateError", "UnknownControllerError"]


class ControlError(RobomodelError):
    """Root of the control layer's errors."""


class ConfigError(ControlError):
    """A controller YAML file that cannot be used; ``location`` is file:line:column."""

    def __init__(self, message: str, location: SourceLocation | None = None) -> None:
        self.location = location
        self.message = message
        super().__init__(f"{location}: {message}" if location is not None else message)


class UnknownControllerError(ControlError, KeyError):
    """A controller name the manager does not know."""

    def __init__(self, name: str, available: tuple[str, ...]) -> None:
        self.name = name
        self.available = available
        super().__init__(
            describe_unknown("unknown controller", name, available, "loaded controllers")
        )

    def __str__(self) -> str:
        return str(self.args[0])


class ControllerStateError(ControlError):
    """A lifecycle operation that the controller's current state does not allow."""
