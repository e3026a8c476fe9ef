"""``launch_ros.parameter_descriptions`` and parameter normalisation/evaluation.

Transcribes ``launch_ros.utilities.normalize_parameters`` and ``evaluate_parameters``: Python
strings and substitutions in dicts are YAML-parsed after substitution (so ``'1'`` becomes 1 and
a URDF string stays a string), nested dicts flatten to dotted names, lists keep a uniform type,
``ParameterValue(value, value_type=str)`` keeps the text.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import yaml

from robomodel._files import UserFileError, read_user_text
from robomodel.launch.ros2.frontend.substitution_parser import parse_substitution
from robomodel.launch.ros2.shim.context import LaunchContext, SubstitutionFailure
from robomodel.launch.ros2.shim.substitutions import (
    Substitution,
    TextSubstitution,
    coerce_bool,
    load_yaml_value,
    normalize_to_list_of_substitutions,
    perform_substitutions,
    perform_typed_substitution,
)

__all__ = ["Parameter", "ParameterFile", "ParameterValue", "evaluate_dict", "normalize_dict"]

_SCALARS = (bool, int, float, str, bytes)


class ParameterValue:
    """A parameter value with an optional type (``value_type=str`` keeps text as text)."""

    def __init__(self, value: Any, *, value_type: Any = None) -> None:
        if isinstance(value, (Substitution, str)) or (
            isinstance(value, (list, tuple))
            and value
            and all(isinstance(v, Substitution) for v in value)
        ):
            value = normalize_to_list_of_substitutions(value)
        elif isinstance(value, (list, tuple)) and any(isinstance(v, list) for v in value):
            value = [normalize_to_list_of_substitutions(v) for v in value]
        self.value = value
        self.value_type = value_type

    def evaluate(self, context: LaunchContext) -> Any:
        """The typed value."""
        if isinstance(self.value, list) and self.value and isinstance(self.value[0], list):
            items = [perform_substitutions(context, v) for v in self.value]
            if self.value_type is str:
                return items
            return [
                load_yaml_value(item, what="a parameter value") if item else "" for item in items
            ]
        return perform_typed_substitution(context, self.value, self.value_type)


class Parameter:
    """One named parameter (``launch_ros.parameter_descriptions.Parameter``)."""

    def __init__(self, name: Any, value: Any, *, value_type: Any = None) -> None:
        self.name = normalize_to_list_of_substitutions(name)
        self.parameter_value = ParameterValue(value, value_type=value_type)

    def evaluate(self, context: LaunchContext) -> tuple[str, Any]:
        """``(name, value)``."""
        return perform_substitutions(context, self.name), self.parameter_value.evaluate(context)


class ParameterFile:
    """A YAML parameter file; with ``allow_substs`` its ``$(...)`` are substituted."""

    def __init__(self, param_file: Any, *, allow_substs: Any = False) -> None:
        if isinstance(param_file, os.PathLike):
            param_file = os.fspath(param_file)
        self.param_file = normalize_to_list_of_substitutions(param_file)
        self.allow_substs = allow_substs

    def evaluate(self, context: LaunchContext) -> tuple[Path, bool]:
        """The file's path (a substituted temporary copy with ``allow_substs``) and the flag."""
        path = Path(os.path.abspath(perform_substitutions(context, self.param_file)))
        allow = self.allow_substs
        if not isinstance(allow, bool):
            allow = coerce_bool(
                perform_substitutions(context, normalize_to_list_of_substitutions(allow))
            )
        if not allow:
            return path, False
        try:
            text = read_user_text(path, what="parameter file")
        except UserFileError as exc:
            raise SubstitutionFailure(str(exc)) from None
        parsed = perform_substitutions(context, parse_substitution(text))
        try:
            load_yaml_value(parsed, what=str(path))
        except yaml.YAMLError:
            raise SubstitutionFailure(
                "The substituted parameter file is not a valid yaml file"
            ) from None
        handle, name = tempfile.mkstemp(prefix="launch_params_", suffix=".yaml")
        session = getattr(context, "session", None)
        if session is not None:  # removed when the launch ends (Ros2Launch.temporary_files)
            session.temporary_files.append(Path(name))
        with os.fdopen(handle, "w", encoding="utf-8") as f:
            f.write(parsed)
        return Path(name), True


def _normalize_list(value: Sequence[Any]) -> Any:
    kinds: set[type] = set()
    for item in value:
        if isinstance(item, Substitution):
            kinds.add(Substitution)
        elif isinstance(item, bool):
            kinds.add(bool)
        elif isinstance(item, (str, int, float)):
            kinds.add(type(item))
        elif isinstance(item, Sequence):
            kinds.add(tuple)
        else:
            raise TypeError(f"Unexpected type for parameter value {item!r}")
    if kinds == {int}:
        return tuple(int(e) for e in value)
    if kinds in ({float}, {int, float}):
        return tuple(float(e) for e in value)
    if Substitution in kinds and kinds <= {str, Substitution}:
        return tuple(normalize_to_list_of_substitutions(value))
    if kinds == {bool}:
        return tuple(bool(e) for e in value)
    out = []
    for element in value:
        if isinstance(element, (float, int, bool, str)):
            element = yaml.dump(element)
        out.append(tuple(normalize_to_list_of_substitutions(element)))
    return tuple(out)


def normalize_dict(
    parameters: Mapping[Any, Any], prefix: list[Substitution] | None = None
) -> dict[tuple[Substitution, ...], Any]:
    """``normalize_parameter_dict``: keys become substitution tuples, nested dicts flatten."""
    if not isinstance(parameters, Mapping):
        raise TypeError("expected dict")
    out: dict[tuple[Substitution, ...], Any] = {}
    for key, value in parameters.items():
        name = normalize_to_list_of_substitutions(key)
        if prefix:
            name = [*prefix, TextSubstitution(text="."), *name]
        if isinstance(value, Mapping):
            out.update(normalize_dict(value, name))
        elif isinstance(value, ParameterValue):
            out[tuple(name)] = value
        elif isinstance(value, str):
            out[tuple(name)] = tuple(normalize_to_list_of_substitutions(yaml.dump(value)))
        elif isinstance(value, Substitution):
            out[tuple(name)] = (value,)
        elif isinstance(value, (float, bool, int, bytes)):
            out[tuple(name)] = value
        elif isinstance(value, Sequence):
            out[tuple(name)] = _normalize_list(value)
        else:
            raise TypeError(f"Unexpected type for parameter value {value!r}")
    return out


def _uniform(seq: Sequence[Any]) -> bool:
    if not seq:
        return False
    first = type(seq[0])
    return first in (bool, int, float, str) and all(isinstance(x, first) for x in seq)


def _yaml_value(name: str, text: str) -> Any:
    try:
        value = load_yaml_value(text if text else "''", what=f"parameter {name}")
    except yaml.YAMLError:
        raise TypeError(
            f"Unable to parse the value of parameter {name} as yaml. If the parameter is meant "
            "to be a string, try wrapping it in launch_ros.parameter_descriptions.ParameterValue"
            "(value, value_type=str)"
        ) from None
    if type(value) in _SCALARS:
        return value
    if isinstance(value, list):
        if not _uniform(value):
            raise TypeError(
                "Expected a non-empty sequence, with items of uniform type. Allowed sequence "
                f'item types are bool, int, float, str. Got inconsistent input for "{name}"'
            )
        return tuple(value)
    raise TypeError(
        "Allowed value types are bytes, bool, int, float, str, Sequence[bool], Sequence[int], "
        f'Sequence[float], Sequence[str]. Got {type(value)} for "{name}". If the parameter is '
        "meant to be a string, try wrapping it in "
        "launch_ros.parameter_descriptions.ParameterValue(value, value_type=str)"
    )


def evaluate_dict(
    context: LaunchContext, parameters: Mapping[tuple[Any, ...], Any]
) -> dict[str, Any]:
    """``evaluate_parameter_dict``: substitute, then YAML-parse substituted text."""
    out: dict[str, Any] = {}
    for key, value in parameters.items():
        name = perform_substitutions(context, list(key))
        if isinstance(value, tuple) and value and isinstance(value[0], Substitution):
            out[name] = _yaml_value(name, perform_substitutions(context, list(value)))
        elif isinstance(value, tuple) and value and isinstance(value[0], tuple):
            items = [
                load_yaml_value(perform_substitutions(context, list(v)) or "''", what=name)
                for v in value
            ]
            if not _uniform(items):
                raise TypeError(
                    "Expected a non-empty sequence, with items of uniform type. Allowed sequence "
                    f'item types are bool, int, float, str. Got inconsistent input for "{name}"'
                )
            out[name] = tuple(items)
        elif isinstance(value, tuple):
            out[name] = tuple(value)
        elif isinstance(value, ParameterValue):
            result = value.evaluate(context)
            out[name] = tuple(result) if isinstance(result, list) else result
        else:
            out[name] = value
    return out
