"""Parsing of ``<joint>`` (urdfdom's ``parseJoint``). Every joint-level problem is fatal."""

from __future__ import annotations

from lxml import etree

from robomodel.description.model import (
    Calibration,
    Dynamics,
    Joint,
    JointType,
    Limit,
    Mimic,
    RawElement,
    SafetyController,
)
from robomodel.description.urdf.context import ElementError, ParseContext
from robomodel.description.urdf.read_link import raw

__all__ = ["read_joint"]

_TYPES = {t.value: t for t in JointType}
_KNOWN = frozenset(
    {
        "origin",
        "parent",
        "child",
        "axis",
        "limit",
        "dynamics",
        "mimic",
        "safety_controller",
        "calibration",
    }
)


def _limit(ctx: ParseContext, element: etree._Element, name: str, jtype: JointType) -> Limit:
    num = ctx.optional_number
    lower = num(element, "lower", "lower value")
    upper = num(element, "upper", "upper value")
    effort = num(element, "effort", "effort value")
    velocity = num(element, "velocity", "velocity value")
    extras: dict[str, float | None] = {}
    for key in ("acceleration", "deceleration", "jerk"):
        if element.get(key) is None:
            extras[key] = None
        elif ctx.at_least(1, 2):
            extras[key] = num(element, key, f"{key} value")
        else:
            ctx.warn(
                f"joint [{name}]: Ignoring {key} attribute. Required atleast URDF version 1.2, "
                f"but the specified version is {ctx.version[0]}.{ctx.version[1]}.",
                element,
                "version-gated",
            )
            extras[key] = None
    if ctx.at_least(1, 2):
        for key, value in (("effort", effort), ("velocity", velocity), *extras.items()):
            if value is not None and value < 0:
                raise ElementError(f"joint [{name}]: {key} value ({value:g}) is negative", element)
        if jtype in (JointType.REVOLUTE, JointType.PRISMATIC):
            if lower is None or upper is None:
                raise ElementError(
                    f"joint [{name}]: revolute and prismatic joints must have both lower and "
                    "upper position limits specified in URDF version 1.2 or later",
                    element,
                )
            if upper < lower:
                raise ElementError(
                    f"joint [{name}]: upper position limit ({upper:f}) cannot be smaller than "
                    f"lower position limit ({lower:f})",
                    element,
                )
    else:
        if effort is None:
            raise ElementError(
                f"joint [{name}]: limit has no effort (joint limit: no effort)", element
            )
        if velocity is None:
            raise ElementError(
                f"joint [{name}]: limit has no velocity (joint limit: no velocity)", element
            )
    return Limit(
        lower,
        upper,
        effort,
        velocity,
        extras["acceleration"],
        extras["deceleration"],
        extras["jerk"],
    )


def _dynamics(ctx: ParseContext, element: etree._Element) -> Dynamics:
    damping = ctx.optional_number(element, "damping", "damping value")
    friction = ctx.optional_number(element, "friction", "friction value")
    if damping is None and friction is None:
        raise ElementError(
            "joint dynamics element specified with no damping and no friction; give "
            'damping="..." and/or friction="..."',
            element,
        )
    return Dynamics(damping, friction)


def _mimic(ctx: ParseContext, element: etree._Element) -> Mimic:
    target = element.get("joint")
    if target is None:
        raise ElementError('joint mimic: no mimic joint specified; give joint="NAME"', element)
    return Mimic(
        target,
        ctx.optional_number(element, "multiplier", "multiplier value"),
        ctx.optional_number(element, "offset", "offset value"),
    )


def _safety(ctx: ParseContext, element: etree._Element) -> SafetyController:
    k_velocity = ctx.optional_number(element, "k_velocity", "k_velocity value")
    if k_velocity is None:
        raise ElementError("joint safety: no k_velocity; k_velocity is required", element)
    return SafetyController(
        k_velocity,
        ctx.optional_number(element, "soft_lower_limit", "soft_lower_limit value"),
        ctx.optional_number(element, "soft_upper_limit", "soft_upper_limit value"),
        ctx.optional_number(element, "k_position", "k_position value"),
    )


def _calibration(ctx: ParseContext, element: etree._Element) -> Calibration:
    return Calibration(
        ctx.optional_number(element, "rising", "rising value"),
        ctx.optional_number(element, "falling", "falling value"),
        ctx.optional_number(element, "reference_position", "reference_position value"),
    )


def read_joint(ctx: ParseContext, element: etree._Element) -> Joint:
    """Parse a ``<joint>``; any problem raises the fatal error urdfdom would."""
    name = element.get("name")
    if name is None:
        ctx.fatal('unnamed joint found; every <joint> needs name="..."', element, "joint-name")
    try:
        return _read_joint(ctx, element, name)
    except ElementError as exc:
        ctx.fatal(exc.message, exc.element if exc.element is not None else element, "joint")


def _split_children(
    ctx: ParseContext, element: etree._Element
) -> tuple[dict[str, etree._Element], tuple[RawElement, ...]]:
    """The first child of each known tag (urdfdom reads only the first), and the unknown
    children kept raw so that a write gives them back."""
    first: dict[str, etree._Element] = {}
    extra: list[RawElement] = []
    for child in element:
        tag = child.tag
        if not isinstance(tag, str):
            continue
        if tag in _KNOWN:
            first.setdefault(tag, child)
        else:
            extra.append(raw(ctx, child))
    return first, tuple(extra)


def _joint_type(element: etree._Element, name: str) -> JointType:
    """The joint's ``type`` attribute, which must be one of :class:`JointType`'s values."""
    type_text = element.get("type")
    if type_text is None:
        raise ElementError(
            f"joint [{name}] has no type, check to see if it's a reference.", element
        )
    jtype = _TYPES.get(type_text)
    if jtype is None:
        raise ElementError(
            f"Joint [{name}] has no known type [{type_text}]; valid types are " + ", ".join(_TYPES),
            element,
        )
    return jtype


def _axis(
    ctx: ParseContext, axis_el: etree._Element | None, name: str, jtype: JointType
) -> tuple[float, float, float]:
    """The joint axis: x when ``<axis>`` is absent, zero when it has no ``xyz`` (as urdfdom)."""
    if axis_el is None:
        return (1.0, 0.0, 0.0)
    xyz = axis_el.get("xyz")
    if xyz is None:
        return (0.0, 0.0, 0.0)
    try:
        ax, ay, az = ctx.vector(xyz, axis_el)
    except ElementError as exc:
        if jtype not in (JointType.FIXED, JointType.FLOATING):
            raise ElementError(
                f"Malformed axis element for joint [{name}]: {exc.message}", axis_el
            ) from None
        # urdfdom never reads the axis of fixed and floating joints.
        ctx.warn(
            f"ignoring malformed axis of {jtype.value} joint [{name}]: {exc.message}",
            axis_el,
            "axis",
        )
        return (1.0, 0.0, 0.0)
    return (ax, ay, az)


def _joint_limit(
    ctx: ParseContext,
    limit_el: etree._Element | None,
    element: etree._Element,
    name: str,
    jtype: JointType,
) -> Limit | None:
    """The ``<limit>``, which revolute and prismatic joints must have."""
    if limit_el is not None:
        return _limit(ctx, limit_el, name, jtype)
    if jtype is JointType.REVOLUTE:
        raise ElementError(
            f"Joint [{name}] is of type REVOLUTE but it does not specify limits; add "
            '<limit lower="..." upper="..." effort="..." velocity="..."/>',
            element,
        )
    if jtype is JointType.PRISMATIC:
        raise ElementError(
            f"Joint [{name}] is of type PRISMATIC without limits; add "
            '<limit lower="..." upper="..." effort="..." velocity="..."/>',
            element,
        )
    return None


def _read_joint(ctx: ParseContext, element: etree._Element, name: str) -> Joint:
    first, extra = _split_children(ctx, element)
    try:
        origin = ctx.origin(first.get("origin"))
    except ElementError as exc:
        raise ElementError(
            f"Malformed parent origin element for joint [{name}]: {exc.message}", exc.element
        ) from None
    parent = first["parent"].get("link", "") if "parent" in first else ""
    child = first["child"].get("link", "") if "child" in first else ""
    jtype = _joint_type(element, name)
    axis = _axis(ctx, first.get("axis"), name, jtype)
    limit = _joint_limit(ctx, first.get("limit"), element, name, jtype)
    safety = _safety(ctx, first["safety_controller"]) if "safety_controller" in first else None
    calibration = _calibration(ctx, first["calibration"]) if "calibration" in first else None
    mimic = _mimic(ctx, first["mimic"]) if "mimic" in first else None
    dynamics = _dynamics(ctx, first["dynamics"]) if "dynamics" in first else None
    return Joint(
        name,
        jtype,
        parent,
        child,
        origin,
        axis,
        limit,
        dynamics,
        mimic,
        safety,
        calibration,
        extra,
        ctx.span(element),
    )
