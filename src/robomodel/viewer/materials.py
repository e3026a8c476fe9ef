"""Colours of visuals: inline ``<color>``, robot-level materials by name, or a default."""

from __future__ import annotations

from robomodel.description.model import Material, Robot

__all__ = ["DEFAULT_RGBA", "material_rgba", "rgb255"]

Rgba = tuple[float, float, float, float]

# RViz draws a link without a material in a light grey.
DEFAULT_RGBA: Rgba = (0.8, 0.8, 0.8, 1.0)


def material_rgba(material: Material | None, robot: Robot) -> Rgba | None:
    """The colour a visual's material gives, or ``None`` when it names none.

    An inline ``<color>`` wins; a reference (``<material name="x"/>``) takes the robot-level
    material's colour; an unknown name or a texture-only material gives ``None``.
    """
    if material is None:
        return None
    if material.rgba is not None:
        return material.rgba
    for candidate in robot.materials:
        if candidate.name == material.name and candidate.rgba is not None:
            return candidate.rgba
    return None


def rgb255(rgba: Rgba) -> tuple[int, int, int]:
    """viser's colour format: RGB integers in [0, 255]."""
    r, g, b, _ = (min(max(c, 0.0), 1.0) for c in rgba)
    return (round(r * 255), round(g * 255), round(b * 255))
