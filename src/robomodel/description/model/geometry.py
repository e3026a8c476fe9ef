"""Geometry, materials, visuals and collisions of a link (URDF ``<visual>``/``<collision>``)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TypeAlias

from robomodel.description.model.pose import Origin
from robomodel.description.model.source import SourceSpan

__all__ = [
    "Box",
    "Capsule",
    "Collision",
    "Cylinder",
    "Geometry",
    "Material",
    "Mesh",
    "Sphere",
    "Visual",
]

Vec3: TypeAlias = tuple[float, float, float]


@dataclass(frozen=True, slots=True)
class Box:
    """A box centred on its origin. ``size_m`` are the full side lengths [m]."""

    size_m: Vec3


@dataclass(frozen=True, slots=True)
class Cylinder:
    """A cylinder along the local z axis, centred on its origin [m]."""

    radius_m: float
    length_m: float


@dataclass(frozen=True, slots=True)
class Sphere:
    """A sphere centred on its origin [m]."""

    radius_m: float


@dataclass(frozen=True, slots=True)
class Capsule:
    """A capsule along z (URDF 1.1): ``length_m`` is the cylinder part, caps excluded [m]."""

    radius_m: float
    length_m: float


@dataclass(frozen=True, slots=True)
class Mesh:
    """A mesh file (``package://``, ``file://`` or relative), with an optional scale."""

    filename: str
    scale: Vec3 | None = None


Geometry: TypeAlias = Box | Cylinder | Sphere | Capsule | Mesh


@dataclass(frozen=True, slots=True)
class Material:
    """A material: a named reference, or an inline colour (rgba in [0, 1]) and/or texture."""

    name: str
    rgba: tuple[float, float, float, float] | None = None
    texture: str | None = None
    span: SourceSpan | None = field(default=None, compare=False, repr=False)

    @property
    def is_reference(self) -> bool:
        """True when this only names a robot-level material."""
        return self.rgba is None and self.texture is None


@dataclass(frozen=True, slots=True)
class Visual:
    """One ``<visual>`` of a link."""

    geometry: Geometry
    origin: Origin = Origin()
    name: str | None = None
    material: Material | None = None
    span: SourceSpan | None = field(default=None, compare=False, repr=False)


@dataclass(frozen=True, slots=True)
class Collision:
    """One ``<collision>`` of a link."""

    geometry: Geometry
    origin: Origin = Origin()
    name: str | None = None
    span: SourceSpan | None = field(default=None, compare=False, repr=False)
