"""Substitutions that reach outside the launch file: commands, Python expressions, packages."""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.launch.processes import CommandError, run_bounded
from robomodel.launch.ros2.shim.context import LaunchContext, SubstitutionFailure, current_session
from robomodel.launch.ros2.shim.substitutions import (
    PathJoinSubstitution,
    Substitution,
    _describe,
    normalize_to_list_of_substitutions,
    perform_substitutions,
    split_command,
)
from robomodel.xacro._evaluation import _BUILTINS
from robomodel.xacro._safe_eval import ExpressionError, Guards, Limits, compile_expression, evaluate
from robomodel.xacro._symbols import ReadOnlyNamespace

__all__ = [
    "Command",
    "ExecutableInPackage",
    "FindPackage",
    "FindPackagePrefix",
    "FindPackageShare",
    "PackageNotFoundError",
    "PythonExpression",
    "get_package_prefix",
    "get_package_share_directory",
    "get_package_share_path",
    "run_xacro",
]


class PackageNotFoundError(KeyError):
    """``ament_index_python.packages.PackageNotFoundError``."""


def _index() -> Any:
    session = current_session()
    if session is None:
        raise SubstitutionFailure("package lookups only work while robomodel loads a launch file")
    return session.packages


def get_package_share_directory(package_name: str, print_warning: bool = True) -> str:
    """The share directory of a package (its source directory for a source workspace)."""
    try:
        return str(_index().find(package_name))
    except RobomodelError as exc:
        raise PackageNotFoundError(str(exc)) from None


def get_package_share_path(package_name: str, print_warning: bool = True) -> Path:
    """:func:`get_package_share_directory` as a ``pathlib.Path``."""
    return Path(get_package_share_directory(package_name))


def get_package_prefix(package_name: str) -> str:
    """The install prefix of a package: ``<prefix>`` of ``<prefix>/share/<name>``.

    A package found in a source tree (no ``share/<name>`` layout) is its own prefix.
    """
    share = Path(get_package_share_directory(package_name))
    if share.parent.name == "share" and share.name == package_name:
        return str(share.parent.parent)
    return str(share)


def run_xacro(argv: list[str], context: LaunchContext) -> str:
    """Run ``xacro FILE [name:=value ...]`` with robomodel's xacro; return its stdout text."""
    from robomodel import xacro

    mappings: dict[str, str] = {}
    inputs: list[str] = []
    skip = False
    for token in argv[1:]:
        if skip:
            skip = False
        elif token in ("-o", "--output"):
            skip = True
        elif token.startswith("-"):
            continue
        elif ":=" in token:
            name, _, value = token.partition(":=")
            mappings[name] = value
        else:
            inputs.append(token)
    if len(inputs) != 1:
        raise SubstitutionFailure(f"xacro expects one input file, got: {' '.join(argv)}")
    try:
        doc = xacro.process_file(inputs[0], mappings, package_index=context.session.packages)
        return doc.toprettyxml(indent="  ")
    except RobomodelError as exc:
        raise SubstitutionFailure(
            f"executed command failed. Command: {' '.join(argv)}\n{exc}"
        ) from None


class Command(Substitution):
    """The standard output of a command (``$(command '...')``).

    ``xacro`` (by name, ``FindExecutable(name='xacro')`` or a path ending in ``/xacro``) runs
    robomodel's xacro in this process; other commands run as subprocesses with the launch's
    environment. ``on_stderr`` is ``fail`` (default), ``ignore``, ``warn`` or ``capture``.
    """

    def __init__(self, command: Any, *, on_stderr: Any = "fail") -> None:
        self.command = normalize_to_list_of_substitutions(command)
        self.on_stderr = normalize_to_list_of_substitutions(on_stderr)

    def describe(self) -> str:
        return f"Command({_describe(self.command)})"

    def perform(self, context: LaunchContext) -> str:
        command_str = perform_substitutions(context, self.command)
        argv = split_command(command_str)
        on_stderr = perform_substitutions(context, self.on_stderr)
        if on_stderr not in ("fail", "ignore", "warn", "capture"):
            raise SubstitutionFailure(
                "expected 'on_stderr' to be one of: 'fail', 'ignore', 'warn' or 'capture'"
            )
        if argv and os.path.basename(argv[0]) in ("xacro", "xacro.py"):
            return run_xacro(argv, context)
        try:
            result = run_bounded(
                argv,
                env=context.environment,
                merge_stderr=on_stderr == "capture",
                timeout_s=context.session.command_timeout_s,
            )
        except (FileNotFoundError, PermissionError) as ex:
            raise SubstitutionFailure(f"file not found: {ex}") from None
        except CommandError as exc:
            raise SubstitutionFailure(f"command {command_str!r} {exc}") from None
        stdout = result.stdout.decode("utf-8", "replace")
        stderr = result.stderr.decode("utf-8", "replace")
        if result.returncode != 0:
            message = f"executed command failed. Command: {command_str}"
            if stderr:
                message += f"\nCaptured stderr output: {stderr}"
            raise SubstitutionFailure(message)
        if stderr:
            message = (
                f"executed command showed stderr output. Command: {command_str}\n"
                f"Captured stderr output:\n{stderr}"
            )
            if on_stderr == "fail":
                raise SubstitutionFailure(message)
            if on_stderr == "warn":
                context.session.warn(message)
        return stdout


_ALLOWED_MODULES = {"math"}


def _math_namespace() -> dict[str, object]:
    return {k: v for k, v in vars(math).items() if not k.startswith("_")}


class PythonExpression(Substitution):
    """A Python expression's value as text (``$(eval '...')``), by robomodel's safe evaluator.

    As in launch, ``math``'s names are available directly and as ``math.<name>``; the
    expression sees the builtins the xacro evaluator allows (``str``, ``int``, ``len``, ...).
    Modules other than ``math`` in ``python_modules`` are refused.
    """

    def __init__(self, expression: Any, python_modules: Any = ("math",)) -> None:
        self.expression = normalize_to_list_of_substitutions(expression)
        self.python_modules = normalize_to_list_of_substitutions(
            list(python_modules)
            if not isinstance(python_modules, (str, Substitution))
            else python_modules
        )

    def describe(self) -> str:
        modules = ", ".join(sub.describe() for sub in self.python_modules)
        return f"PythonExpr({_describe(self.expression)}, [{modules}])"

    def perform(self, context: LaunchContext) -> str:
        names: dict[str, object] = dict(_BUILTINS)
        names.update({"True": True, "False": False, "None": None})
        for sub in self.python_modules:
            module = context.perform_substitution(sub).strip()
            if module not in _ALLOWED_MODULES:
                raise SubstitutionFailure(
                    f"PythonExpression: module '{module}' is not available in robomodel's safe "
                    f"evaluator (available: {', '.join(sorted(_ALLOWED_MODULES))})"
                )
            names.update(_math_namespace())
            names["math"] = ReadOnlyNamespace("math", _math_namespace())
        text = perform_substitutions(context, self.expression)
        guards = Guards(Limits())

        def lookup(name: str) -> object:
            if name in names:
                return names[name]
            raise NameError(f"name '{name}' is not defined")

        try:
            value = evaluate(compile_expression(text.strip()), lookup, guards, guards.functions())
        except ExpressionError as exc:
            raise SubstitutionFailure(f"PythonExpression '{text}': {exc}") from None
        except SyntaxError as exc:
            raise SubstitutionFailure(
                f"PythonExpression '{text}': invalid syntax ({exc.msg})"
            ) from None
        except Exception as exc:  # the expression's own error (ZeroDivisionError, TypeError, ...)
            raise SubstitutionFailure(
                f"PythonExpression '{text}': {type(exc).__name__}: {exc}"
            ) from None
        return str(value)


class FindPackage(Substitution):
    """Base of the package substitutions (``launch_ros.substitutions.FindPackage``)."""

    def __init__(self, package: Any) -> None:
        self.package = normalize_to_list_of_substitutions(package)

    def find(self, package_name: str) -> str:
        """Where the package is."""
        raise NotImplementedError

    def describe(self) -> str:
        return f"Pkg(pkg={_describe(self.package)})"

    def perform(self, context: LaunchContext) -> str:
        name = perform_substitutions(context, self.package)
        try:
            return self.find(name)
        except PackageNotFoundError as exc:
            raise SubstitutionFailure(str(exc.args[0])) from None

    def __truediv__(self, other: Any) -> Any:
        return PathJoinSubstitution([self]) / other


class FindPackagePrefix(FindPackage):
    """The install prefix of a package (``$(find-pkg-prefix pkg)``)."""

    def find(self, package_name: str) -> str:
        return get_package_prefix(package_name)


class FindPackageShare(FindPackage):
    """The share directory of a package (``$(find-pkg-share pkg)``)."""

    def find(self, package_name: str) -> str:
        return get_package_share_directory(package_name)


class ExecutableInPackage(FindPackagePrefix):
    """``<prefix>/lib/<package>/<executable>`` (``$(exec-in-pkg exe pkg)``)."""

    def __init__(self, executable: Any, package: Any) -> None:
        super().__init__(package)
        self.executable = normalize_to_list_of_substitutions(executable)

    def perform(self, context: LaunchContext) -> str:
        prefix = super().perform(context)
        package = perform_substitutions(context, self.package)
        return os.path.join(prefix, "lib", package, perform_substitutions(context, self.executable))
