"""A user's executables, found as ``ros2 run`` and ``rosrun`` find them, with no build step.

- **install prefix** (a package found through ``AMENT_PREFIX_PATH``, ``<prefix>/share/PKG``):
  the file ``<prefix>/lib/PKG/EXEC``, as ``ros2 run`` looks there;
- **ament_python source package**: the ``console_scripts`` entry points of ``setup.py`` (read
  with :mod:`ast`, never run) or of ``setup.cfg``'s ``[options.entry_points]``: the entry
  ``EXEC = module.sub:function`` runs ``function`` with the package folder on ``sys.path``, as
  ``colcon build`` would have installed it;
- **catkin, ament_cmake and other source packages**: any file named ``EXEC`` below the package
  (``rosrun``'s ``find -name EXEC``), so ``rospy_tutorials/001_talker_listener/talker.py`` runs
  as ``rosrun rospy_tutorials talker.py``. Two such files are ambiguous, as for rosrun.

A Python file runs with robomodel's interpreter; a compiled node (an ELF file, or a name that
CMakeLists.txt's ``add_executable`` builds from C++ sources) cannot run here:
:class:`CompiledNodeError` says so in one line.
"""

from __future__ import annotations

import ast
import configparser
import os
import re
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

from robomodel.errors import RobomodelError, describe_unknown

__all__ = [
    "AmbiguousExecutableError",
    "BuildType",
    "CompiledNodeError",
    "ExecutableNotFoundError",
    "UserExecutable",
    "build_type",
    "executable_names",
    "find_executable",
]

BuildType = Literal["ament_python", "ament_cmake", "catkin", "install"]

_SKIPPED_DIRS = frozenset({".git", ".svn", ".hg", "__pycache__", "build", "devel", "install"})
_MAX_DEPTH = 8


class ExecutableNotFoundError(RobomodelError):
    """The package has no executable of that name (``available``: the names it has)."""

    def __init__(self, message: str, *, package: str, name: str, available: tuple[str, ...]):
        self.package = package
        self.name = name
        self.available = available
        super().__init__(message)


class AmbiguousExecutableError(RobomodelError):
    """More than one file of that name in a source package (rosrun asks which; we refuse)."""


class CompiledNodeError(RobomodelError):
    """A C++ (compiled) node: robomodel runs Python nodes only."""

    def __init__(self, package: str, name: str, why: str) -> None:
        self.package = package
        self.name = name
        super().__init__(
            f"{package}/{name} is a C++ node ({why}): robomodel runs Python nodes (rclpy, "
            "rospy); a C++ node needs ROS 2 and colcon build (or ROS 1 and catkin_make)"
        )


@dataclass(frozen=True, slots=True)
class UserExecutable:
    """One executable of a user's package and how to start it.

    Attributes:
        package: The package name.
        name: The executable's name (``ros2 run``'s EXEC, ``rosrun``'s TYPE).
        build_type: How the package is built (which decides the message flavour).
        path: The file to run (None for a ``console_scripts`` entry point).
        entry_point: ``module.sub:function`` of a ``console_scripts`` entry.
        source_dir: The folder an entry point's module is imported from.
    """

    package: str
    name: str
    build_type: BuildType
    path: Path | None = None
    entry_point: str | None = None
    source_dir: Path | None = None

    @property
    def flavour(self) -> str:
        """The message classes the node gets: genpy's for catkin packages, rosidl's else."""
        return "genpy" if self.build_type == "catkin" else "rosidl"

    def command(self, python: str = sys.executable) -> list[str]:
        """The command line that starts it (its own arguments are appended by the caller)."""
        if self.entry_point is not None:
            module, _, function = self.entry_point.partition(":")
            attribute = function.strip() or "main"
            code = (
                f"import sys; sys.argv[0] = {self.name!r}; "
                f"from {module.strip()} import {attribute.split('.')[0]} as _entry; "
                f"sys.exit(_entry{attribute[len(attribute.split('.')[0]) :]}())"
            )
            return [python, "-c", code]
        assert self.path is not None  # one of path / entry_point is set (find_executable)
        if _is_python(self.path):
            return [python, str(self.path)]
        return [str(self.path)]

    def pythonpath(self) -> tuple[str, ...]:
        """Folders the node's imports need first on ``sys.path``."""
        return (str(self.source_dir),) if self.source_dir is not None else ()


_BUILD_TYPE_RE = re.compile(rb"<build_type>\s*([A-Za-z_]+)\s*</build_type>")


def build_type(package_dir: Path) -> BuildType:
    """The package's build type from its ``package.xml`` (``<build_type>`` in ``<export>``;
    ``catkin`` for a ``<buildtool_depend>catkin``; ``ament_cmake``, rosidl's default, else)."""
    try:
        manifest = (package_dir / "package.xml").read_bytes()[:200_000]
    except OSError:
        manifest = b""
    found = _BUILD_TYPE_RE.search(manifest)
    if found is not None:
        kind = found.group(1).decode()
        if kind == "ament_python":
            return "ament_python"
        if kind == "catkin":
            return "catkin"
        return "ament_cmake"
    if b"catkin</buildtool_depend>" in manifest.replace(b" ", b""):
        return "catkin"
    if (package_dir / "setup.py").is_file() and not (package_dir / "CMakeLists.txt").is_file():
        return "ament_python"
    return "ament_cmake"


def _install_prefix(package: str, package_dir: Path) -> Path | None:
    """``<prefix>`` when ``package_dir`` is ``<prefix>/share/<package>``."""
    if package_dir.parent.name == "share" and package_dir.name == package:
        return package_dir.parent.parent
    return None


def _colcon_source(prefix: Path, package: str) -> Path | None:
    """The source folder of an installed package in a colcon workspace (``install/`` or
    ``install/<pkg>/`` beside ``src/``), to tell a C++ target apart from a missing name."""
    from robomodel.description.packages import PackageIndex
    from robomodel.errors import PackageNotFoundError

    for workspace in (prefix.parent, prefix.parent.parent):
        if (workspace / "src").is_dir():
            index = PackageIndex(package_paths=[workspace / "src"], use_environment=False)
            try:
                return index.find(package)
            except PackageNotFoundError:
                return None
    return None


def console_scripts(package_dir: Path) -> dict[str, str]:
    """``name -> module:function`` of the package's ``console_scripts`` (setup.py, setup.cfg)."""
    found: dict[str, str] = {}
    setup_cfg = package_dir / "setup.cfg"
    if setup_cfg.is_file():
        parser = configparser.ConfigParser()
        try:
            parser.read(setup_cfg, encoding="utf-8")
            text = parser.get("options.entry_points", "console_scripts", fallback="")
        except configparser.Error:
            text = ""
        found.update(_entries(text.splitlines()))
    setup_py = package_dir / "setup.py"
    if setup_py.is_file():
        found.update(_setup_py_scripts(setup_py))
    return found


def _entries(lines: list[str]) -> dict[str, str]:
    entries: dict[str, str] = {}
    for line in lines:
        name, sep, target = line.partition("=")
        if sep and name.strip() and target.strip():
            entries[name.strip()] = target.strip()
    return entries


def _setup_py_scripts(path: Path) -> dict[str, str]:
    """``entry_points={'console_scripts': [...]}`` in the ``setup()`` call, read as literals
    (module-level names assigned a literal, such as ``package_name``, are substituted)."""
    try:
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    except (OSError, SyntaxError, ValueError):
        return {}
    names: dict[str, object] = {}
    for statement in tree.body:
        if isinstance(statement, ast.Assign) and len(statement.targets) == 1:
            target = statement.targets[0]
            if isinstance(target, ast.Name):
                value = _literal(statement.value, names)
                if value is not None:
                    names[target.id] = value
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        for keyword in node.keywords:
            if keyword.arg != "entry_points":
                continue
            value = _literal(keyword.value, names)
            if isinstance(value, dict):
                scripts = value.get("console_scripts", [])
                lines = scripts.splitlines() if isinstance(scripts, str) else list(scripts)
                return _entries([str(line) for line in lines])
    return {}


def _literal(node: ast.expr, names: dict[str, object]) -> object:
    """A literal expression's value, with known names and f-strings / ``+`` of strings."""
    if isinstance(node, ast.Name):
        return names.get(node.id)
    if isinstance(node, ast.JoinedStr):
        parts = []
        for value in node.values:
            if isinstance(value, ast.FormattedValue):
                part = _literal(value.value, names)
                if part is None:
                    return None
                parts.append(str(part))
            else:
                parts.append(str(_literal(value, names)))
        return "".join(parts)
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
        left, right = _literal(node.left, names), _literal(node.right, names)
        return left + right if isinstance(left, str) and isinstance(right, str) else None
    if isinstance(node, ast.Dict):
        keys = [_literal(k, names) if k is not None else None for k in node.keys]
        values = [_literal(v, names) for v in node.values]
        return dict(zip(keys, values, strict=True))
    if isinstance(node, ast.List | ast.Tuple):
        return [_literal(element, names) for element in node.elts]
    try:
        return ast.literal_eval(node)
    except ValueError:
        return None


def _files_named(root: Path, name: str) -> list[Path]:
    """Every file called ``name`` below ``root`` (rosrun's find), sorted."""
    found: list[Path] = []
    for folder, subdirs, files in os.walk(root, followlinks=True):
        depth = len(Path(folder).relative_to(root).parts)
        subdirs[:] = sorted(d for d in subdirs if d not in _SKIPPED_DIRS and not d.startswith("."))
        if depth >= _MAX_DEPTH:
            subdirs[:] = []
        if name in files and os.path.isfile(os.path.join(folder, name)):
            found.append(Path(folder) / name)
    return sorted(found)


def _runnable_files(root: Path) -> list[str]:
    """The names of the files ``rosrun`` could run below ``root`` (executable ones)."""
    names: set[str] = set()
    for folder, subdirs, files in os.walk(root, followlinks=True):
        depth = len(Path(folder).relative_to(root).parts)
        subdirs[:] = [d for d in subdirs if d not in _SKIPPED_DIRS and not d.startswith(".")]
        if depth >= _MAX_DEPTH:
            subdirs[:] = []
        for name in files:
            path = os.path.join(folder, name)
            if os.access(path, os.X_OK) and os.path.isfile(path):
                names.add(name)
    return sorted(names)


def _is_python(path: Path) -> bool:
    if path.suffix == ".py":
        return True
    try:
        with open(path, "rb") as handle:
            head = handle.readline(256)
    except OSError:
        return False
    return head.startswith(b"#!") and b"python" in head


def _is_compiled(path: Path) -> bool:
    try:
        with open(path, "rb") as handle:
            return handle.read(4) == b"\x7fELF"
    except OSError:
        return False


_ADD_EXECUTABLE_RE = re.compile(r"add_executable\s*\(\s*([A-Za-z0-9_.${}-]+)([^)]*)\)", re.S)


def _cmake_targets(package_dir: Path) -> dict[str, str]:
    """``add_executable(NAME sources...)`` targets of CMakeLists.txt: name -> its sources."""
    try:
        text = (package_dir / "CMakeLists.txt").read_text(encoding="utf-8", errors="replace")
    except OSError:
        return {}
    text = re.sub(r"#[^\n]*", "", text)
    return {m.group(1): m.group(2).strip() for m in _ADD_EXECUTABLE_RE.finditer(text)}


def executable_names(package: str, package_dir: Path) -> tuple[str, ...]:
    """The executables a package offers (for error messages and ``--help``)."""
    prefix = _install_prefix(package, package_dir)
    if prefix is not None:
        return tuple(_runnable_files(prefix / "lib" / package))
    names = set(console_scripts(package_dir)) | set(_cmake_targets(package_dir))
    names.update(_runnable_files(package_dir))
    return tuple(sorted(names))


def find_executable(package: str, name: str, package_dir: Path) -> UserExecutable:
    """The executable ``name`` of ``package`` (found at ``package_dir``), as ros2 run / rosrun
    find it (see the module docstring).

    Raises:
        ExecutableNotFoundError: no such executable (the message lists the package's).
        AmbiguousExecutableError: several files of that name in a source package.
        CompiledNodeError: it is a compiled (C++) node.
    """
    kind = build_type(package_dir)
    prefix = _install_prefix(package, package_dir)
    if prefix is not None:
        path = prefix / "lib" / package / name
        if path.is_file():
            return _checked(UserExecutable(package, name, "install", path=path))
        source = _colcon_source(prefix, package)
        if source is not None and name in _cmake_targets(source):
            raise CompiledNodeError(
                package,
                name,
                f"{source}/CMakeLists.txt builds it with add_executable from "
                f"{_cmake_targets(source)[name] or 'its sources'}",
            )
    else:
        scripts = console_scripts(package_dir)
        if name in scripts:
            source = package_dir
            return UserExecutable(
                package, name, "ament_python", entry_point=scripts[name], source_dir=source
            )
        matches = _files_named(package_dir, name)
        runnable = [m for m in matches if os.access(m, os.X_OK) or _is_python(m)]
        if len(runnable) > 1:
            listing = ", ".join(str(m) for m in runnable)
            raise AmbiguousExecutableError(
                f"More than one executable named {name} in package {package}: {listing}; "
                "rename one, or run the file you mean with python"
            )
        if runnable:
            return _checked(UserExecutable(package, name, kind, path=runnable[0]))
        targets = _cmake_targets(package_dir)
        if name in targets:
            sources = targets[name] or "its sources"
            raise CompiledNodeError(
                package, name, f"CMakeLists.txt builds it with add_executable from {sources}"
            )
    names = executable_names(package, package_dir)
    where = prefix / "lib" / package if prefix is not None else package_dir
    raise ExecutableNotFoundError(
        describe_unknown(
            f"package '{package}' ({where}) has no executable",
            name,
            names,
            f"{package}'s executables are",
        ),
        package=package,
        name=name,
        available=names,
    )


def _checked(found: UserExecutable) -> UserExecutable:
    assert found.path is not None
    if _is_compiled(found.path):
        raise CompiledNodeError(found.package, found.name, f"{found.path} is a compiled program")
    if not _is_python(found.path) and not os.access(found.path, os.X_OK):
        raise ExecutableNotFoundError(
            f"{found.path} is neither a Python file nor executable (chmod +x it)",
            package=found.package,
            name=found.name,
            available=(),
        )
    return found
