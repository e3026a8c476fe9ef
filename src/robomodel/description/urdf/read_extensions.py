"""Parsing of ``<transmission>``, ``<gazebo>`` and ``<ros2_control>`` blocks.

urdfdom ignores all three; robomodel interprets them for the control and simulation layers.
Problems here are reported as warnings and the block is kept verbatim instead.
"""

from __future__ import annotations

from lxml import etree

from robomodel.description.model import (
    ComponentInterfaces,
    GazeboBlock,
    Interface,
    RawElement,
    Ros2Control,
    Transmission,
    TransmissionActuator,
    TransmissionJoint,
    TransmissionStyle,
)
from robomodel.description.urdf.context import ElementError, ParseContext, local_tag
from robomodel.description.urdf.read_link import raw

__all__ = ["read_gazebo", "read_ros2_control", "read_transmission"]


def _text(element: etree._Element | None) -> str | None:
    if element is None:
        return None
    return (element.text or "").strip()


_SIDE_TAGS = frozenset(
    ("role", "hardwareInterface", "hardware_interface", "mechanicalReduction",
     "mechanical_reduction", "offset")
)  # fmt: skip
_INTERFACE_TAGS = ("hardwareInterface", "hardware_interface")
_REDUCTION_TAGS = ("mechanicalReduction", "mechanical_reduction")


def _side(
    ctx: ParseContext, element: etree._Element
) -> tuple[str, str | None, tuple[str, ...], float | None, float | None, tuple[RawElement, ...]]:
    name = element.get("name")
    if name is None:
        raise ElementError("transmission joint/actuator needs a name attribute", element)
    # One pass over the children (``find`` compiles a path per call): the first <role>, the
    # first <mechanicalReduction> (else <mechanical_reduction>), the first <offset>.
    first: dict[str, etree._Element] = {}
    interfaces: list[str] = []
    extra: list[RawElement] = []
    for child in element:
        tag = child.tag
        if not isinstance(tag, str):
            continue
        if tag in _SIDE_TAGS:
            if tag in _INTERFACE_TAGS:
                interfaces.append(_text(child) or "")
            elif tag not in first:
                first[tag] = child
        else:
            extra.append(raw(ctx, child))
    role = element.get("role")
    if role is None:
        role = _text(first.get("role"))
    reduction = None
    for tag in _REDUCTION_TAGS:
        child = first.get(tag)
        if child is not None:
            reduction = ctx.number(_text(child) or "", tag, child)
            break
    offset_el = first.get("offset")
    offset = None if offset_el is None else ctx.number(_text(offset_el) or "", "offset", offset_el)
    return name, role, tuple(interfaces), reduction, offset, tuple(extra)


def read_transmission(ctx: ParseContext, element: etree._Element) -> Transmission:
    """Parse a transmission in the ROS 1 (``<type>``) or ROS 2 (``<plugin>``) form."""
    name = element.get("name")
    if name is None:
        raise ElementError("transmission needs a name attribute", element)
    type_el = plugin_el = None
    for child in element:
        tag = child.tag
        if tag == "type" and type_el is None:
            type_el = child
        elif tag == "plugin" and plugin_el is None:
            plugin_el = child
    if plugin_el is not None:
        style, kind = TransmissionStyle.ROS2, _text(plugin_el)
    elif type_el is not None:
        style, kind = TransmissionStyle.ROS1, _text(type_el)
    elif element.get("type") is not None:
        style, kind = TransmissionStyle.ROS1_TYPE_ATTRIBUTE, element.get("type")
    else:
        raise ElementError(
            f"transmission [{name}] has no type; give <type>transmission_interface/"
            "SimpleTransmission</type> (ROS 1) or <plugin>...</plugin> (ROS 2)",
            element,
        )
    joints: list[TransmissionJoint] = []
    actuators: list[TransmissionActuator] = []
    extra: list[RawElement] = []
    reduction = None
    for child in element:
        tag = child.tag
        if not isinstance(tag, str) or tag in ("type", "plugin"):
            continue
        if tag == "joint":
            joints.append(TransmissionJoint(*_side(ctx, child)))
        elif tag == "actuator":
            actuators.append(TransmissionActuator(*_side(ctx, child)))
        elif tag in ("mechanicalReduction", "mechanical_reduction") and reduction is None:
            reduction = ctx.number(_text(child) or "", tag, child)
        else:
            extra.append(raw(ctx, child))
    return Transmission(
        name,
        kind or "",
        style,
        tuple(joints),
        tuple(actuators),
        reduction,
        tuple(extra),
        ctx.span(element),
    )


def read_gazebo(ctx: ParseContext, element: etree._Element) -> GazeboBlock:
    """Keep a ``<gazebo>`` block verbatim with its ``reference``."""
    xml = etree.tostring(element, encoding="unicode", with_tail=False)
    return GazeboBlock(element.get("reference"), xml, ctx.span(element))


def _params(element: etree._Element) -> tuple[tuple[str, str], ...]:
    return tuple((p.get("name", ""), (p.text or "").strip()) for p in element if p.tag == "param")


def _interface(element: etree._Element) -> Interface:
    name = element.get("name")
    if name is None:
        raise ElementError("ros2_control interface needs a name attribute", element)
    size_text = element.get("size")
    try:
        size = None if size_text is None else int(size_text)
    except ValueError:
        raise ElementError(f"interface size [{size_text}] is not an integer", element) from None
    return Interface(name, _params(element), element.get("data_type"), size)


def _component(element: etree._Element) -> ComponentInterfaces:
    name = element.get("name")
    if name is None:
        raise ElementError(f"ros2_control <{element.tag}> needs a name attribute", element)
    commands = tuple(_interface(c) for c in element if c.tag == "command_interface")
    states = tuple(_interface(c) for c in element if c.tag == "state_interface")
    attributes = tuple((k, v) for k, v in element.attrib.items() if k != "name")
    return ComponentInterfaces(name, commands, states, _params(element), attributes)


def read_ros2_control(ctx: ParseContext, element: etree._Element) -> Ros2Control:
    """Parse a ``<ros2_control name type>`` block (hardware, joints, sensors, gpios)."""
    name = element.get("name")
    kind = element.get("type")
    if name is None or kind is None:
        raise ElementError(
            '<ros2_control> needs name="..." and type="system|actuator|sensor"', element
        )
    plugin = None
    hw_params: tuple[tuple[str, str], ...] = ()
    joints: list[ComponentInterfaces] = []
    sensors: list[ComponentInterfaces] = []
    gpios: list[ComponentInterfaces] = []
    transmissions: list[Transmission] = []
    extra: list[RawElement] = []
    for child in element:
        tag = child.tag
        if not isinstance(tag, str):
            continue
        if tag == "hardware":
            plugin = _text(child.find("plugin"))
            hw_params = _params(child)
        elif tag == "joint":
            joints.append(_component(child))
        elif tag == "sensor":
            sensors.append(_component(child))
        elif tag == "gpio":
            gpios.append(_component(child))
        elif tag == "transmission":
            transmissions.append(read_transmission(ctx, child))
        else:
            extra.append(raw(ctx, child))
    attributes = tuple((k, v) for k, v in element.attrib.items() if k not in ("name", "type"))
    return Ros2Control(
        name,
        kind,
        plugin,
        hw_params,
        tuple(joints),
        tuple(sensors),
        tuple(gpios),
        tuple(transmissions),
        attributes,
        tuple(extra),
        ctx.span(element),
    )


def tag_of(element: etree._Element) -> str:
    return local_tag(element)
