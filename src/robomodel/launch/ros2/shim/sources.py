"""``launch.launch_description_sources``: where an included launch description comes from."""

from __future__ import annotations

import os
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
    "FrontendLaunchDescriptionSource",
    "LaunchDescriptionSource",
    "PythonLaunchDescriptionSource",
    "XMLLaunchDescriptionSource",
    "YAMLLaunchDescriptionSource",
    "load_description_file",
]

_PYTHON = (".py",)
_XML = (".xml",)
_YAML = (".yaml", ".yml")


def load_description_file(path: Path, kind: str, *, record: bool = True) -> LaunchDescription:
    """Load a launch file as a LaunchDescription: ``kind`` is python, xml, yaml or any."""
    session = current_session()
    if kind == "any":
        suffix = path.suffix.lower()
        kind = (
            "python"
            if suffix in _PYTHON
            else "xml"
            if suffix in _XML
            else "yaml"
            if suffix in _YAML
            else "any"
        )
        if kind == "any":
            raise SubstitutionFailure(
                f"cannot tell the launch file type of '{path}' (expected .py, .xml or .yaml)"
            )
    if not path.is_file():
        raise SubstitutionFailure(f"launch file '{path}' does not exist")
    if session is not None:
        # every read counts, also the static walks for required arguments (the fan-out bound)
        session.charge(INCLUDE_WORK, SourceLocation(str(path)))
        if record and path not in session.files:
            session.files.append(path)
    if kind == "python":
        from robomodel.launch.ros2.python_loader import load_python_description

        return load_python_description(path)
    if kind == "xml":
        from robomodel.launch.ros2.frontend.xml_frontend import load_xml_description

        return load_xml_description(path)
    from robomodel.launch.ros2.frontend.yaml_frontend import load_yaml_description

    return load_yaml_description(path)


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
