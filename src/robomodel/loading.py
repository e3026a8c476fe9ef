"""Loading a robot description from a ``.urdf`` or a ``.xacro`` file, or from text.

This sits above the description and xacro layers: a path ending in ``.xacro`` (or text that
declares the xacro namespace) is expanded first, then parsed as URDF.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

from robomodel.description.model import Robot
from robomodel.description.packages import PackageIndex
from robomodel.description.urdf.reader import ParseResult, read_urdf

__all__ = ["LoadedDescription", "expand_description", "is_xacro", "load", "read_description"]


@dataclass(frozen=True, slots=True)
class LoadedDescription:
    """URDF text ready to parse, where it came from, and the files it was built from."""

    urdf: bytes
    path: str | None
    base_dir: Path
    is_xacro: bool
    dependencies: tuple[str, ...]


def is_xacro(source: str | os.PathLike[str]) -> bool:
    """True for a path ending in ``.xacro`` or XML text declaring the xacro namespace."""
    text = os.fspath(source)
    if text.lstrip().startswith("<"):
        return "xmlns:xacro" in text
    return text.endswith(".xacro")


def expand_description(
    source: str | os.PathLike[str],
    *,
    args: Mapping[str, str] | None = None,
    package_index: PackageIndex | None = None,
) -> LoadedDescription:
    """Return URDF bytes for a URDF/xacro path or text, running xacro when needed."""
    index = package_index or PackageIndex()
    text = os.fspath(source)
    inline = text.lstrip().startswith("<")
    if not is_xacro(source):
        if inline:
            return LoadedDescription(text.encode(), None, Path.cwd(), False, ())
        path = Path(text)
        from robomodel._files import read_user_bytes

        data = read_user_bytes(path, what="robot description")
        return LoadedDescription(data, text, Path(os.path.abspath(path)).parent, False, ())
    from robomodel import xacro  # not at the top: a plain URDF does not need the xacro layer

    if inline:
        expanded = xacro.process(text, dict(args or {}), package_index=index)
        return LoadedDescription(expanded.encode(), None, Path.cwd(), True, ())
    index = index.with_workspace_of(text)
    result = xacro.expand(text, mappings=dict(args or {}), package_index=index)
    return LoadedDescription(
        result.text.encode(), text, Path(os.path.abspath(text)).parent, True, result.includes
    )


def read_description(
    source: str | os.PathLike[str],
    *,
    args: Mapping[str, str] | None = None,
    package_index: PackageIndex | None = None,
) -> tuple[ParseResult, LoadedDescription]:
    """Expand (if xacro) and parse a description, keeping its diagnostics."""
    loaded = expand_description(source, args=args, package_index=package_index)
    name = loaded.path
    if loaded.is_xacro and name is not None:
        name = f"{name} (expanded)"
    return read_urdf(loaded.urdf, path=name), loaded


def load(
    path_or_text: str | os.PathLike[str],
    *,
    args: Mapping[str, str] | None = None,
    package_paths: Sequence[str | os.PathLike[str]] = (),
    packages: Mapping[str, str | os.PathLike[str]] | None = None,
) -> Robot:
    """Load a robot model from a ``.urdf`` or ``.xacro`` file, or from URDF/xacro text.

    Args:
        path_or_text: A file path, or the document itself (text starting with ``<``).
        args: xacro arguments (``name:=value`` on the command line).
        package_paths: Directories to search for ROS packages (``$(find)``, ``package://``).
        packages: Explicit package name to directory mappings.

    Raises:
        InputError: the description is invalid (with file:line:column).
    """
    index = PackageIndex(package_paths=package_paths, packages=packages)
    result, _ = read_description(path_or_text, args=args, package_index=index)
    return result.robot
