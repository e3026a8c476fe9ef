"""Parameter values as roslaunch makes them: ``type=`` conversion, ``textfile``/``binfile``,
``command`` (xacro in-process), and ``<rosparam>`` YAML with rosparam's ``!degrees``/``!radians``.
"""

from __future__ import annotations

import math
import os
import shlex
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import yaml

from robomodel._files import UserFileError, decode_utf8, read_user_bytes, read_user_text
from robomodel.description.packages import PackageIndex
from robomodel.errors import InputError
from robomodel.launch.processes import COMMAND_TIMEOUT_S, CommandError, run_bounded

__all__ = ["Binary", "ParamValueError", "convert_value", "load_rosparam_yaml", "run_command"]


class ParamValueError(Exception):
    """A parameter value that cannot be made (bad type, missing file, failed command)."""

    def __init__(self, message: str, notes: tuple[str, ...] = ()) -> None:
        super().__init__(message)
        self.notes = notes


@dataclass(frozen=True, slots=True)
class Binary:
    """A ``binfile`` parameter: bytes, as xmlrpclib.Binary carries them."""

    data: bytes


def convert_value(value: str, type_name: str) -> Any:
    """roslaunch's ``loader.convert_value``: ``auto`` infers float (a ``.``), int, bool, str."""
    kind = type_name.lower()
    if kind == "auto":
        try:
            if "." in value:
                return float(value)
            if "_" not in value:
                return int(value)
        except ValueError:
            pass
        if value.lower() in ("true", "false"):
            return convert_value(value, "bool")
        return value
    if kind in ("str", "string"):
        return value
    if kind == "int":
        try:
            return int(value)
        except ValueError:
            raise ParamValueError(f"{value!r} is not an int") from None
    if kind == "double":
        try:
            return float(value)
        except ValueError:
            raise ParamValueError(f"{value!r} is not a double") from None
    if kind in ("bool", "boolean"):
        text = value.lower().strip()
        if text in ("true", "1"):
            return True
        if text in ("false", "0"):
            return False
        raise ParamValueError(f"{text} is not a '{kind}' type")
    if kind == "yaml":
        from robomodel._yaml_bounded import YamlNestingError, load_yaml_file

        try:
            return load_yaml_file(value, where="the yaml value", loader=RosparamLoader)
        except yaml.YAMLError as exc:
            raise ParamValueError(f"invalid YAML: {exc}") from None
        except YamlNestingError as exc:
            raise ParamValueError(f"invalid YAML: {exc.problem}") from None
    raise ParamValueError(
        f"Unknown type '{type_name}'; valid types are auto, str, string, int, double, bool, "
        "boolean, yaml"
    )


class RosparamLoader(yaml.SafeLoader):
    """YAML as rosparam reads it: SafeLoader plus ``!degrees``, ``!radians``, ``deg()``, ``rad()``."""


def _radians(loader: yaml.SafeLoader, node: yaml.Node) -> float:
    text = str(loader.construct_scalar(node)).strip()  # type: ignore[arg-type]
    if text.startswith("rad("):
        text = text[4:-1]
    expr = text.replace("pi", str(math.pi))
    if not all(c in "0123456789.+-*/() e" for c in expr):
        raise yaml.constructor.ConstructorError(None, None, f"invalid radian expression: {text}")
    try:
        return float(eval(expr, {"__builtins__": {}}, {}))  # digits and operators only
    except Exception:
        raise yaml.constructor.ConstructorError(
            None, None, f"invalid radian expression: {text}"
        ) from None


def _degrees(loader: yaml.SafeLoader, node: yaml.Node) -> float:
    text = str(loader.construct_scalar(node))  # type: ignore[arg-type]
    if text.startswith("deg("):
        text = text.strip()[4:-1]
    try:
        return float(text) * math.pi / 180.0
    except ValueError:
        raise yaml.constructor.ConstructorError(
            None, None, f"invalid degree value: {text}"
        ) from None


def _binary(loader: yaml.SafeLoader, node: yaml.Node) -> Binary:
    return Binary(loader.construct_yaml_binary(node))  # type: ignore[arg-type]


RosparamLoader.add_constructor("!radians", _radians)
RosparamLoader.add_constructor("!degrees", _degrees)
RosparamLoader.add_constructor("tag:yaml.org,2002:binary", _binary)
RosparamLoader.add_implicit_resolver(
    "!degrees", __import__("re").compile(r"^deg\([^\)]*\)$"), ["d"]
)
RosparamLoader.add_implicit_resolver(
    "!radians", __import__("re").compile(r"^rad\([^\)]*\)$"), ["r"]
)


def load_rosparam_yaml(text: str, *, where: str = "the <rosparam> block") -> Any:
    """Parse ``<rosparam>`` YAML; an empty document is ``{}`` (as roslaunch). Bounded in size,
    nesting and alias expansion (:func:`robomodel._yaml_bounded.load_yaml_file`)."""
    from robomodel._yaml_bounded import load_yaml_file

    data = load_yaml_file(text, where=where, loader=RosparamLoader)
    return {} if data is None else data


_XACRO_NAMES = ("xacro", "xacro.py")


def _is_xacro(executable: str) -> bool:
    return os.path.basename(executable) in _XACRO_NAMES


def _run_xacro(argv: list[str], packages: PackageIndex, cwd: str) -> str:
    """``xacro FILE [name:=value ...]`` with robomodel's xacro, in this process."""
    from robomodel.xacro import expand

    inputs: list[str] = []
    mappings: dict[str, str] = {}
    for arg in argv:
        if ":=" in arg:
            name, _, value = arg.partition(":=")
            mappings[name] = value
        elif arg in ("--inorder", "-i", "--legacy"):
            continue
        elif arg.startswith("-"):
            raise ParamValueError(f"xacro option {arg} is not supported in a launch command")
        else:
            inputs.append(arg)
    if len(inputs) != 1:
        raise ParamValueError(f"xacro expects exactly one input file, got {inputs}")
    path = inputs[0] if os.path.isabs(inputs[0]) else os.path.join(cwd, inputs[0])
    index = packages.with_workspace_of(path)
    try:
        return expand(path, mappings=mappings, package_index=index).text
    except InputError as exc:
        notes = tuple(note.format() for note in exc.notes)
        raise ParamValueError(exc.diagnostic.format(), notes) from None


def run_command(
    name: str,
    command: str,
    packages: PackageIndex,
    cwd: str | None = None,
    *,
    timeout_s: float = COMMAND_TIMEOUT_S,
) -> str:
    """The output of a ``command=`` parameter.

    ``xacro`` (``$(find xacro)/xacro``, ``xacro.py`` or plain ``xacro``) runs robomodel's xacro
    in this process; anything else runs as a subprocess, split with shlex and no shell, as
    roslaunch does, and must exit 0 within ``timeout_s`` and write at most 64 MiB (roslaunch
    has neither bound; its group is killed when it overruns).
    """
    argv = shlex.split(command)
    if not argv:
        raise ParamValueError(f"Cannot load command parameter [{name}]: empty command")
    where = cwd or os.getcwd()
    if _is_xacro(argv[0]):
        return _run_xacro(argv[1:], packages, where)
    try:
        proc = run_bounded(argv, cwd=where, timeout_s=timeout_s)
    except FileNotFoundError:
        raise ParamValueError(
            f"Cannot load command parameter [{name}]: no such command [{argv[0]}]"
        ) from None
    except PermissionError:
        raise ParamValueError(
            f"Cannot load command parameter [{name}]: [{argv[0]}] is not executable"
        ) from None
    except CommandError as exc:
        raise ParamValueError(f"Cannot load command parameter [{name}]: {argv} {exc}") from None
    if proc.returncode != 0:
        stderr = proc.stderr.decode("utf-8", "replace").strip().splitlines()
        raise ParamValueError(
            f"Cannot load command parameter [{name}]: command {argv} returned with code "
            f"[{proc.returncode}]",
            tuple(stderr[-5:]),
        )
    try:
        return decode_utf8(proc.stdout, f"output of {argv[0]}")
    except UserFileError as exc:
        raise ParamValueError(f"Cannot load command parameter [{name}]: {exc}") from None


def read_text_file(path: str, what: str = "textfile") -> str:
    try:
        return read_user_text(path, what=what)
    except UserFileError as exc:
        raise ParamValueError(str(exc)) from None


def read_binary_file(path: str) -> Binary:
    try:
        return Binary(read_user_bytes(path, what="binfile"))
    except UserFileError as exc:
        raise ParamValueError(str(exc)) from None


def flatten_params(name: str, value: Any, out: dict[str, Any], join: Any) -> None:
    """roslaunch's ``Loader.add_param``: dictionaries become one parameter per leaf."""
    if isinstance(value, Mapping):  # an empty mapping sets nothing, as roslaunch
        for key, item in value.items():
            flatten_params(join(name, str(key)), item, out, join)
    else:
        out[name] = value
