"""Parsing of ``<material>``, ``<link>`` and its inertial, visuals and collisions.

urdfdom treats every link-level problem as non-fatal: it logs an error and keeps a partly
parsed link. robomodel keeps the link too, drops only the broken element, and reports a
warning with its location (``--strict`` turns these into errors).
"""

from __future__ import annotations

from collections.abc import Callable

from lxml import etree

from robomodel.description.model import (
    Box,
    Capsule,
    Collision,
    Cylinder,
    Geometry,
    Inertia,
    Inertial,
    Link,
    Material,
    Mesh,
    RawElement,
    Sphere,
    Visual,
)
from robomodel.description.urdf.context import ElementError, ParseContext, local_tag

__all__ = ["read_link", "read_material"]

_INERTIA_KEYS = tuple(
    (key, f"Inertial: inertia element {key}") for key in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
)
_LINK_CHILDREN = frozenset({"inertial", "visual", "collision"})


def raw(ctx: ParseContext, element: etree._Element) -> RawElement:
    """Keep an uninterpreted element verbatim."""
    xml = etree.tostring(element, encoding="unicode", with_tail=False)
    return RawElement(local_tag(element), xml, ctx.span(element))


def read_material(
    ctx: ParseContext, element: etree._Element, *, only_name_is_ok: bool
) -> Material | None:
    """Parse a material (``parseMaterial``). Returns None when it defines nothing usable."""
    name = element.get("name")
    if name is None:
        raise ElementError("Material must contain a name attribute", element)
    rgba: tuple[float, float, float, float] | None = None
    texture: str | None = None
    has_color = False
    for child in element:
        tag = child.tag
        if tag == "texture" and texture is None:
            texture = child.get("filename")
        elif tag == "color" and not has_color and child.get("rgba") is not None:
            has_color = True
            rgba = _read_rgba(ctx, child, name)
    if rgba is None and texture is None and not has_color:
        if not only_name_is_ok:
            ctx.error(
                f"Material [{name}] color has no rgba and no texture; give "
                '<color rgba="r g b a"/> with values in [0, 1], or <texture filename="..."/>',
                element,
                "material-empty",
            )
        return Material(name, None, None, ctx.span(element)) if only_name_is_ok else None
    return Material(name, rgba, texture, ctx.span(element))


def _read_rgba(
    ctx: ParseContext, element: etree._Element, name: str
) -> tuple[float, float, float, float] | None:
    text = element.get("rgba") or ""
    values = []
    for piece in text.split(" "):
        if not piece:
            continue
        try:
            value = ctx.number(piece, "rgba component", element)
        except ElementError:
            value = -1.0
        if not 0.0 <= value <= 1.0:
            ctx.error(
                f"Material [{name}] has malformed color rgba values: component [{piece}] is "
                "not a number in [0, 1]; the colour is ignored",
                element,
                "material-rgba",
            )
            return None
        values.append(value)
    if len(values) != 4:
        ctx.warn(
            f"Material [{name}] rgba has {len(values)} values, 4 expected (r g b a in [0, 1]); "
            "urdfdom silently uses black",
            element,
            "material-rgba",
        )
        return None
    return (values[0], values[1], values[2], values[3])


def _read_geometry(
    ctx: ParseContext, element: etree._Element | None, owner: etree._Element
) -> Geometry:
    if element is None:
        raise ElementError("visual or collision has no <geometry> element", owner)
    shape = next((c for c in element if isinstance(c.tag, str)), None)
    if shape is None:
        raise ElementError(
            "Geometry tag contains no child element; expected one of box, cylinder, sphere, "
            "mesh" + (", capsule" if ctx.at_least(1, 1) else ""),
            element,
        )
    kind = local_tag(shape)
    reader = _SHAPE_READERS.get(kind)
    if reader is None:
        raise ElementError(
            f"Unknown geometry type '{kind}'; expected box, cylinder, sphere, mesh"
            + (" or capsule" if ctx.at_least(1, 1) else ""),
            shape,
        )
    geometry = reader(ctx, shape)
    if ctx.at_least(1, 2):
        _check_positive(geometry, shape)
    return geometry


def _read_box(ctx: ParseContext, shape: etree._Element) -> Geometry:
    size = shape.get("size")
    if size is None:
        raise ElementError('Box shape has no size attribute; expected size="x y z"', shape)
    x, y, z = ctx.vector(size, shape)
    return Box((x, y, z))


def _radius_and_length(ctx: ParseContext, shape: etree._Element, kind: str) -> tuple[float, float]:
    """A cylinder's or capsule's radius and length [m], both required."""
    length, radius = shape.get("length"), shape.get("radius")
    if length is None or radius is None:
        raise ElementError(f"{kind} shape must have both length and radius attributes", shape)
    return ctx.number(radius, "radius", shape), ctx.number(length, "length", shape)


def _read_cylinder(ctx: ParseContext, shape: etree._Element) -> Geometry:
    return Cylinder(*_radius_and_length(ctx, shape, "Cylinder"))


def _read_capsule(ctx: ParseContext, shape: etree._Element) -> Geometry:
    """A capsule, which URDF 1.1 introduced (urdfdom ignores it in older documents)."""
    if not ctx.at_least(1, 1):
        raise ElementError(
            "Ignoring capsule attribute minimum required version URDF version 1.1 since "
            f'specified version is {ctx.version[0]}.{ctx.version[1]}; set version="1.1" on '
            "<robot>",
            shape,
        )
    return Capsule(*_radius_and_length(ctx, shape, "Capsule"))


def _read_sphere(ctx: ParseContext, shape: etree._Element) -> Geometry:
    radius = shape.get("radius")
    if radius is None:
        raise ElementError("Sphere shape must have a radius attribute", shape)
    return Sphere(ctx.number(radius, "radius", shape))


def _read_mesh(ctx: ParseContext, shape: etree._Element) -> Geometry:
    filename = shape.get("filename")
    if filename is None:
        raise ElementError("Mesh must contain a filename attribute", shape)
    scale_text = shape.get("scale")
    if scale_text is None:
        return Mesh(filename, None)
    try:
        sx, sy, sz = ctx.vector(scale_text, shape)
    except ElementError as exc:
        raise ElementError(
            f"Mesh scale was specified, but could not be parsed: {exc.message}", shape
        ) from None
    return Mesh(filename, (sx, sy, sz))


_SHAPE_READERS: dict[str, Callable[[ParseContext, etree._Element], Geometry]] = {
    "box": _read_box,
    "cylinder": _read_cylinder,
    "sphere": _read_sphere,
    "mesh": _read_mesh,
    "capsule": _read_capsule,
}


def _check_positive(geometry: Geometry, shape: etree._Element) -> None:
    """URDF 1.2's geometry sanity checks (non-fatal in urdfdom 6)."""
    bad = (
        (isinstance(geometry, Sphere) and geometry.radius_m <= 0)
        or (isinstance(geometry, Box) and min(geometry.size_m) <= 0)
        or (
            isinstance(geometry, (Cylinder, Capsule))
            and min(geometry.radius_m, geometry.length_m) <= 0
        )
    )
    if bad:
        kind = type(geometry).__name__
        raise ElementError(f"{kind} dimensions must be positive finite values", shape)


def _first_children(element: etree._Element) -> dict[str, etree._Element]:
    first: dict[str, etree._Element] = {}
    for child in element:
        tag = child.tag
        if isinstance(tag, str) and tag not in first:
            first[tag] = child
    return first


def _read_visual(ctx: ParseContext, element: etree._Element) -> Visual:
    first = _first_children(element)
    origin = ctx.origin(first.get("origin"))
    geometry = _read_geometry(ctx, first.get("geometry"), element)
    material = None
    mat = first.get("material")
    if mat is not None:
        if mat.get("name") is None:
            raise ElementError("Visual material must contain a name attribute", mat)
        material = read_material(ctx, mat, only_name_is_ok=True)
    return Visual(geometry, origin, element.get("name"), material, ctx.span(element))


def _read_collision(ctx: ParseContext, element: etree._Element) -> Collision:
    first = _first_children(element)
    origin = ctx.origin(first.get("origin"))
    geometry = _read_geometry(ctx, first.get("geometry"), element)
    return Collision(geometry, origin, element.get("name"), ctx.span(element))


def _read_inertial(ctx: ParseContext, element: etree._Element) -> Inertial:
    first = _first_children(element)
    origin = ctx.origin(first.get("origin"))
    mass_el = first.get("mass")
    if mass_el is None:
        raise ElementError("Inertial element must have a mass element", element)
    mass_text = mass_el.get("value")
    if mass_text is None:
        raise ElementError("Inertial: mass element must have value attribute", mass_el)
    mass = ctx.number(mass_text, "Inertial: mass", mass_el)
    inertia_el = first.get("inertia")
    if inertia_el is None:
        raise ElementError("Inertial element must have inertia element", element)
    values = []
    number = ctx.number
    get = inertia_el.get
    for key, what in _INERTIA_KEYS:
        text = get(key)
        if text is None:
            raise ElementError(
                f"Inertial: inertia element missing {key} attribute; <inertia> needs ixx ixy "
                "ixz iyy iyz izz",
                inertia_el,
            )
        values.append(number(text, what, inertia_el))
    return Inertial(mass, Inertia(*values), origin, ctx.span(element))


def read_link(ctx: ParseContext, element: etree._Element) -> Link:
    """Parse a ``<link>``; broken sub-elements are dropped with a warning."""
    name = element.get("name")
    if name is None:
        ctx.error("No name given for the link; urdfdom names it ''", element, "link-name")
        name = ""
    inertial = None
    visuals: list[Visual] = []
    collisions: list[Collision] = []
    extra: list[RawElement] = []
    for child in element:
        tag = child.tag
        if not isinstance(tag, str):
            continue
        try:
            if tag == "inertial":
                if inertial is None:
                    inertial = _read_inertial(ctx, child)
            elif tag == "visual":
                visuals.append(_read_visual(ctx, child))
            elif tag == "collision":
                collisions.append(_read_collision(ctx, child))
            else:
                extra.append(raw(ctx, child))
        except ElementError as exc:
            ctx.error(
                f"{exc.message} (in {tag} of link [{name}]; the {tag} is ignored, as urdfdom does)",
                exc.element if exc.element is not None else child,
                f"link-{tag}",
            )
    return Link(name, inertial, tuple(visuals), tuple(collisions), tuple(extra), ctx.span(element))
