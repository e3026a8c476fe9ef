"""Controller YAML files, ROS 2 and ROS 1 formats, to one normalised configuration.

ROS 2 (``controller_manager: ros__parameters: {update_rate, <name>: {type}}`` plus
``<name>: ros__parameters: {...}``; node keys may also be ``/name``, ``/ns/name``, ``/**/name``,
and ``/**`` applies to every controller). ROS 1 (``<name>: {type: ..., joint: ..., pid: ...}``,
optionally under a namespace key as in seed 000's ``rrbot:``), with the ROS 1 type names
mapped onto our controllers (:data:`ROS1_TYPES`). Nested mappings become dotted parameter
names (``pid.p``). Errors carry file:line:column from the YAML marks.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from robomodel._files import UserFileError, read_user_text
from robomodel._yaml_bounded import YamlNestingError, check_yaml_file
from robomodel.control.controllers.registry import CONTROLLER_TYPES
from robomodel.control.exceptions import ConfigError
from robomodel.errors import SourceLocation, close_matches

__all__ = ["ROS1_TYPES", "ControllerConfig", "ControllerSpec", "load_controller_config"]


@dataclass(frozen=True, slots=True)
class ControllerSpec:
    """One controller of a configuration: its name, our type name and flattened parameters."""

    name: str
    type: str
    params: Mapping[str, Any] = field(default_factory=dict)
    location: SourceLocation | None = None
    original_type: str = ""


@dataclass(frozen=True, slots=True)
class ControllerConfig:
    """A whole controller file: the manager's rate and the controllers in file order."""

    update_rate_hz: int = 100
    controllers: tuple[ControllerSpec, ...] = ()
    namespace: str = "/"
    format: str = "ros2"
    path: str | None = None
    manager_params: Mapping[str, Any] = field(default_factory=dict)

    def controller(self, name: str) -> ControllerSpec:
        for spec in self.controllers:
            if spec.name == name:
                return spec
        from robomodel.control.exceptions import UnknownControllerError

        raise UnknownControllerError(name, tuple(s.name for s in self.controllers))


def _ros1_group(kind: str) -> Callable[[dict[str, Any]], tuple[str, dict[str, Any]]]:
    def convert(p: dict[str, Any]) -> tuple[str, dict[str, Any]]:
        p.setdefault("topic", "~/command")
        return f"{kind}_controllers/JointGroup{kind.capitalize()}Controller", p

    return convert


def _ros1_single(kind: str) -> Callable[[dict[str, Any]], tuple[str, dict[str, Any]]]:
    def convert(p: dict[str, Any]) -> tuple[str, dict[str, Any]]:
        p["interface_name"] = kind
        return "robomodel_controllers/SingleJointForwardController", p

    return convert


def _ros1_jtc(kind: str) -> Callable[[dict[str, Any]], tuple[str, dict[str, Any]]]:
    def convert(p: dict[str, Any]) -> tuple[str, dict[str, Any]]:
        p.setdefault("command_interfaces", [kind])
        p.setdefault("state_interfaces", ["position", "velocity"])
        p.setdefault("topic", "~/command")
        return "joint_trajectory_controller/JointTrajectoryController", p

    return convert


def _ros1_jsc(p: dict[str, Any]) -> tuple[str, dict[str, Any]]:
    # publish_rate stays: the broadcaster limits its publishing by elapsed time, as ROS 1's
    # JointStateController does (an update_rate would be rounded to a divisor of the loop's)
    p.setdefault("topic", "joint_states")  # relative: /<ns>/joint_states
    p.setdefault("publish_dynamic_joint_states", False)  # not in ROS 1
    return "joint_state_broadcaster/JointStateBroadcaster", p


def _ros1_diff(p: dict[str, Any]) -> tuple[str, dict[str, Any]]:
    for side in ("left", "right"):
        if f"{side}_wheel" in p:
            p[f"{side}_wheel_names"] = p.pop(f"{side}_wheel")
    if "wheel_radius_multiplier" in p:
        m = p.pop("wheel_radius_multiplier")
        p.setdefault("left_wheel_radius_multiplier", m)
        p.setdefault("right_wheel_radius_multiplier", m)
    p.setdefault("derive_wheel_params_from_urdf", True)
    p.setdefault("use_stamped_vel", False)
    p.setdefault("cmd_vel_unstamped_topic", "~/cmd_vel")
    return "diff_drive_controller/DiffDriveController", p


def _same(type_name: str) -> Callable[[dict[str, Any]], tuple[str, dict[str, Any]]]:
    return lambda p: (type_name, p)


# ROS 1 (ros_controllers) type -> our type and parameter conversion.
ROS1_TYPES: dict[str, Callable[[dict[str, Any]], tuple[str, dict[str, Any]]]] = {
    "joint_state_controller/JointStateController": _ros1_jsc,
    "effort_controllers/JointPositionController": _same(
        "effort_controllers/JointPositionController"
    ),
    "position_controllers/JointPositionController": _ros1_single("position"),
    "velocity_controllers/JointVelocityController": _ros1_single("velocity"),
    "effort_controllers/JointEffortController": _ros1_single("effort"),
    "position_controllers/JointGroupPositionController": _ros1_group("position"),
    "velocity_controllers/JointGroupVelocityController": _ros1_group("velocity"),
    "effort_controllers/JointGroupEffortController": _ros1_group("effort"),
    "position_controllers/JointTrajectoryController": _ros1_jtc("position"),
    "velocity_controllers/JointTrajectoryController": _ros1_jtc("velocity"),
    "effort_controllers/JointTrajectoryController": _ros1_jtc("effort"),
    "diff_drive_controller/DiffDriveController": _ros1_diff,
}


class _Located:
    """YAML data with the mark of every mapping key and value."""

    def __init__(self, path: str | None) -> None:
        self.path = path
        self.marks: dict[tuple[str, ...], yaml.Mark] = {}

    def loc(self, key: tuple[str, ...]) -> SourceLocation:
        mark = self.marks.get(key)
        while mark is None and key:
            key = key[:-1]
            mark = self.marks.get(key)
        if mark is None:
            return SourceLocation(self.path)
        return SourceLocation(self.path, mark.line + 1, mark.column + 1)

    def convert(self, node: yaml.Node, key: tuple[str, ...]) -> Any:
        self.marks.setdefault(key, node.start_mark)
        if isinstance(node, yaml.MappingNode):
            out: dict[str, Any] = {}
            for k, v in node.value:
                name = str(yaml.safe_load(yaml.serialize(k)))  # scalar keys
                if name in out:
                    raise ConfigError(f"duplicate key '{name}'", self._at(k))
                path = (*key, name)
                self.marks[path] = k.start_mark
                out[name] = self.convert(v, path)
            return out
        if isinstance(node, yaml.SequenceNode):
            return [self.convert(v, (*key, str(i))) for i, v in enumerate(node.value)]
        return yaml.safe_load(yaml.serialize(node))

    def _at(self, node: yaml.Node) -> SourceLocation:
        return SourceLocation(self.path, node.start_mark.line + 1, node.start_mark.column + 1)


def _flatten(data: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    out: dict[str, Any] = {}
    for k, v in data.items():
        if isinstance(v, Mapping):
            out.update(_flatten(v, f"{prefix}{k}."))
        else:
            out[f"{prefix}{k}"] = v
    return out


def _node_name(key: str) -> str:
    return key.rstrip("/").rsplit("/", 1)[-1] if key != "/**" else "/**"


def _resolve_type(
    name: str, type_name: Any, params: dict[str, Any], loc: SourceLocation, ros1: bool
) -> tuple[str, dict[str, Any]]:
    if not isinstance(type_name, str) or not type_name:
        raise ConfigError(f"controller '{name}': 'type' must be a controller type name", loc)
    if ros1 and type_name in ROS1_TYPES:
        return ROS1_TYPES[type_name](params)
    if type_name in CONTROLLER_TYPES:
        return type_name, params
    if type_name in ROS1_TYPES:
        return ROS1_TYPES[type_name](params)
    known = tuple(sorted({*CONTROLLER_TYPES, *ROS1_TYPES}))
    hint = close_matches(type_name, known)
    raise ConfigError(
        f"controller '{name}': unknown controller type '{type_name}'"
        + (f" (did you mean {', '.join(repr(h) for h in hint)}?)" if hint else "")
        + f"; known types: {', '.join(known)}",
        loc,
    )


def _ros2(data: dict[str, Any], doc: _Located) -> ControllerConfig:
    cm_key = next(k for k in data if _node_name(k) == "controller_manager")
    cm = data[cm_key]
    if not isinstance(cm, dict) or not isinstance(cm.get("ros__parameters"), dict):
        raise ConfigError(
            "controller_manager needs a 'ros__parameters' mapping", doc.loc((cm_key,))
        )
    cm_params = cm["ros__parameters"]
    rate = cm_params.get("update_rate", 100)
    if isinstance(rate, bool) or not isinstance(rate, int) or rate <= 0:
        raise ConfigError(
            f"update_rate must be a positive integer [Hz], got {rate!r}",
            doc.loc((cm_key, "ros__parameters", "update_rate")),
        )
    per_node: dict[str, dict[str, Any]] = {}
    wildcard: dict[str, Any] = {}
    for key, value in data.items():
        if key == cm_key:
            continue
        if not isinstance(value, dict) or not isinstance(value.get("ros__parameters"), dict):
            raise ConfigError(f"'{key}' needs a 'ros__parameters' mapping", doc.loc((key,)))
        flat = _flatten(value["ros__parameters"])
        if key == "/**":
            wildcard.update(flat)
        else:
            per_node.setdefault(_node_name(key), {}).update(flat)
    specs: list[ControllerSpec] = []
    for name, entry in cm_params.items():
        if not isinstance(entry, dict) or "type" not in entry:
            continue  # other manager parameters (use_sim_time, ...)
        loc = doc.loc((cm_key, "ros__parameters", name, "type"))
        params = {**wildcard, **per_node.get(name, {})}
        if "params_file" in entry:
            files = entry["params_file"]
            for file in [files] if isinstance(files, str) else list(files):
                where = doc.loc((cm_key, "ros__parameters", name, "params_file"))
                params.update(_params_file(str(file), name, doc.path, where))
        if "fallback_controllers" in entry:
            params.setdefault("fallback_controllers", entry["fallback_controllers"])
        our_type, params = _resolve_type(name, entry["type"], params, loc, ros1=False)
        specs.append(ControllerSpec(name, our_type, params, loc, entry["type"]))
    unused = sorted(set(per_node) - {s.name for s in specs})
    for name in unused:
        raise ConfigError(
            f"parameters for '{name}', which controller_manager does not list with a type; "
            f"controllers: {', '.join(s.name for s in specs) or '(none)'}",
            doc.loc((next(k for k in data if _node_name(k) == name),)),
        )
    manager_params = _flatten(
        {k: v for k, v in cm_params.items() if not (isinstance(v, dict) and "type" in v)}
    )
    return ControllerConfig(int(rate), tuple(specs), "/", "ros2", doc.path, manager_params)


def _params_file(
    file: str, name: str, config_path: str | None, where: SourceLocation
) -> dict[str, Any]:
    """The parameters for controller ``name`` in a ``<name>.params_file`` (``/**`` first)."""
    path = Path(file)
    if not path.is_absolute() and config_path is not None:
        path = Path(config_path).parent / path
    try:
        text = read_user_text(path, what="params_file")
    except UserFileError as exc:
        raise ConfigError(f"params_file '{file}' of '{name}': {exc}", where) from None
    doc = _Located(str(path))
    try:
        check_yaml_file(text, where=str(path))
        node = yaml.compose(text, Loader=yaml.SafeLoader)
    except YamlNestingError as exc:
        raise ConfigError(
            exc.problem, SourceLocation(str(path), exc.line or None, exc.column or None)
        ) from None
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark
        loc = SourceLocation(str(path), mark.line + 1, mark.column + 1) if mark else where
        raise ConfigError(f"YAML syntax error: {exc.problem}", loc) from None
    data = doc.convert(node, ()) if node is not None else {}
    out: dict[str, Any] = {}
    if isinstance(data, dict):
        for key in sorted(data, key=lambda k: k != "/**"):  # wildcard first, then the node
            value = data[key]
            if (key == "/**" or _node_name(key) == name) and isinstance(value, dict):
                inner = value.get("ros__parameters")
                if isinstance(inner, dict):
                    out.update(_flatten(inner))
    return out


def _ros1(data: dict[str, Any], doc: _Located) -> ControllerConfig:
    namespace = "/"
    prefix: tuple[str, ...] = ()
    entries = data
    # seed 000: everything under a namespace key (rrbot:)
    if len(data) == 1:
        ((only, inner),) = data.items()
        if (
            isinstance(inner, dict)
            and "type" not in inner
            and any(isinstance(v, dict) and "type" in v for v in inner.values())
        ):
            namespace, prefix, entries = "/" + only.strip("/"), (only,), inner
    specs: list[ControllerSpec] = []
    for name, entry in entries.items():
        if not isinstance(entry, dict):
            continue
        if "type" not in entry:
            if name in ("gazebo_ros_control",):
                continue
            raise ConfigError(f"controller '{name}' has no 'type'", doc.loc((*prefix, name)))
        loc = doc.loc((*prefix, name, "type"))
        params = _flatten({k: v for k, v in entry.items() if k != "type"})
        our_type, params = _resolve_type(name, entry["type"], params, loc, ros1=True)
        specs.append(ControllerSpec(name, our_type, params, loc, entry["type"]))
    if not specs:
        raise ConfigError("no controllers found (no entry has a 'type')", doc.loc(()))
    return ControllerConfig(100, tuple(specs), namespace, "ros1", doc.path)


_BOUND_KEYS = (
    ("i", "i_clamp_min", "i_clamp_max"),
    ("u", "u_clamp_min", "u_clamp_max"),
)


def _check_pid_bounds(data: Any, key: tuple[str, ...], doc: _Located) -> None:
    """Refuse PID gains whose clamps have min > max, at the min's line (control_toolbox's Pid
    throws ``invalid_argument`` on them; the controller would never be configured)."""
    if isinstance(data, dict):
        for kind, low_key, high_key in _BOUND_KEYS:
            low, high = data.get(low_key), data.get(high_key)
            if isinstance(low, int | float) and isinstance(high, int | float) and low > high:
                raise ConfigError(
                    f"received {kind}_min > {kind}_max ({low_key}={low:g} > {high_key}="
                    f"{high:g}); control_toolbox's Pid needs {low_key} <= {high_key}",
                    doc.loc((*key, low_key)),
                )
        for name, value in data.items():
            _check_pid_bounds(value, (*key, name), doc)
    elif isinstance(data, list):
        for index, value in enumerate(data):
            _check_pid_bounds(value, (*key, str(index)), doc)


def load_controller_config(
    source: str | os.PathLike[str], *, text: str | None = None
) -> ControllerConfig:
    """Read a controller YAML file (or ``text``, with ``source`` naming it in messages).

    Raises:
        ConfigError: YAML syntax errors, unknown types, missing ``type`` or ``ros__parameters``,
            each with file:line:column.
    """
    path = str(source)
    if text is None:
        try:
            text = read_user_text(path, what="controller file")
        except UserFileError as exc:
            raise ConfigError(
                exc.reason, SourceLocation(path, exc.line or None, exc.column or None)
            ) from None
    doc = _Located(path)
    try:
        check_yaml_file(text, where=path)
        node = yaml.compose(text, Loader=yaml.SafeLoader)
    except YamlNestingError as exc:
        raise ConfigError(
            exc.problem, SourceLocation(path, exc.line or None, exc.column or None)
        ) from None
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark
        loc = SourceLocation(path, mark.line + 1, mark.column + 1) if mark else SourceLocation(path)
        raise ConfigError(f"YAML syntax error: {exc.problem}", loc) from None
    if node is None:
        raise ConfigError("the controller file is empty", SourceLocation(path))
    data = doc.convert(node, ())
    if not isinstance(data, dict):
        raise ConfigError("the controller file must be a mapping", doc.loc(()))
    _check_pid_bounds(data, (), doc)
    if any(_node_name(k) == "controller_manager" for k in data):
        return _ros2(data, doc)
    return _ros1(data, doc)
