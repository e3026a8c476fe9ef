"""Errors of the kinematics layer."""

from __future__ import annotations

from collections.abc import Sequence

from robomodel.description.model import UnknownNameError
from robomodel.errors import RobomodelError

__all__ = [
    "ConfigurationError",
    "KinematicsError",
    "KinematicsWarning",
    "MimicCycleError",
    "UnknownNameError",
    "UnreachableError",
    "ZeroAxisError",
]


class KinematicsError(RobomodelError):
    """A robot model cannot be compiled for kinematics, or a request cannot be served."""


class KinematicsWarning(UserWarning):
    """A model quirk that kinematics works around (e.g. a mimic of a missing joint)."""


class ZeroAxisError(KinematicsError):
    """A movable joint has a zero-length axis, so it has no direction to move in."""

    def __init__(self, joint: str) -> None:
        self.joint = joint
        super().__init__(f"joint '{joint}' has a zero axis; give <axis xyz=...> a nonzero vector")


class MimicCycleError(KinematicsError):
    """Mimic joints follow each other in a loop, so none of them has a value."""

    def __init__(self, cycle: Sequence[str]) -> None:
        self.cycle = tuple(cycle)
        super().__init__("mimic joints form a cycle: " + " -> ".join([*self.cycle, self.cycle[0]]))


class ConfigurationError(KinematicsError, ValueError):
    """A joint configuration ``q`` has the wrong shape or contains NaN/inf."""


class UnreachableError(KinematicsError):
    """IK found no configuration within the tolerances (the CLI exits 1 on it)."""
