"""Reading ``<gazebo>`` URDF extensions (sdformat parser_urdf.cc ``ParseSDFExtension``).

``<gazebo reference="LINK">`` applies to a link, ``reference="JOINT"`` to a joint, no
reference to the model. Understood here: ``mu1``/``mu2``, ``kp``/``kd``, ``material``,
``selfCollide``, ``turnGravityOff``, ``static``, ``<sensor>`` (see :mod:`robomodel.sim.sensors.spec`)
and the ``gazebo_ros_control`` / ``gazebo_ros2_control`` model plugins. Joint references
(``springStiffness``, ``springReference``) are read by :mod:`robomodel.sim.build.joint_extras`.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field, replace

from lxml import etree

from robomodel.description.model import GazeboBlock, Robot
from robomodel.sim.build.inertia import where
from robomodel.sim.exceptions import SimulationError
from robomodel.sim.sensors.spec import SensorSpec, parse_sensor

__all__ = ["GAZEBO_MATERIALS", "GazeboExtensions", "LinkSurface", "read_gazebo"]

# OGRE colours of gazebo.material's common scripts (ambient/diffuse of Gazebo classic).
GAZEBO_MATERIALS: dict[str, tuple[float, float, float, float]] = {
    "Gazebo/Black": (0.0, 0.0, 0.0, 1.0),
    "Gazebo/White": (1.0, 1.0, 1.0, 1.0),
    "Gazebo/Grey": (0.7, 0.7, 0.7, 1.0),
    "Gazebo/DarkGrey": (0.175, 0.175, 0.175, 1.0),
    "Gazebo/Red": (1.0, 0.0, 0.0, 1.0),
    "Gazebo/Green": (0.0, 1.0, 0.0, 1.0),
    "Gazebo/Blue": (0.0, 0.0, 1.0, 1.0),
    "Gazebo/Yellow": (1.0, 1.0, 0.0, 1.0),
    "Gazebo/Orange": (1.0, 0.5088, 0.0468, 1.0),
    "Gazebo/Purple": (1.0, 0.0, 1.0, 1.0),
    "Gazebo/Turquoise": (0.0, 1.0, 1.0, 1.0),
    "Gazebo/Wood": (0.5, 0.3, 0.1, 1.0),
}


@dataclass(frozen=True, slots=True)
class LinkSurface:
    """Per-link extensions. ``None`` means "not given" (Gazebo's defaults apply)."""

    mu1: float | None = None
    mu2: float | None = None
    kp: float | None = None
    kd: float | None = None
    material: str | None = None
    self_collide: bool = False
    gravity: bool = True

    @property
    def rgba(self) -> tuple[float, float, float, float] | None:
        return GAZEBO_MATERIALS.get(self.material or "")

    @property
    def friction(self) -> float | None:
        """Sliding friction: ``mu1`` (MuJoCo friction is isotropic; ``mu2`` is the fallback)."""
        return self.mu1 if self.mu1 is not None else self.mu2


@dataclass(frozen=True, slots=True)
class GazeboExtensions:
    """Everything read from a robot's ``<gazebo>`` blocks."""

    links: dict[str, LinkSurface] = field(default_factory=dict)
    sensors: tuple[SensorSpec, ...] = ()
    static: bool = False
    ros_control_plugin: bool = False
    plugin_namespace: str = ""
    plugin_parameters: tuple[str, ...] = ()  # gazebo_ros2_control's <parameters> YAML files

    def surface(self, link: str) -> LinkSurface:
        return self.links.get(link, _DEFAULT_SURFACE)


_DEFAULT_SURFACE = LinkSurface()
_CONTROL_PLUGINS = ("libgazebo_ros_control.so", "libgazebo_ros2_control.so", "gz_ros2_control")


def _float(el: etree._Element, block: GazeboBlock) -> float:
    try:
        return float((el.text or "").strip())
    except ValueError:
        raise SimulationError(
            f"<{el.tag}> must be a number, got {el.text!r}", where=_line(block, el)
        ) from None


def _bool(el: etree._Element) -> bool:
    return (el.text or "").strip().lower() in ("true", "1")


def _line(block: GazeboBlock, el: etree._Element) -> str:
    at = where(block)
    span = block.span
    if span is None or span.line is None or el.sourceline is None:
        return at
    return f"{span.path or '<string>'}:{span.line + el.sourceline - 1}"


def read_gazebo(robot: Robot) -> GazeboExtensions:
    """Collect the ``<gazebo>`` extensions of ``robot``.

    Unknown sensor types are warned about and skipped, so the rest of the robot loads; a
    reference to a link or joint that does not exist is warned about too (Gazebo ignores it
    silently).
    """
    links: dict[str, LinkSurface] = {}
    sensors: list[SensorSpec] = []
    model = _ModelBlocks()
    for block in robot.gazebo:
        try:
            root = etree.fromstring(block.xml.encode())
        except etree.XMLSyntaxError as exc:
            raise SimulationError(
                f"<gazebo> block does not parse: {exc}", where=where(block)
            ) from None
        ref = block.reference
        if ref is None:
            model.read(root)
            continue
        if not robot.has_link(ref):
            if not robot.has_joint(ref):
                warnings.warn(
                    f"{where(block)}: <gazebo reference='{ref}'> names no link or joint; ignored",
                    stacklevel=2,
                )
            continue
        links[ref] = _read_link(root, block, links.get(ref, _DEFAULT_SURFACE), sensors)
    return GazeboExtensions(
        links, tuple(sensors), model.static, model.plugin, model.namespace, tuple(model.parameters)
    )


@dataclass
class _ModelBlocks:
    """What the ``<gazebo>`` blocks without a reference say of the whole model."""

    static: bool = False
    plugin: bool = False  # a ros_control / ros2_control plugin
    namespace: str = ""
    parameters: list[str] = field(default_factory=list)

    def read(self, root: etree._Element) -> None:
        for el in root:
            if el.tag == "static":
                self.static = _bool(el)
            elif el.tag == "plugin" and (el.get("filename") or "") in _CONTROL_PLUGINS:
                self.plugin = True
                ns = el.find("robotNamespace")
                if ns is None:
                    ns = el.find("ros/namespace")  # gazebo_ros2_control
                if ns is not None and ns.text:
                    self.namespace = ns.text.strip()
                self.parameters += [
                    (p.text or "").strip() for p in el.findall("parameters") if p.text
                ]


_SURFACE_FLOATS = frozenset({"mu1", "mu2", "kp", "kd"})  # LinkSurface fields of the same names


def _read_link(
    root: etree._Element, block: GazeboBlock, surface: LinkSurface, sensors: list[SensorSpec]
) -> LinkSurface:
    """A ``<gazebo reference="link">`` block: the link's surface, and its sensors appended."""
    for el in root:
        tag = el.tag
        if tag in _SURFACE_FLOATS:
            surface = replace(surface, **{tag: _float(el, block)})  # type: ignore[arg-type]
        elif tag == "material":
            surface = replace(surface, material=(el.text or "").strip())
        elif tag == "selfCollide":
            surface = replace(surface, self_collide=_bool(el))
        elif tag == "turnGravityOff":
            surface = replace(surface, gravity=not _bool(el))
        elif tag == "sensor":
            spec = parse_sensor(el, block.reference or "", _line(block, el))
            if spec is not None:
                sensors.append(spec)
    return surface
