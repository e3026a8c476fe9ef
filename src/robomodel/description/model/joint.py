"""Joints (URDF ``<joint>``) and their optional sub-elements."""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field

from robomodel.description.model.pose import Origin
from robomodel.description.model.raw import RawElement
from robomodel.description.model.source import SourceSpan

__all__ = [
    "Calibration",
    "Dynamics",
    "Joint",
    "JointType",
    "Limit",
    "Mimic",
    "SafetyController",
]


class JointType(enum.Enum):
    """The six URDF joint types."""

    REVOLUTE = "revolute"
    CONTINUOUS = "continuous"
    PRISMATIC = "prismatic"
    FIXED = "fixed"
    FLOATING = "floating"
    PLANAR = "planar"

    @property
    def is_movable(self) -> bool:
        return self is not JointType.FIXED


@dataclass(frozen=True, slots=True)
class Limit:
    """``<limit>``: position limits [rad or m], effort [N·m or N], velocity [rad/s or m/s].

    ``None`` means the attribute was absent; URDF 1.2 adds acceleration, deceleration and jerk.
    Use the ``*_or_default`` helpers for urdfdom's defaults.
    """

    lower: float | None = None
    upper: float | None = None
    effort: float | None = None
    velocity: float | None = None
    acceleration: float | None = None
    deceleration: float | None = None
    jerk: float | None = None

    @property
    def lower_or_default(self) -> float:
        return 0.0 if self.lower is None else self.lower

    @property
    def upper_or_default(self) -> float:
        return 0.0 if self.upper is None else self.upper

    @property
    def effort_or_inf(self) -> float:
        return math.inf if self.effort is None else self.effort

    @property
    def velocity_or_inf(self) -> float:
        return math.inf if self.velocity is None else self.velocity


@dataclass(frozen=True, slots=True)
class Dynamics:
    """``<dynamics>``: viscous damping [N·m·s/rad or N·s/m] and Coulomb friction [N·m or N]."""

    damping: float | None = None
    friction: float | None = None


@dataclass(frozen=True, slots=True)
class Mimic:
    """``<mimic>``: this joint's value is ``multiplier * q[joint] + offset``."""

    joint: str
    multiplier: float | None = None
    offset: float | None = None

    @property
    def multiplier_or_default(self) -> float:
        return 1.0 if self.multiplier is None else self.multiplier

    @property
    def offset_or_default(self) -> float:
        return 0.0 if self.offset is None else self.offset


@dataclass(frozen=True, slots=True)
class SafetyController:
    """``<safety_controller>`` (soft limits and gains of the ROS safety layer)."""

    k_velocity: float
    soft_lower_limit: float | None = None
    soft_upper_limit: float | None = None
    k_position: float | None = None


@dataclass(frozen=True, slots=True)
class Calibration:
    """``<calibration>``: reference positions of the calibration switches."""

    rising: float | None = None
    falling: float | None = None
    reference_position: float | None = None


@dataclass(frozen=True, slots=True)
class Joint:
    """A joint connecting ``parent`` to ``child``; ``origin`` is the child frame in the parent.

    ``axis`` is stored as given (not normalised), defaulting to (1, 0, 0) like urdfdom; an
    ``<axis>`` element without ``xyz`` gives (0, 0, 0), also like urdfdom.
    """

    name: str
    type: JointType
    parent: str
    child: str
    origin: Origin = Origin()
    axis: tuple[float, float, float] = (1.0, 0.0, 0.0)
    limit: Limit | None = None
    dynamics: Dynamics | None = None
    mimic: Mimic | None = None
    safety_controller: SafetyController | None = None
    calibration: Calibration | None = None
    extra: tuple[RawElement, ...] = ()
    span: SourceSpan | None = field(default=None, compare=False, repr=False)
