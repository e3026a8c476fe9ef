"""Links: inertial properties, visuals and collisions (URDF ``<link>``)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from robomodel.description.model.geometry import Collision, Visual
from robomodel.description.model.pose import Origin
from robomodel.description.model.raw import RawElement
from robomodel.description.model.source import SourceSpan

if TYPE_CHECKING:
    import numpy as np
    from numpy.typing import NDArray

__all__ = ["Inertia", "Inertial", "Link"]


@dataclass(frozen=True, slots=True)
class Inertia:
    """The six independent entries of a rotational inertia tensor [kg·m²]."""

    ixx: float
    ixy: float
    ixz: float
    iyy: float
    iyz: float
    izz: float

    def matrix(self) -> NDArray[np.float64]:
        """The symmetric 3x3 tensor."""
        import numpy as np  # not at the top: parsing and checking a URDF never need numpy

        m = np.array(
            [
                [self.ixx, self.ixy, self.ixz],
                [self.ixy, self.iyy, self.iyz],
                [self.ixz, self.iyz, self.izz],
            ]
        )
        m.setflags(write=False)
        return m


@dataclass(frozen=True, slots=True)
class Inertial:
    """Mass [kg] and inertia about the centre of mass, expressed in ``origin``."""

    mass_kg: float
    inertia: Inertia
    origin: Origin = Origin()
    span: SourceSpan | None = field(default=None, compare=False, repr=False)


@dataclass(frozen=True, slots=True)
class Link:
    """A rigid body of the robot."""

    name: str
    inertial: Inertial | None = None
    visuals: tuple[Visual, ...] = ()
    collisions: tuple[Collision, ...] = ()
    extra: tuple[RawElement, ...] = ()
    span: SourceSpan | None = field(default=None, compare=False, repr=False)
