"""``launch.launch_description_sources``: where an included launch description comes from.

The readers of the three launch file types (Python, XML and YAML) are not imported here: they
build descriptions out of the actions, which include descriptions through these sources.
``load_launch`` hands them to the load as a :class:`LoaderRegistry` keyed by file type
(upstream finds its front-ends through entry points the same way, by name), made current with
:func:`loader_scope` as the session is.
"""

from __future__ import annotations

import contextvars
import os
from collections.abc import Callable, Iterable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from robomodel.errors import SourceLocation
from robomodel.launch.bounds import INCLUDE_WORK
from robomodel.launch.ros2.shim.action import LaunchDescription
from robomodel.launch.ros2.shim.context import (
    LaunchContext,
    SubstitutionFailure,
    WorkBoundError,
    current_session,
)
from robomodel.launch.ros2.shim.substitutions import (
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

__all__ = [
    "AnyLaunchDescriptionSource",
    "FileLoader",
    "FrontendLaunchDescriptionSource",
    "LaunchDescriptionSource",
    "LoaderRegistry",
    "PythonLaunchDescriptionSource",
    "XMLLaunchDescriptionSource",
    "YAMLLaunchDescriptionSource",
    "load_description_file",
    "loader_scope",
]


@dataclass(frozen=True, slots=True)
class FileLoader:
    """How one launch file type becomes a LaunchDescription.

    Attributes:
        kind: The file type (``python``, ``xml``, ``yaml``), as the sources name it.
        suffixes: The lower-case suffixes that mean this type (``.py``).
        load: Reads the file (errors as LaunchError at file:line).
    """

    kind: str
    suffixes: tuple[str, ...]
    load: Callable[[Path], LaunchDescription]


class LoaderRegistry:
    """The file loaders of a launch, keyed by file type (see the module docstring)."""

    def __init__(self, loaders: Iterable[FileLoader]) -> None:
        self._loaders: Mapping[str, FileLoader] = {loader.kind: loader for loader in loaders}

    def kind_of(self, path: Path) -> str:
        """The file type of ``path`` by its suffix."""
        suffix = path.suffix.lower()
        for loader in self._loaders.values():
            if suffix in loader.suffixes:
                return loader.kind
        names = [loader.suffixes[0] for loader in self._loaders.values()]
        expected = " or ".join([", ".join(names[:-1]), names[-1]] if len(names) > 1 else names)
        raise SubstitutionFailure(
            f"cannot tell the launch file type of '{path}' (expected {expected})"
        )

    def loader(self, kind: str) -> FileLoader:
        """The loader of file type ``kind``."""
        try:
            return self._loaders[kind]
        except KeyError:
            known = ", ".join(sorted(self._loaders)) or "none"
            raise SubstitutionFailure(
                f"no loader for {kind} launch files (this load reads: {known})"
            ) from None


_LOADERS: contextvars.ContextVar[LoaderRegistry | None] = contextvars.ContextVar(
    "robomodel_ros2_launch_loaders", default=None
)


@contextmanager
def loader_scope(loaders: LoaderRegistry) -> Iterator[LoaderRegistry]:
    """Make ``loaders`` the file loaders of the sources used inside."""
    token = _LOADERS.set(loaders)
    try:
        yield loaders
    finally:
        _LOADERS.reset(token)


def load_description_file(path: Path, kind: str, *, record: bool = True) -> LaunchDescription:
    """Load a launch file as a LaunchDescription: ``kind`` is python, xml, yaml or any."""
    loaders = _LOADERS.get()
    if loaders is None:
        raise SubstitutionFailure(
            f"cannot load '{path}': launch files are loaded inside "
            "robomodel.launch.ros2.load_launch"
        )
    session = current_session()
    if kind == "any":
        kind = loaders.kind_of(path)
    loader = loaders.loader(kind)
    if not path.is_file():
        raise SubstitutionFailure(f"launch file '{path}' does not exist")
    if session is not None:
        # every read counts, also the static walks for required arguments (the fan-out bound)
        session.charge(INCLUDE_WORK, SourceLocation(str(path)))
        if record and path not in session.files:
            session.files.append(path)
    return loader.load(path)


class LaunchDescriptionSource:
    """A launch description from a file path given as substitutions."""

    kind = "any"

    def __init__(self, launch_file_path: Any = None, method: str = "") -> None:
        if isinstance(launch_file_path, os.PathLike):
            launch_file_path = os.fspath(launch_file_path)
        self.path_subs = normalize_to_list_of_substitutions(launch_file_path)
        self.location = "<not yet substituted>"
        self.method = method or f"interpreted {self.kind} launch file"

    def get_launch_description(
        self, context: LaunchContext, include_location: SourceLocation | None = None
    ) -> LaunchDescription:
        """Substitute the path and load the file."""
        path = Path(perform_substitutions(context, self.path_subs))
        self.location = str(path)
        return load_description_file(path, self.kind)

    def try_get_launch_description_without_context(self) -> LaunchDescription | None:
        """The description if the path needs no context (for ``--show-args``), else None."""
        try:
            context = LaunchContext()
            path = Path(perform_substitutions(context, self.path_subs))
            return load_description_file(path, self.kind, record=False)
        except WorkBoundError:
            raise
        except Exception:
            return None


class PythonLaunchDescriptionSource(LaunchDescriptionSource):
    """A Python launch file."""

    kind = "python"


class FrontendLaunchDescriptionSource(LaunchDescriptionSource):
    """An XML or YAML launch file, by its suffix."""

    kind = "any"


class XMLLaunchDescriptionSource(LaunchDescriptionSource):
    """An XML launch file."""

    kind = "xml"


class YAMLLaunchDescriptionSource(LaunchDescriptionSource):
    """A YAML launch file."""

    kind = "yaml"


class AnyLaunchDescriptionSource(LaunchDescriptionSource):
    """A launch file of any type, by its suffix."""

    kind = "any"
