"""Checks that a link's inertial can be simulated (refused with the link's file:line)."""

from __future__ import annotations

import math

import numpy as np

from robomodel.description.model import Link
from robomodel.sim.exceptions import SimulationError

__all__ = ["check_inertial", "where"]

# MuJoCo's mjMINVAL: below this, mass or inertia of a moving body is refused by the compiler.
_MIN_VALUE = 1e-15


def where(item: object) -> str:
    """``file:line`` of a model element (its ``span``), or ``""``."""
    span = getattr(item, "span", None)
    location = getattr(span, "location", None)
    return str(location) if location is not None else ""


def check_inertial(link: Link, *, moving: bool) -> None:
    """Refuse a non-physical ``<inertial>`` of ``link``.

    A moving link needs a positive mass and a positive-definite tensor whose principal moments
    satisfy the triangle inequality (``a + b >= c``), as every physical body does; Gazebo
    accepts such links and then explodes, MuJoCo's compiler refuses some of them without
    naming the URDF line. Links welded to the world (``moving=False``) may be massless.

    Raises:
        SimulationError: naming the link, its file:line and a fix.
    """
    inertial = link.inertial
    at = where(inertial) or where(link)
    if inertial is None:
        if moving:
            raise SimulationError(
                f"link '{link.name}' moves but has no <inertial>; add <inertial> with a "
                "positive <mass> and <inertia>",
                where=at,
                name=link.name,
            )
        return
    mass = inertial.mass_kg
    if not moving and mass == 0.0:
        return
    if not math.isfinite(mass) or mass <= _MIN_VALUE:
        raise SimulationError(
            f"link '{link.name}' has mass {mass} kg; a moving link needs a positive mass "
            '(e.g. <mass value="0.1"/>)',
            where=at,
            name=link.name,
        )
    tensor = np.asarray(inertial.inertia.matrix(), dtype=float)
    if not np.all(np.isfinite(tensor)):
        raise SimulationError(
            f"link '{link.name}' has a non-finite inertia tensor", where=at, name=link.name
        )
    moments = np.linalg.eigvalsh(tensor)
    if moments[0] <= _MIN_VALUE:
        raise SimulationError(
            f"link '{link.name}' has an inertia tensor that is not positive definite "
            f"(principal moments {_fmt(moments)} kg m^2); for a solid box of size a x b x c "
            "use ixx = m (b^2 + c^2) / 12 and likewise",
            where=at,
            name=link.name,
        )
    a, b, c = moments
    if a + b < c * (1.0 - 1e-6):
        raise SimulationError(
            f"link '{link.name}' has principal moments of inertia {_fmt(moments)} kg m^2 that "
            "violate the triangle inequality (the two smaller must add up to at least the "
            "largest), which no physical body has; recompute the inertia from the shape",
            where=at,
            name=link.name,
        )


def _fmt(values: np.ndarray) -> str:
    return "(" + ", ".join(f"{v:.3g}" for v in values) + ")"
