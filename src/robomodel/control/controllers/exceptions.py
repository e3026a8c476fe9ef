"""Errors of the controllers."""

from __future__ import annotations

from robomodel.control.exceptions import ControlError
from robomodel.errors import close_matches

__all__ = ["ControllerError", "UnknownControllerTypeError"]


class ControllerError(ControlError):
    """A controller that cannot be initialised, configured or activated (bad parameters, ...)."""


class UnknownControllerTypeError(ControllerError):
    """A ``type:`` that no controller implements; lists the known types."""

    def __init__(self, type_name: str, known: tuple[str, ...], where: str = "") -> None:
        self.type_name = type_name
        self.known = known
        hint = close_matches(type_name, known)
        msg = f"{where + ': ' if where else ''}unknown controller type '{type_name}'"
        if hint:
            msg += f" (did you mean {', '.join(repr(h) for h in hint)}?)"
        msg += f"; known types: {', '.join(known)}"
        super().__init__(msg)
