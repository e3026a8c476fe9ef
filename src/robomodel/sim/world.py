"""Worlds: the default empty world and the common subset of SDF world files.

Understood (sdformat world.sdf / model.sdf / physics.sdf): ``<include><uri>model://ground_plane``
and ``model://sun``; ``<gravity>``; ``<physics><max_step_size>``, ``<real_time_factor>``;
``<model>`` with ``<static>``, ``<pose>`` and links whose ``<collision>`` geometry is a
``<box><size>``, ``<cylinder><radius><length>``, ``<sphere><radius>`` or ``<plane>`` (walls,
obstacles, floors). Models that are not static become free bodies with their ``<inertial>``
mass (1 kg by default). ``<sensor>`` elements of a static model's links (a camera on a pole, as
gazebo_ros's camera demo worlds have) become :class:`WorldSensor` (those of moving models are
skipped with a warning). Anything else is warned about and skipped.
"""

from __future__ import annotations

import enum
import math
import os
import warnings
from dataclasses import dataclass, replace

from lxml import etree

from robomodel._files import UserFileError, read_user_bytes
from robomodel.description.rigid import (
    PoseXyzw,
    compose_poses,
    quat_xyzw_from_rpy,
    rpy_exact_from_quat_xyzw,
)
from robomodel.sim.exceptions import WorldError
from robomodel.sim.sensors.spec import SensorSpec, parse_sensor

__all__ = [
    "Shape",
    "ShapeKind",
    "World",
    "WorldSensor",
    "default_world",
    "model_shapes",
    "parse_world",
    "read_world",
]


class ShapeKind(enum.Enum):
    BOX = "box"
    CYLINDER = "cylinder"
    SPHERE = "sphere"
    PLANE = "plane"


@dataclass(frozen=True, slots=True)
class Shape:
    """A world object: one collision shape of a model, posed in the world.

    Attributes:
        size: box full size (x, y, z) [m]; cylinder (radius, length, 0); sphere (radius, 0, 0);
            plane (half x, half y, 0), 0 meaning infinite.
        pose: (x, y, z, roll, pitch, yaw) [m, rad] in the world.
        mass_kg: 0 for static objects.
    """

    model: str
    kind: ShapeKind
    size: tuple[float, float, float]
    pose: tuple[float, float, float, float, float, float]
    mass_kg: float = 0.0
    friction: float = 1.0
    rgba: tuple[float, float, float, float] = (0.6, 0.6, 0.6, 1.0)


@dataclass(frozen=True, slots=True)
class WorldSensor:
    """A sensor of a static world model: ``spec.pose`` is in its link, placed at ``link_pose``
    (x, y, z, roll, pitch, yaw [m, rad]) in the world; MuJoCo names it ``site``."""

    model: str
    link_pose: tuple[float, float, float, float, float, float]
    spec: SensorSpec

    @property
    def site(self) -> str:
        return f"{self.model}::{self.spec.link}::{self.spec.name}"


@dataclass(frozen=True, slots=True)
class World:
    """A world: physics settings, a ground plane, a light and static shapes.

    Attributes:
        timestep_s: The physics step (SDF ``max_step_size``, default 1 ms).
        real_time_factor: Target speed in ``realtime`` mode (SDF ``real_time_factor``).
        ground_friction: Gazebo's ground_plane has ``mu`` 100 (so the robot's value decides).
    """

    name: str = "default"
    timestep_s: float = 0.001
    real_time_factor: float = 1.0
    gravity: tuple[float, float, float] = (0.0, 0.0, -9.81)
    ground_plane: bool = True
    ground_friction: float = 100.0
    sun: bool = True
    shapes: tuple[Shape, ...] = ()
    sensors: tuple[WorldSensor, ...] = ()
    source: str = ""


def default_world() -> World:
    """Gazebo's ``empty.world``: ground plane and sun, 1 ms steps, real time."""
    return World()


def read_world(path: str | os.PathLike[str]) -> World:
    """Parse an SDF world file (see the module docstring).

    Raises:
        WorldError: the file cannot be read or does not parse (with file:line).
    """
    name = os.fspath(path)
    try:
        data = read_user_bytes(name, what="world file")
    except UserFileError as exc:
        raise WorldError(str(exc)) from None
    return parse_world(data, path=name)


def parse_world(data: bytes | str, *, path: str = "<string>") -> World:
    """Parse SDF world text; ``path`` names it in messages."""
    raw = data.encode() if isinstance(data, str) else data
    try:
        root = etree.fromstring(raw, _safe_parser())
    except etree.XMLSyntaxError as exc:
        line = exc.lineno if exc.lineno else 1
        raise WorldError(f"world file does not parse: {exc.msg}", where=f"{path}:{line}") from None
    world = root if root.tag == "world" else root.find("world")
    if world is None:
        raise WorldError(
            f"no <world> element (root is <{root.tag}>)", where=f"{path}:{root.sourceline}"
        )
    return _read(world, path)


def _at(path: str, el: etree._Element) -> str:
    return f"{path}:{el.sourceline}"


def _floats(
    el: etree._Element | None, n: int, path: str, default: tuple[float, ...]
) -> tuple[float, ...]:
    if el is None or not (el.text or "").strip():
        return default
    try:
        values = tuple(float(v) for v in (el.text or "").split())
    except ValueError:
        raise WorldError(
            f"<{el.tag}> must be {n} numbers, got {el.text!r}", where=_at(path, el)
        ) from None
    if len(values) != n:
        raise WorldError(f"<{el.tag}> must be {n} numbers, got {el.text!r}", where=_at(path, el))
    return values


def _safe_parser() -> etree.XMLParser:
    """No entity expansion, no network, no huge trees: a world file cannot read other files."""
    return etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False)


def model_shapes(
    data: str, *, name: str, pose: tuple[float, float, float, float, float, float], path: str
) -> tuple[Shape, ...]:
    """The shapes of one SDF ``<model>`` (alone or in ``<sdf>``), renamed ``name`` and placed
    at ``pose`` (``spawn_model -sdf``): models of rigid shapes, as a world file holds them.

    Raises:
        WorldError: not XML, no ``<model>``, or a model with joints (an articulated robot is a
            URDF, spawned with ``-urdf``).
    """
    try:
        root = etree.fromstring(data.encode(), _safe_parser())
    except etree.XMLSyntaxError as exc:
        raise WorldError(f"the SDF model does not parse: {exc.msg}", where=path) from None
    model = root if root.tag == "model" else root.find("model")
    if model is None:
        raise WorldError(f"no <model> element (root is <{root.tag}>)", where=path)
    if model.find("joint") is not None:
        raise WorldError(
            f"SDF model '{name}' has joints: robomodel spawns articulated robots from URDF "
            "(spawn_model -urdf); SDF models of rigid shapes only",
            where=path,
        )
    model.set("name", name)
    return tuple(replace(s, pose=_compose(pose, s.pose)) for s in _model(model, path))


def _read(world: etree._Element, path: str) -> World:
    timestep, rtf = 0.001, 1.0
    physics = world.find("physics")
    if physics is not None:
        (timestep,) = _floats(physics.find("max_step_size"), 1, path, (timestep,))
        (rtf,) = _floats(physics.find("real_time_factor"), 1, path, (rtf,))
        if not (timestep > 0 and math.isfinite(timestep)):
            raise WorldError(
                f"max_step_size must be positive, got {timestep}", where=_at(path, physics)
            )
    gravity = _floats(world.find("gravity"), 3, path, (0.0, 0.0, -9.81))
    ground = sun = False
    shapes: list[Shape] = []
    sensors: list[WorldSensor] = []
    for el in world:
        if not isinstance(el.tag, str):
            continue
        if el.tag == "include":
            uri = (el.findtext("uri") or "").strip()
            if uri.endswith("ground_plane"):
                ground = True
            elif uri.endswith("sun"):
                sun = True
            else:
                warnings.warn(
                    f"{_at(path, el)}: <include> of '{uri}' is not supported; skipped", stacklevel=3
                )
        elif el.tag == "model":
            shapes.extend(_model(el, path))
            sensors.extend(_sensors(el, path))
        elif el.tag == "light":
            sun = True
        elif el.tag not in (
            "physics",
            "gravity",
            "scene",
            "plugin",
            "gui",
            "magnetic_field",
            "atmosphere",
            "spherical_coordinates",
            "wind",
            "state",
        ):
            warnings.warn(
                f"{_at(path, el)}: <{el.tag}> in a world is not supported; skipped", stacklevel=3
            )
    return World(
        name=world.get("name", "default"),
        timestep_s=timestep,
        real_time_factor=rtf,
        gravity=gravity,  # type: ignore[arg-type]
        ground_plane=ground,
        sun=sun,
        shapes=tuple(shapes),
        sensors=tuple(sensors),
        source=path,
    )


def _compose(
    a: tuple[float, ...], b: tuple[float, ...]
) -> tuple[float, float, float, float, float, float]:
    """Pose b given in the frame of pose a, in the world (x y z roll pitch yaw, SDF's order)."""
    (x, y, z), q = compose_poses(_pose(a), _pose(b))
    return (x, y, z, *rpy_exact_from_quat_xyzw(*q))


def _pose(pose: tuple[float, ...]) -> PoseXyzw:
    x, y, z, roll, pitch, yaw = pose
    return (x, y, z), quat_xyzw_from_rpy(roll, pitch, yaw)


def _model(model: etree._Element, path: str) -> list[Shape]:
    name = model.get("name", "model")
    static = (model.findtext("static") or "false").strip().lower() in ("1", "true")
    if model.find("include") is not None:
        warnings.warn(
            f"{_at(path, model)}: nested includes are not supported; skipped", stacklevel=4
        )
    model_pose = _floats(model.find("pose"), 6, path, (0.0,) * 6)
    shapes: list[Shape] = []
    for link in model.iterfind("link"):
        link_pose = _compose(model_pose, _floats(link.find("pose"), 6, path, (0.0,) * 6))
        (mass,) = _floats(link.find("inertial/mass"), 1, path, (1.0,))
        for collision in link.iterfind("collision"):
            pose = _compose(link_pose, _floats(collision.find("pose"), 6, path, (0.0,) * 6))
            geometry = collision.find("geometry")
            if geometry is None or len(geometry) == 0:
                raise WorldError(
                    f"model '{name}': <collision> without <geometry>", where=_at(path, collision)
                )
            shape = geometry[0]
            kind, size = _geometry(shape, path, name)
            if kind is None:
                continue
            mu = _floats(collision.find("surface/friction/ode/mu"), 1, path, (1.0,))[0]
            shapes.append(
                Shape(
                    name, kind, size, pose, 0.0 if static or kind is ShapeKind.PLANE else mass, mu
                )
            )
    return shapes


def _sensors(model: etree._Element, path: str) -> list[WorldSensor]:
    name = model.get("name", "model")
    static = (model.findtext("static") or "false").strip().lower() in ("1", "true")
    model_pose = _floats(model.find("pose"), 6, path, (0.0,) * 6)
    found: list[WorldSensor] = []
    for link in model.iterfind("link"):
        link_pose = _compose(model_pose, _floats(link.find("pose"), 6, path, (0.0,) * 6))
        for el in link.iterfind("sensor"):
            if not static:
                warnings.warn(
                    f"{_at(path, el)}: model '{name}': sensors of moving world models are not "
                    "supported; skipped",
                    stacklevel=4,
                )
                continue
            spec = parse_sensor(el, link.get("name", "link"), _at(path, el))
            if spec is not None:
                found.append(WorldSensor(name, link_pose, spec))
    return found


def _geometry(
    shape: etree._Element, path: str, model: str
) -> tuple[ShapeKind | None, tuple[float, float, float]]:
    if shape.tag == "box":
        x, y, z = _floats(shape.find("size"), 3, path, (1.0, 1.0, 1.0))
        return ShapeKind.BOX, (x, y, z)
    if shape.tag == "cylinder":
        (r,) = _floats(shape.find("radius"), 1, path, (0.5,))
        (h,) = _floats(shape.find("length"), 1, path, (1.0,))
        return ShapeKind.CYLINDER, (r, h, 0.0)
    if shape.tag == "sphere":
        (r,) = _floats(shape.find("radius"), 1, path, (0.5,))
        return ShapeKind.SPHERE, (r, 0.0, 0.0)
    if shape.tag == "plane":
        sx, sy = _floats(shape.find("size"), 2, path, (0.0, 0.0))
        return ShapeKind.PLANE, (sx / 2, sy / 2, 0.0)
    warnings.warn(
        f"{_at(path, shape)}: model '{model}': <{shape.tag}> geometry is not supported; skipped",
        stacklevel=5,
    )
    return None, (0.0, 0.0, 0.0)
