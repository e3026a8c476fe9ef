"""The options of numerical IK, shared by :meth:`Kinematics.ik` and :meth:`Kinematics.ik_batch`.

One frozen dataclass holds every option and its one default; the methods take it as
``options=`` and also accept its fields as keyword arguments, which override it
(``kin.ik(T, link, position_only=True)`` and ``kin.ik(T, link, options=IKOptions(
position_only=True))`` are the same call).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TypedDict

from robomodel.kinematics.exceptions import KinematicsError

__all__ = ["IKOptionOverrides", "IKOptions"]


@dataclass(frozen=True, slots=True)
class IKOptions:
    """How numerical IK searches (see :mod:`robomodel.kinematics.ik` for the method).

    Attributes:
        position_only: Only reach the position; the orientation is free.
        tol_m: Position tolerance [m].
        tol_rad: Rotation tolerance [rad].
        max_iterations: Iteration budget per target over all its attempts (3000: enough for
            Panda and UR5 targets from 50 restarts of at most 60 iterations).
        max_time_s: Optional time budget over all attempts [s], checked between attempts
            (None: no time limit). :meth:`~Kinematics.ik` only: a batch has no time limit.
        restarts: Random restarts after the first attempt, at most. :meth:`~Kinematics.ik`
            only: in a batch, targets restart until ``max_iterations`` is spent.

    Raises:
        KinematicsError: an option is out of range (the message names it and what is valid).
    """

    position_only: bool = False
    tol_m: float = 1e-6
    tol_rad: float = 1e-6
    max_iterations: int = 3000
    max_time_s: float | None = None
    restarts: int = 50

    def __post_init__(self) -> None:
        if self.max_iterations < 1:
            raise KinematicsError(f"max_iterations must be at least 1, not {self.max_iterations}")
        for name, value in (("tol_m", self.tol_m), ("tol_rad", self.tol_rad)):
            if not (math.isfinite(value) and value >= 0.0):
                raise KinematicsError(f"{name} must be a finite number >= 0, not {value}")
        if self.restarts < 0:
            raise KinematicsError(f"restarts must be 0 or more, not {self.restarts}")
        if self.max_time_s is not None and not self.max_time_s > 0.0:
            raise KinematicsError(f"max_time_s must be None or > 0, not {self.max_time_s}")

    def replace(self, overrides: Mapping[str, object]) -> IKOptions:
        """These options with ``overrides`` (keyword arguments of ``ik``/``ik_batch``) applied.

        Raises:
            KinematicsError: an override names no option (the message lists the options).
        """
        if not overrides:
            return self
        names = [f.name for f in dataclasses.fields(self)]
        unknown = sorted(set(overrides) - set(names))
        if unknown:
            raise KinematicsError(
                f"unknown IK option(s) {', '.join(unknown)}; options are: {', '.join(names)}"
            )
        return dataclasses.replace(self, **overrides)  # type: ignore[arg-type]


class IKOptionOverrides(TypedDict, total=False):
    """:class:`IKOptions`' fields as keyword arguments (each overrides ``options=``)."""

    position_only: bool
    tol_m: float
    tol_rad: float
    max_iterations: int
    max_time_s: float | None
    restarts: int
