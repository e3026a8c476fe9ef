"""A serial robot from a kinematics parameter YAML file (seed 004's format), and back to URDF.

The format, as the seed's ``kinematics_parameters.yaml`` shows it::

    base:                       # pose of link_0 in base (joint "base_offset", fixed)
      position: 0.0 0.0 0.0     # x y z [m]; a list of numbers is accepted too
      orientation: 0.0 0.0 0.0  # roll pitch yaw [rad]
    types: [revolute, revolute, revolute]
    links:                      # origin of joint_i (link_{i-1} -> link_i), i = 1..n
      - position: 0.0 0.0 0.2
        orientation: 0.0 0.0 0.0
    joints:                     # limits of joint_i
      - {lower: -3.14, upper: 3.14, velocity: 1000.0, effort: 1000.0}
    end_effector:               # pose of end_effector in link_n (joint "end_effector_offset")
      position: 0.28 0.0 0.0
      orientation: 1.5707963267948966 0.0 1.5707963267948966

The robot has the links ``base``, ``link_0`` ... ``link_n`` and ``end_effector``, as the seed's
xacro builds them. Joints turn or slide about z unless an entry of ``joints`` gives ``axis``
(the seed's DH-style convention); ``name`` at the top level names the robot (default
``robot``). ``types``, ``links`` and ``joints`` must have the same length.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from typing import Any

import yaml

from robomodel._files import UserFileError, read_user_text
from robomodel.description.model import Joint, JointType, Limit, Link, Origin, Robot
from robomodel.description.urdf.writer import urdf_to_string
from robomodel.errors import InputError, close_matches

__all__ = ["kinematics_yaml_to_urdf", "read_kinematics_yaml"]

_TYPES = {t.value: t for t in JointType}


def _fail(message: str, path: str | None) -> InputError:
    return InputError.at(message, path)


def _triple(value: Any, where: str, path: str | None) -> tuple[float, float, float]:
    items = value.split() if isinstance(value, str) else value
    try:
        numbers = tuple(float(v) for v in items)
    except (TypeError, ValueError):
        raise _fail(f"{where} must be three numbers ('x y z'), not {value!r}", path) from None
    if len(numbers) != 3 or not all(math.isfinite(v) for v in numbers):
        raise _fail(f"{where} must be three finite numbers, not {value!r}", path)
    return numbers[0], numbers[1], numbers[2]


def _pose(entry: Any, where: str, path: str | None) -> Origin:
    if not isinstance(entry, Mapping):
        raise _fail(f"{where} must be a mapping with position and orientation", path)
    unknown = set(entry) - {"position", "orientation"}
    if unknown:
        raise _fail(
            f"{where}: unknown key '{sorted(unknown)[0]}'; keys are position, orientation", path
        )
    xyz = _triple(entry.get("position", "0 0 0"), f"{where}.position", path)
    rpy = _triple(entry.get("orientation", "0 0 0"), f"{where}.orientation", path)
    return Origin(xyz, rpy)


def _limit(entry: Any, where: str, path: str | None) -> tuple[Limit, tuple[float, float, float]]:
    if not isinstance(entry, Mapping):
        raise _fail(f"{where} must be a mapping (lower, upper, velocity, effort)", path)
    allowed = {"lower", "upper", "velocity", "effort", "axis"}
    for key in entry:
        if key not in allowed:
            hint = close_matches(str(key), allowed)
            extra = f" (did you mean '{hint[0]}'?)" if hint else ""
            raise _fail(
                f"{where}: unknown key '{key}'{extra}; keys are {', '.join(sorted(allowed))}", path
            )
    values: dict[str, float | None] = {}
    for key in ("lower", "upper", "velocity", "effort"):
        raw = entry.get(key)
        try:
            values[key] = None if raw is None else float(raw)
        except (TypeError, ValueError):
            raise _fail(f"{where}.{key} must be a number, not {raw!r}", path) from None
    axis = _triple(entry.get("axis", "0 0 1"), f"{where}.axis", path)
    limit = Limit(values["lower"], values["upper"], values["effort"], values["velocity"])
    return limit, axis


def _load_document(source: str | os.PathLike[str]) -> tuple[Mapping[str, Any], str | None]:
    """The YAML mapping of a path or text, checked for the three parallel lists."""
    text = os.fspath(source)
    path: str | None = None
    if "\n" not in text and not text.lstrip().startswith("{"):
        path = text
        try:
            text = read_user_text(path, what="model file")
        except UserFileError as exc:
            raise _fail(exc.reason, path) from None
    from robomodel._yaml_bounded import YamlNestingError, load_yaml_file

    try:
        doc = load_yaml_file(text, where=path or "the model text")
    except YamlNestingError as exc:
        raise InputError.at(exc.problem, path, exc.line or None, exc.column or None) from None
    except yaml.YAMLError as exc:
        raise _fail(f"invalid YAML: {exc}", path) from None
    if not isinstance(doc, Mapping):
        raise _fail(
            "the document must be a mapping with base, types, links, joints, end_effector", path
        )
    for key in ("types", "links", "joints"):
        if not isinstance(doc.get(key), list):
            raise _fail(f"'{key}' must be a list", path)
    types, links, joints = doc["types"], doc["links"], doc["joints"]
    if not len(types) == len(links) == len(joints):
        raise _fail(
            f"types, links and joints must have the same length (got {len(types)}, "
            f"{len(links)}, {len(joints)})",
            path,
        )
    return doc, path


def _moving_joint(i: int, kind: Any, pose: Any, limits: Any, path: str | None) -> Joint:
    """Joint ``i`` (1-based) between link_{i-1} and link_i."""
    joint_type = _TYPES.get(str(kind))
    if joint_type is None:
        hint = close_matches(str(kind), _TYPES)
        extra = f" (did you mean '{hint[0]}'?)" if hint else ""
        raise _fail(
            f"types[{i - 1}]: unknown joint type '{kind}'{extra}; types are {', '.join(_TYPES)}",
            path,
        )
    limit, axis = _limit(limits, f"joints[{i - 1}]", path)
    if joint_type in (JointType.REVOLUTE, JointType.PRISMATIC) and (
        limit.lower is None or limit.upper is None
    ):
        raise _fail(f"joints[{i - 1}]: a {joint_type.value} joint needs lower and upper", path)
    return Joint(
        f"joint_{i}",
        joint_type,
        f"link_{i - 1}",
        f"link_{i}",
        _pose(pose, f"links[{i - 1}]", path),
        axis=axis,
        limit=None if joint_type is JointType.FIXED else limit,
    )


def read_kinematics_yaml(source: str | os.PathLike[str], *, name: str | None = None) -> Robot:
    """Build the robot described by a kinematics YAML file (path) or text.

    Raises:
        InputError: the YAML is invalid or does not follow the format (the message names the
            key, e.g. ``links[1].position``).
    """
    doc, path = _load_document(source)
    types, links, joints = doc["types"], doc["links"], doc["joints"]
    robot_links = [
        Link("base"),
        *(Link(f"link_{i}") for i in range(len(types) + 1)),
        Link("end_effector"),
    ]
    base = _pose(doc.get("base", {}), "base", path)
    robot_joints = [Joint("base_offset", JointType.FIXED, "base", "link_0", base)]
    for i, (kind, pose, limits) in enumerate(zip(types, links, joints, strict=True), start=1):
        robot_joints.append(_moving_joint(i, kind, pose, limits, path))
    tip = _pose(doc.get("end_effector", {}), "end_effector", path)
    last = f"link_{len(types)}"
    robot_joints.append(Joint("end_effector_offset", JointType.FIXED, last, "end_effector", tip))
    robot_name = name or str(doc.get("name", "robot"))
    return Robot(robot_name, links=tuple(robot_links), joints=tuple(robot_joints), source_path=path)


def kinematics_yaml_to_urdf(source: str | os.PathLike[str], *, name: str | None = None) -> str:
    """The URDF text of the robot a kinematics YAML file describes."""
    return urdf_to_string(read_kinematics_yaml(source, name=name))
