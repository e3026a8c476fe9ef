"""Writing the model back to URDF XML, such that ``read(write(robot)) == robot``.

Numbers are written with ``repr`` (shortest round-tripping form), unlike urdfdom's exporter,
which keeps 6 significant digits and loses precision. Raw blocks (``<gazebo>``, unknown
elements) are inserted verbatim.
"""

from __future__ import annotations

import os
from collections.abc import Iterable

from robomodel._atomic import atomic_write_text
from robomodel.description.model import (
    Box,
    Capsule,
    Collision,
    ComponentInterfaces,
    Cylinder,
    Geometry,
    Inertial,
    Interface,
    Joint,
    Link,
    Material,
    Mesh,
    Origin,
    Robot,
    Ros2Control,
    Sphere,
    Transmission,
    TransmissionStyle,
    Visual,
)

__all__ = ["quote_attr", "urdf_to_string", "write_urdf"]


def _num(value: float) -> str:
    text = repr(float(value))
    return text[:-2] if text.endswith(".0") else text


def _vec(values: Iterable[float]) -> str:
    return " ".join(_num(v) for v in values)


def _attrs(pairs: Iterable[tuple[str, str | float | None]]) -> str:
    out = []
    for key, value in pairs:
        if value is None:
            continue
        text = value if isinstance(value, str) else _num(value)
        out.append(f" {key}={quote_attr(text)}")
    return "".join(out)


def quote_attr(text: str) -> str:
    """``xml.sax.saxutils.quoteattr``: the escaped value in the quotes that need no escaping.

    Written here because importing ``xml.sax.saxutils`` pulls in ``urllib.request``, ``http``,
    ``ssl`` and ``email`` (tens of ms of every command that writes URDF).
    """
    text = _escape_text(text).replace("\n", "&#10;").replace("\r", "&#13;").replace("\t", "&#9;")
    if '"' not in text:
        return f'"{text}"'
    if "'" not in text:
        return f"'{text}'"
    return '"' + text.replace('"', "&quot;") + '"'


def _escape_text(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


class _Out:
    def __init__(self) -> None:
        self.lines: list[str] = []

    def add(self, depth: int, text: str) -> None:
        self.lines.append("  " * depth + text)

    def raw(self, depth: int, xml: str) -> None:
        self.lines.append("  " * depth + xml)


def _origin(out: _Out, depth: int, origin: Origin) -> None:
    if origin.is_identity:
        return
    if origin.quat_xyzw is not None:
        out.add(depth, f'<origin xyz="{_vec(origin.xyz_m)}" quat_xyzw="{_vec(origin.quat_xyzw)}"/>')
    else:
        out.add(depth, f'<origin xyz="{_vec(origin.xyz_m)}" rpy="{_vec(origin.rpy_rad)}"/>')


def _geometry(out: _Out, depth: int, geometry: Geometry) -> None:
    out.add(depth, "<geometry>")
    if isinstance(geometry, Box):
        out.add(depth + 1, f'<box size="{_vec(geometry.size_m)}"/>')
    elif isinstance(geometry, Cylinder):
        out.add(
            depth + 1,
            f"<cylinder{_attrs([('radius', geometry.radius_m), ('length', geometry.length_m)])}/>",
        )
    elif isinstance(geometry, Sphere):
        out.add(depth + 1, f"<sphere{_attrs([('radius', geometry.radius_m)])}/>")
    elif isinstance(geometry, Capsule):
        out.add(
            depth + 1,
            f"<capsule{_attrs([('radius', geometry.radius_m), ('length', geometry.length_m)])}/>",
        )
    elif isinstance(geometry, Mesh):
        scale = None if geometry.scale is None else _vec(geometry.scale)
        out.add(depth + 1, f"<mesh{_attrs([('filename', geometry.filename), ('scale', scale)])}/>")
    out.add(depth, "</geometry>")


def _material(out: _Out, depth: int, material: Material) -> None:
    if material.is_reference:
        out.add(depth, f"<material{_attrs([('name', material.name)])}/>")
        return
    out.add(depth, f"<material{_attrs([('name', material.name)])}>")
    if material.rgba is not None:
        out.add(depth + 1, f'<color rgba="{_vec(material.rgba)}"/>')
    if material.texture is not None:
        out.add(depth + 1, f"<texture{_attrs([('filename', material.texture)])}/>")
    out.add(depth, "</material>")


def _inertial(out: _Out, depth: int, inertial: Inertial) -> None:
    i = inertial.inertia
    out.add(depth, "<inertial>")
    _origin(out, depth + 1, inertial.origin)
    out.add(depth + 1, f"<mass{_attrs([('value', inertial.mass_kg)])}/>")
    keys = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
    out.add(depth + 1, f"<inertia{_attrs((k, getattr(i, k)) for k in keys)}/>")
    out.add(depth, "</inertial>")


def _shape_element(out: _Out, depth: int, tag: str, element: Visual | Collision) -> None:
    out.add(depth, f"<{tag}{_attrs([('name', element.name)])}>")
    _origin(out, depth + 1, element.origin)
    _geometry(out, depth + 1, element.geometry)
    if isinstance(element, Visual) and element.material is not None:
        _material(out, depth + 1, element.material)
    out.add(depth, f"</{tag}>")


def _link(out: _Out, depth: int, link: Link) -> None:
    if link.inertial is None and not link.visuals and not link.collisions and not link.extra:
        out.add(depth, f"<link{_attrs([('name', link.name)])}/>")
        return
    out.add(depth, f"<link{_attrs([('name', link.name)])}>")
    if link.inertial is not None:
        _inertial(out, depth + 1, link.inertial)
    for visual in link.visuals:
        _shape_element(out, depth + 1, "visual", visual)
    for collision in link.collisions:
        _shape_element(out, depth + 1, "collision", collision)
    for raw in link.extra:
        out.raw(depth + 1, raw.xml)
    out.add(depth, "</link>")


def _joint(out: _Out, depth: int, joint: Joint) -> None:
    out.add(depth, f"<joint{_attrs([('name', joint.name), ('type', joint.type.value)])}>")
    _origin(out, depth + 1, joint.origin)
    out.add(depth + 1, f"<parent{_attrs([('link', joint.parent)])}/>")
    out.add(depth + 1, f"<child{_attrs([('link', joint.child)])}/>")
    if joint.axis != (1.0, 0.0, 0.0):
        out.add(depth + 1, f'<axis xyz="{_vec(joint.axis)}"/>')
    if joint.limit is not None:
        lim = joint.limit
        fields = ("lower", "upper", "effort", "velocity", "acceleration", "deceleration", "jerk")
        out.add(depth + 1, f"<limit{_attrs((f, getattr(lim, f)) for f in fields)}/>")
    if joint.dynamics is not None:
        dyn = joint.dynamics
        out.add(
            depth + 1,
            f"<dynamics{_attrs([('damping', dyn.damping), ('friction', dyn.friction)])}/>",
        )
    if joint.mimic is not None:
        m = joint.mimic
        out.add(
            depth + 1,
            f"<mimic{_attrs([('joint', m.joint), ('multiplier', m.multiplier), ('offset', m.offset)])}/>",
        )
    if joint.safety_controller is not None:
        s = joint.safety_controller
        pairs = [
            ("soft_lower_limit", s.soft_lower_limit),
            ("soft_upper_limit", s.soft_upper_limit),
            ("k_position", s.k_position),
            ("k_velocity", s.k_velocity),
        ]
        out.add(depth + 1, f"<safety_controller{_attrs(pairs)}/>")
    if joint.calibration is not None:
        c = joint.calibration
        pairs = [
            ("rising", c.rising),
            ("falling", c.falling),
            ("reference_position", c.reference_position),
        ]
        out.add(depth + 1, f"<calibration{_attrs(pairs)}/>")
    for raw in joint.extra:
        out.raw(depth + 1, raw.xml)
    out.add(depth, "</joint>")


def _text_element(out: _Out, depth: int, tag: str, text: str) -> None:
    out.add(depth, f"<{tag}>{_escape_text(text)}</{tag}>")


def _transmission(out: _Out, depth: int, tr: Transmission) -> None:
    ros2 = tr.style is TransmissionStyle.ROS2
    head = [("name", tr.name)]
    if tr.style is TransmissionStyle.ROS1_TYPE_ATTRIBUTE:
        head.append(("type", tr.type))
    out.add(depth, f"<transmission{_attrs(head)}>")
    if tr.style is TransmissionStyle.ROS1:
        _text_element(out, depth + 1, "type", tr.type)
    elif ros2:
        _text_element(out, depth + 1, "plugin", tr.type)
    reduction_tag = "mechanical_reduction" if ros2 else "mechanicalReduction"
    for tag, sides in (("joint", tr.joints), ("actuator", tr.actuators)):
        for side in sides:
            attrs = [("name", side.name), ("role", side.role if ros2 else None)]
            out.add(depth + 1, f"<{tag}{_attrs(attrs)}>")
            if side.role is not None and not ros2:
                _text_element(out, depth + 2, "role", side.role)
            for hw in side.hardware_interfaces:
                _text_element(out, depth + 2, "hardwareInterface", hw)
            if side.mechanical_reduction is not None:
                _text_element(out, depth + 2, reduction_tag, _num(side.mechanical_reduction))
            if side.offset is not None:
                _text_element(out, depth + 2, "offset", _num(side.offset))
            for raw in side.extra:
                out.raw(depth + 2, raw.xml)
            out.add(depth + 1, f"</{tag}>")
    if tr.mechanical_reduction is not None:
        _text_element(out, depth + 1, reduction_tag, _num(tr.mechanical_reduction))
    for raw in tr.extra:
        out.raw(depth + 1, raw.xml)
    out.add(depth, "</transmission>")


def _params(out: _Out, depth: int, params: tuple[tuple[str, str], ...]) -> None:
    for name, value in params:
        out.add(depth, f"<param{_attrs([('name', name)])}>{_escape_text(value)}</param>")


def _interface(out: _Out, depth: int, tag: str, iface: Interface) -> None:
    attrs = _attrs(
        [
            ("name", iface.name),
            ("data_type", iface.data_type),
            ("size", None if iface.size is None else str(iface.size)),
        ]
    )
    if not iface.params:
        out.add(depth, f"<{tag}{attrs}/>")
        return
    out.add(depth, f"<{tag}{attrs}>")
    _params(out, depth + 1, iface.params)
    out.add(depth, f"</{tag}>")


def _component(out: _Out, depth: int, tag: str, comp: ComponentInterfaces) -> None:
    out.add(depth, f"<{tag}{_attrs([('name', comp.name), *comp.attributes])}>")
    for iface in comp.command_interfaces:
        _interface(out, depth + 1, "command_interface", iface)
    for iface in comp.state_interfaces:
        _interface(out, depth + 1, "state_interface", iface)
    _params(out, depth + 1, comp.params)
    out.add(depth, f"</{tag}>")


def _ros2_control(out: _Out, depth: int, block: Ros2Control) -> None:
    out.add(
        depth,
        f"<ros2_control{_attrs([('name', block.name), ('type', block.type), *block.attributes])}>",
    )
    if block.hardware_plugin is not None or block.hardware_params:
        out.add(depth + 1, "<hardware>")
        if block.hardware_plugin is not None:
            _text_element(out, depth + 2, "plugin", block.hardware_plugin)
        _params(out, depth + 2, block.hardware_params)
        out.add(depth + 1, "</hardware>")
    for tag, comps in (("joint", block.joints), ("sensor", block.sensors), ("gpio", block.gpios)):
        for comp in comps:
            _component(out, depth + 1, tag, comp)
    for tr in block.transmissions:
        _transmission(out, depth + 1, tr)
    for raw in block.extra:
        out.raw(depth + 1, raw.xml)
    out.add(depth, "</ros2_control>")


def urdf_to_string(robot: Robot) -> str:
    """Serialize ``robot`` as a URDF document (UTF-8 text with an XML declaration)."""
    out = _Out()
    out.lines.append('<?xml version="1.0" encoding="utf-8"?>')
    head = [("name", robot.name), ("version", robot.version), *robot.attributes]
    out.add(0, f"<robot{_attrs(head)}>")
    for material in robot.materials:
        _material(out, 1, material)
    for link in robot.links:
        _link(out, 1, link)
    for joint in robot.joints:
        _joint(out, 1, joint)
    for tr in robot.transmissions:
        _transmission(out, 1, tr)
    for block in robot.ros2_control:
        _ros2_control(out, 1, block)
    for gazebo in robot.gazebo:
        out.raw(1, gazebo.xml)
    for raw in robot.extra:
        out.raw(1, raw.xml)
    out.add(0, "</robot>")
    return "\n".join(out.lines) + "\n"


def write_urdf(robot: Robot, path: str | os.PathLike[str]) -> None:
    """Write ``robot`` to ``path`` atomically."""
    atomic_write_text(path, urdf_to_string(robot))
