"""Node parameters: declare / get / set / list, validation callbacks, ROS 2 YAML files.

Types follow rcl_interfaces/ParameterType: bool, integer, double, string and arrays of each.
As in ROS 2, a declared parameter keeps its type (an int may be given for a double), setting an
undeclared parameter fails unless the node allows undeclared parameters, and set callbacks may
reject a change with a reason. Files use the ``node: ros__parameters:`` layout, with nested
mappings for dotted names (``zeros.joint1``) and ``/**`` as a wildcard node.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from robomodel._atomic import atomic_write_text
from robomodel._files import UserFileError, read_user_text
from robomodel._yaml_bounded import YamlNestingError, load_yaml, load_yaml_file
from robomodel.errors import RobomodelError, close_matches

__all__ = [
    "ParameterError",
    "ParameterStore",
    "SetResult",
    "dump_parameters_yaml",
    "load_parameters_file",
    "parameter_type_name",
    "parse_parameter_value",
]

ParameterValue = bool | int | float | str | list[bool] | list[int] | list[float] | list[str]


class ParameterError(RobomodelError):
    """A parameter that is unknown, of the wrong type, or rejected by the node."""


@dataclass(frozen=True, slots=True)
class SetResult:
    """Outcome of a set: ``successful`` or the ``reason`` it was refused (rcl_interfaces)."""

    successful: bool
    reason: str = ""


def parameter_type_name(value: Any) -> str:
    """The rcl_interfaces type name of a value (``double``, ``string_array``, ...)."""
    if isinstance(value, bool):
        return "bool"
    if isinstance(value, int):
        return "integer"
    if isinstance(value, float):
        return "double"
    if isinstance(value, str):
        return "string"
    if isinstance(value, (list, tuple)):
        if not value:
            return "array"
        kinds = {parameter_type_name(v) for v in value}
        if kinds == {"integer", "double"}:
            return "double_array"
        if len(kinds) == 1 and (kind := kinds.pop()) in ("bool", "integer", "double", "string"):
            return f"{kind}_array"
    raise ParameterError(f"unsupported parameter value {value!r}")


def _coerce(name: str, old: Any, new: Any) -> Any:
    old_type, new_type = parameter_type_name(old), parameter_type_name(new)
    if old_type == new_type or ("array" in (old_type, new_type) and new_type == "array"):
        return list(new) if isinstance(new, (list, tuple)) else new
    if old_type == "double" and new_type == "integer":
        return float(new)
    if old_type == "double_array" and new_type in ("integer_array", "double_array", "array"):
        return [float(v) for v in new]
    if old_type == "array":
        return list(new) if isinstance(new, (list, tuple)) else new
    raise ParameterError(
        f"Wrong parameter type, parameter {{{name}}} is of type {{{old_type}}}, setting it to "
        f"{{{new_type}}} is not allowed."
    )


def parse_parameter_value(text: str) -> ParameterValue:
    """Parse a command-line value as ``ros2 param set`` does (YAML scalars and lists)."""
    import yaml  # here, not at import: a node that never parses a value skips its 20 ms

    try:
        value = load_yaml(text, what="the parameter value")
    except yaml.YAMLError:
        return text
    if value is None:
        return text
    parameter_type_name(value)
    return value  # type: ignore[no-any-return]


SetCallback = Callable[[Mapping[str, Any]], SetResult]


class ParameterStore:
    """The parameters of one node."""

    def __init__(
        self,
        node_name: str,
        overrides: Mapping[str, Any] | None = None,
        *,
        allow_undeclared: bool = False,
    ) -> None:
        self._node = node_name
        self._values: dict[str, Any] = {}
        self._descriptions: dict[str, str] = {}
        self._read_only: set[str] = set()
        self._overrides = dict(overrides or {})
        self._allow_undeclared = allow_undeclared
        self._callbacks: list[SetCallback] = []
        self._post_callbacks: list[Callable[[Mapping[str, Any]], None]] = []
        # change the changes before they are checked (``add_pre_set_parameters_callback``)
        self._pre_callbacks: list[Callable[[Mapping[str, Any]], Mapping[str, Any]]] = []
        if allow_undeclared:
            for name, value in self._overrides.items():
                self._values[name] = value

    def declare(
        self, name: str, default: Any, *, description: str = "", read_only: bool = False
    ) -> Any:
        """Declare ``name`` with ``default`` (an override from a file or CLI wins)."""
        if name in self._values and not self._allow_undeclared:
            raise ParameterError(f"parameter '{name}' has already been declared")
        value = default
        if name in self._overrides:
            override = self._overrides[name]
            # Nodes that accept undeclared parameters declare them from the overrides
            # (rclpy's automatically_declare_parameters_from_overrides): the override's type wins.
            value = override if self._allow_undeclared else _coerce(name, default, override)
        parameter_type_name(value)
        self._values[name] = value
        self._descriptions[name] = description
        if read_only:
            self._read_only.add(name)
        return value

    def has(self, name: str) -> bool:
        return name in self._values

    def get(self, name: str) -> Any:
        try:
            return self._values[name]
        except KeyError:
            hint = close_matches(name, self._values)
            extra = f"; did you mean {', '.join(hint)}?" if hint else ""
            raise ParameterError(
                f"parameter '{name}' is not declared on node '{self._node}'{extra}"
            ) from None

    def names(self, prefix: str = "") -> list[str]:
        return sorted(n for n in self._values if n.startswith(prefix))

    def items(self) -> dict[str, Any]:
        return dict(sorted(self._values.items()))

    def describe(self, name: str) -> str:
        return self._descriptions.get(name, "")

    def is_read_only(self, name: str) -> bool:
        return name in self._read_only

    def add_set_callback(self, callback: SetCallback) -> None:
        """Validate changes before they apply (``add_on_set_parameters_callback``)."""
        self._callbacks.append(callback)

    def add_pre_set_callback(
        self, callback: Callable[[Mapping[str, Any]], Mapping[str, Any]]
    ) -> None:
        """Change the changes before they are checked (``add_pre_set_parameters_callback``):
        ``callback(changes)`` returns the changes to make instead (empty: the set fails)."""
        self._pre_callbacks.append(callback)

    def add_post_set_callback(self, callback: Callable[[Mapping[str, Any]], None]) -> None:
        """Be told about changes after they apply (``add_post_set_parameters_callback``)."""
        self._post_callbacks.append(callback)

    def set(self, changes: Mapping[str, Any]) -> SetResult:
        """Set several parameters atomically; all or nothing. A value of None unsets the
        parameter (rclpy's NOT_SET): a node that takes undeclared parameters lets it go (its
        parameters are dynamically typed), others refuse."""
        for pre in self._pre_callbacks:
            changes = pre(changes)
            if not changes:  # rclpy's words
                return SetResult(False, "parameter list cannot be empty, this might be due to "
                                 "pre_set_parameters_callback modifying the original parameters "
                                 "list.")  # fmt: skip
        coerced: dict[str, Any] = {}
        for name, value in changes.items():
            if name in self._read_only:
                return SetResult(False, f"parameter '{name}' is read-only")
            if value is None:
                if not self._allow_undeclared:
                    return SetResult(False, f"parameter '{name}' cannot be unset: node "
                                     f"'{self._node}' does not allow undeclared parameters")  # fmt: skip
                coerced[name] = None
                continue
            if name not in self._values:
                if not self._allow_undeclared:
                    return SetResult(False, f"parameter '{name}' is not declared")
                parameter_type_name(value)
                coerced[name] = value
                continue
            try:
                coerced[name] = _coerce(name, self._values[name], value)
            except ParameterError as exc:
                return SetResult(False, str(exc))
        for callback in self._callbacks:
            result = callback(coerced)
            if not result.successful:
                return result
        for name, value in coerced.items():
            if value is None:
                self._values.pop(name, None)
                self._descriptions.pop(name, None)
            else:
                self._values[name] = value
        for post in self._post_callbacks:
            post(coerced)
        return SetResult(True)


def _flatten(prefix: str, data: Mapping[str, Any], out: dict[str, Any]) -> None:
    for key, value in data.items():
        name = f"{prefix}.{key}" if prefix else str(key)
        if isinstance(value, Mapping):
            _flatten(name, value, out)
        else:
            out[name] = value


def load_parameters_file(path: str | os.PathLike[str], node_fq_name: str) -> dict[str, Any]:
    """Read the parameters for one node from a ROS 2 parameter YAML file.

    Matches ``/**`` (all nodes), the fully qualified name (``/ns/node``), and the bare node
    name; later, more specific entries override earlier ones.
    """
    try:
        text = read_user_text(path, what="parameter file")
    except UserFileError as exc:
        raise ParameterError(str(exc)) from None
    import yaml

    try:
        data = load_yaml_file(text, where=str(path)) or {}
    except YamlNestingError as exc:
        raise ParameterError(str(exc)) from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"{path}:{mark.line + 1}:{mark.column + 1}" if mark else str(path)
        raise ParameterError(
            f"{where}: error: invalid YAML: {getattr(exc, 'problem', exc)}"
        ) from None
    if not isinstance(data, dict):
        raise ParameterError(f"{path}: error: expected 'node_name: ros__parameters: ...'")
    bare = node_fq_name.rsplit("/", 1)[-1]
    out: dict[str, Any] = {}
    for key in ("/**", bare, node_fq_name.lstrip("/"), node_fq_name):
        section = data.get(key)
        if isinstance(section, dict):
            params = section.get("ros__parameters")
            if params is None:
                raise ParameterError(f"{path}: error: section '{key}' has no 'ros__parameters' key")
            _flatten("", params, out)
    return out


def dump_parameters_yaml(node_fq_name: str, values: Mapping[str, Any]) -> str:
    """``ros2 param dump`` output: nested mappings under ``node: ros__parameters:``."""
    nested: dict[str, Any] = {}
    for name, value in sorted(values.items()):
        target = nested
        parts = name.split(".")
        for part in parts[:-1]:
            target = target.setdefault(part, {})
        target[parts[-1]] = value
    import yaml

    return yaml.safe_dump({node_fq_name: {"ros__parameters": nested}}, sort_keys=False)


def write_parameters_file(path: str | os.PathLike[str], text: str) -> None:
    atomic_write_text(path, text)
