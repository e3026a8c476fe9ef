"""``launch.substitutions``: text that is computed when the launch file is executed."""

from __future__ import annotations

import os
import random
import shlex
import shutil
import socket
from collections.abc import Iterable
from typing import Any

import yaml

from robomodel._files import UserFileError, read_user_text
from robomodel.launch.bounds import value_too_long
from robomodel.launch.ros2.shim.context import LaunchContext, SubstitutionFailure

__all__ = [
    "AnonName",
    "EnvironmentVariable",
    "FileContent",
    "FindExecutable",
    "LaunchConfiguration",
    "LocalSubstitution",
    "PathJoinSubstitution",
    "PathSubstitution",
    "Substitution",
    "SubstitutionFailure",
    "TextSubstitution",
    "ThisLaunchFile",
    "ThisLaunchFileDir",
    "load_yaml_value",
    "normalize_to_list_of_substitutions",
    "perform_substitutions",
    "perform_typed_substitution",
]


class Substitution:
    """Base of every substitution: ``perform(context) -> str`` and ``describe() -> str``."""

    def describe(self) -> str:
        """How ``ros2 launch --print`` shows it."""
        return f"Substitution('{self}')"

    def perform(self, context: LaunchContext) -> str:
        """Compute the text."""
        raise NotImplementedError

    def __repr__(self) -> str:
        return self.describe()


def normalize_to_list_of_substitutions(subs: Any) -> list[Substitution]:
    """``str`` / substitution / iterable of them -> a list of substitutions (as launch does)."""
    if isinstance(subs, str):
        return [TextSubstitution(text=subs)]
    if isinstance(subs, Substitution):
        return [subs]
    if isinstance(subs, Iterable):
        out: list[Substitution] = []
        for item in subs:
            if isinstance(item, str):
                out.append(TextSubstitution(text=item))
            elif isinstance(item, Substitution):
                out.append(item)
            else:
                raise TypeError(
                    f"Failed to normalize given item of type '{type(item).__name__}', "
                    "when only 'str' or 'launch.Substitution' were expected."
                )
        return out
    raise TypeError(
        f"Failed to normalize given item of type '{type(subs).__name__}', "
        "when only 'str' or 'launch.Substitution' were expected."
    )


def perform_substitutions(context: LaunchContext, subs: Iterable[Substitution]) -> str:
    """Perform each substitution and concatenate the results."""
    text = "".join(context.perform_substitution(sub) for sub in subs)
    problem = value_too_long(len(text))
    if problem is not None:
        raise SubstitutionFailure(problem)
    return text


def _describe(subs: Iterable[Substitution]) -> str:
    return " + ".join(sub.describe() for sub in subs)


def load_yaml_value(text: str, *, what: str) -> Any:
    """``yaml.safe_load(text)`` as launch does it, within the bounds of the project's YAML
    loader (nesting, aliases, size): a value past them is a SubstitutionFailure naming
    ``what``; a syntax error is yaml's, for the caller to word as launch does."""
    from robomodel._yaml_bounded import YamlNestingError, load_yaml_file

    try:
        return load_yaml_file(text, where=what)
    except YamlNestingError as exc:
        raise SubstitutionFailure(f"{what}: {exc.problem}") from None


def coerce_bool(text: str) -> bool:
    """launch's bool coercion: '1'/'0' and YAML booleans (``true``, ``False``, ...)."""
    value = {"1": "true", "0": "false"}.get(text, text)
    try:
        out = load_yaml_value(value, what=f"the value '{text[:40]}'")
    except yaml.YAMLError:
        out = None
    if not isinstance(out, bool):
        raise SubstitutionFailure(f"Failed to convert '{text}' to '<class 'bool'>'")
    return out


def perform_typed_substitution(context: LaunchContext, value: Any, data_type: Any) -> Any:
    """Perform and convert as ``launch.utilities.type_utils.perform_typed_substitution``."""
    if not isinstance(value, list) or not all(isinstance(v, Substitution) for v in value):
        return value
    text = perform_substitutions(context, value)
    if data_type is str:
        return text
    if data_type is bool:
        return coerce_bool(text)
    if data_type in (int, float):
        try:
            return data_type(text)
        except ValueError:
            raise SubstitutionFailure(f"Failed to convert '{text}' to '{data_type}'") from None
    try:
        return load_yaml_value(text, what="a substituted value")
    except yaml.YAMLError:
        raise SubstitutionFailure(f"Failed to convert '{text}' using yaml rules") from None


class TextSubstitution(Substitution):
    """A fixed text."""

    def __init__(self, *, text: str) -> None:
        if not isinstance(text, str):
            raise TypeError(f"TextSubstitution expected str, got '{type(text).__name__}'")
        self.text = text

    def describe(self) -> str:
        return f"'{self.text}'"

    def perform(self, context: LaunchContext) -> str:
        return self.text


class LaunchConfiguration(Substitution):
    """The value of a launch configuration (``$(var name)``), with an optional default."""

    def __init__(self, variable_name: Any, *, default: Any = None) -> None:
        self.variable_name = normalize_to_list_of_substitutions(variable_name)
        self.default: list[Substitution] | None = None
        if default is not None:
            items = (
                default
                if isinstance(default, Iterable) and not isinstance(default, str)
                else (default,)
            )
            self.default = normalize_to_list_of_substitutions(
                [x if isinstance(x, (str, Substitution)) else str(x) for x in items]
            )

    def describe(self) -> str:
        return f"LaunchConfig({_describe(self.variable_name)})"

    def perform(self, context: LaunchContext) -> str:
        name = perform_substitutions(context, self.variable_name)
        if name not in context.launch_configurations:
            if self.default is None:
                raise SubstitutionFailure(f"launch configuration '{name}' does not exist")
            return perform_substitutions(context, self.default)
        return str(context.launch_configurations[name])

    def __add__(self, other: Any) -> Any:
        raise TypeError(
            "unsupported operand: a LaunchConfiguration cannot be added to a Python value; "
            "use a list [LaunchConfiguration(...), '...'] or PythonExpression"
        )


class EnvironmentVariable(Substitution):
    """An environment variable of the launch (``$(env NAME [default])``)."""

    def __init__(self, name: Any, *, default_value: Any = None) -> None:
        self.name = normalize_to_list_of_substitutions(name)
        self.default_value = (
            None if default_value is None else normalize_to_list_of_substitutions(default_value)
        )

    def describe(self) -> str:
        return f"EnvVar({_describe(self.name)})"

    def perform(self, context: LaunchContext) -> str:
        default = (
            None
            if self.default_value is None
            else perform_substitutions(context, self.default_value)
        )
        name = perform_substitutions(context, self.name)
        value = context.environment.get(name, default)
        if value is None:
            raise SubstitutionFailure(f"environment variable '{name}' does not exist")
        return value


class FindExecutable(Substitution):
    """The path of an executable on PATH (``$(find-exec name)``).

    ``xacro`` is always found (robomodel runs it in-process), as ``xacro`` when not on PATH.
    """

    def __init__(self, *, name: Any) -> None:
        self.name = normalize_to_list_of_substitutions(name)

    def describe(self) -> str:
        return f"FindExec({_describe(self.name)})"

    def perform(self, context: LaunchContext) -> str:
        name = perform_substitutions(context, self.name)
        found = shutil.which(name, path=context.environment.get("PATH", os.defpath))
        if found is None and name in ("xacro",):
            return name
        if found is None:
            raise SubstitutionFailure(f"executable '{name}' not found on the PATH")
        return found


class PathJoinSubstitution(Substitution):
    """Components joined with ``os.path.join``; ``/`` appends a component (Jazzy)."""

    def __init__(self, substitutions: Any) -> None:
        if isinstance(substitutions, (str, Substitution)):
            substitutions = [substitutions]
        self.components = [normalize_to_list_of_substitutions(c) for c in substitutions]

    @property
    def substitutions(self) -> list[Substitution]:
        """The components, flattened."""
        return [sub for component in self.components for sub in component]

    def describe(self) -> str:
        return f"PathJoin('{_describe(self.substitutions)}')"

    def perform(self, context: LaunchContext) -> str:
        parts = [perform_substitutions(context, component) for component in self.components]
        return os.path.join(*parts) if parts else ""

    def __truediv__(self, additional_path: Any) -> PathJoinSubstitution:
        joined = PathJoinSubstitution([])
        joined.components = [*self.components, normalize_to_list_of_substitutions(additional_path)]
        return joined


class PathSubstitution(PathJoinSubstitution):
    """``PathSubstitution(base) / 'dir' / 'file'`` (launch's pathlib-like wrapper)."""

    def __init__(self, path: Any) -> None:
        super().__init__([path])


class ThisLaunchFileDir(Substitution):
    """The directory of the launch file being executed (``$(dirname)``)."""

    def describe(self) -> str:
        return "ThisLaunchFileDir()"

    def perform(self, context: LaunchContext) -> str:
        value = context.get_locals_as_dict().get("current_launch_file_directory")
        if value is None:
            raise SubstitutionFailure("ThisLaunchFileDir used outside of a launch file")
        return str(value)


class ThisLaunchFile(Substitution):
    """The path of the launch file being executed (``$(filename)``)."""

    def describe(self) -> str:
        return "ThisLaunchFile()"

    def perform(self, context: LaunchContext) -> str:
        value = context.get_locals_as_dict().get("current_launch_file_path")
        if value is None:
            raise SubstitutionFailure("ThisLaunchFile used outside of a launch file")
        return str(value)


class LocalSubstitution(Substitution):
    """A context local, ``LocalSubstitution('event.returncode')`` (attribute path only)."""

    def __init__(self, expression: str, description: str | None = None) -> None:
        self.expression = expression
        self.description = description

    def describe(self) -> str:
        return f"LocalVar('{self.expression if self.description is None else self.description}')"

    def perform(self, context: LaunchContext) -> str:
        value: Any = context.locals
        for part in self.expression.split("."):
            if part.startswith("_") or not hasattr(value, part):
                raise SubstitutionFailure(f"context local '{self.expression}' does not exist")
            value = getattr(value, part)
        return str(value)


class AnonName(Substitution):
    """A name unique to this launch, the same for the same id (``$(anon id)``)."""

    def __init__(self, name: Any) -> None:
        self.name = normalize_to_list_of_substitutions(name)

    def describe(self) -> str:
        return f"AnonName({_describe(self.name)})"

    def perform(self, context: LaunchContext) -> str:
        name = perform_substitutions(context, self.name)
        key = "anon" + name
        if key not in context.launch_configurations:
            value = f"{name}_{socket.gethostname()}_{os.getpid()}_{random.randint(0, 2**63 - 1)}"
            context.launch_configurations[key] = (
                value.replace(".", "_").replace("-", "_").replace(":", "_")
            )
        return str(context.launch_configurations[key])


class FileContent(Substitution):
    """The text of a file (``$(file-content path)``)."""

    def __init__(self, path: Any) -> None:
        self.path = normalize_to_list_of_substitutions(path)

    def describe(self) -> str:
        return f"FileContent({', '.join(s.describe() for s in self.path)})"

    def perform(self, context: LaunchContext) -> str:
        path = perform_substitutions(context, self.path)
        try:
            return read_user_text(path, what="file")
        except UserFileError as exc:
            raise SubstitutionFailure(str(exc)) from None


def split_command(text: str) -> list[str]:
    """Split a command line as launch's ``Command`` does (``shlex.split``)."""
    try:
        return shlex.split(text)
    except ValueError as exc:
        raise SubstitutionFailure(f"cannot split command '{text}': {exc}") from None
