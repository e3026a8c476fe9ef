"""Errors of the simulator: a model that cannot be simulated, a world that does not parse."""

from __future__ import annotations

from robomodel.errors import RobomodelError

__all__ = ["DivergenceError", "SimulationError", "WorldError"]


class SimulationError(RobomodelError):
    """The robot or the scene cannot be simulated (bad inertia, missing mesh, bad command).

    Attributes:
        where: ``file:line`` of the offending element, or ``""``.
        name: The link, joint or sensor concerned, or ``""``.
    """

    def __init__(self, message: str, *, where: str = "", name: str = "") -> None:
        self.where = where
        self.name = name
        super().__init__(f"{where}: {message}" if where else message)


class DivergenceError(SimulationError):
    """The physics produced NaN or infinite states; ``name`` is the body or joint that diverged."""


class WorldError(SimulationError):
    """A world (SDF) file that does not parse or uses unsupported elements."""
