"""``load_launch``: a ROS 2 launch file (Python, XML or YAML) to a :class:`Ros2Launch`."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from robomodel.description.packages import PackageIndex
from robomodel.errors import SourceLocation
from robomodel.launch.model import LaunchError
from robomodel.launch.packages import launch_package_index
from robomodel.launch.processes import COMMAND_TIMEOUT_S
from robomodel.launch.ros2.frontend.xml_frontend import XML_LOADER
from robomodel.launch.ros2.frontend.yaml_frontend import YAML_LOADER
from robomodel.launch.ros2.importer import launch_modules
from robomodel.launch.ros2.model import DeclaredArgument, Ros2Launch
from robomodel.launch.ros2.printing import describe_entities
from robomodel.launch.ros2.python_loader import PYTHON_LOADER
from robomodel.launch.ros2.shim.action import (
    LaunchDescription,
    launch_arguments,
    user_error,
    visit_entities,
)
from robomodel.launch.ros2.shim.actions import IncludeLaunchDescription
from robomodel.launch.ros2.shim.context import LaunchContext, Session, session_scope
from robomodel.launch.ros2.shim.events import EVENTS
from robomodel.launch.ros2.shim.sources import (
    LaunchDescriptionSource,
    LoaderRegistry,
    load_description_file,
    loader_scope,
)
from robomodel.launch.ros2.shim.substitutions import perform_substitutions

__all__ = ["FILE_LOADERS", "load_launch"]

FILE_LOADERS = LoaderRegistry((PYTHON_LOADER, XML_LOADER, YAML_LOADER))
"""The launch file types ``load_launch`` reads, as ``ros2 launch`` does."""


class _Loaded(LaunchDescriptionSource):
    """The top-level file, already loaded (so a Python file runs once)."""

    def __init__(self, path: Path, description: LaunchDescription) -> None:
        super().__init__(str(path))
        self.location = str(path)
        self.description = description

    def get_launch_description(
        self, context: LaunchContext, include_location: Any = None
    ) -> LaunchDescription:
        return self.description

    def try_get_launch_description_without_context(self) -> LaunchDescription | None:
        return self.description


def _arguments(
    description: LaunchDescription, context: LaunchContext
) -> tuple[DeclaredArgument, ...]:
    out = []
    for action, conditional, _ in launch_arguments(description.entities):
        default: str | None = None
        described: str | None = None
        if action.default_value is not None:
            described = " + ".join(sub.describe() for sub in action.default_value)
            try:
                default = perform_substitutions(context, action.default_value)
            except Exception:
                default = described
        out.append(
            DeclaredArgument(
                name=action.name,
                default=default,
                description=action.description,
                choices=None if action.choices is None else tuple(action.choices),
                default_description=described,
                conditional=conditional,
            )
        )
    return tuple(out)


def _visit(
    path: Path, session: Session, env: dict[str, str], args: Mapping[str, str] | None
) -> tuple[tuple[str, ...], tuple[DeclaredArgument, ...]]:
    """Load the top file and visit it as ``ros2 launch`` does: (its description's lines, the
    declared arguments)."""
    with launch_modules(), session_scope(session), loader_scope(FILE_LOADERS):
        context = LaunchContext(session=session, environ=env)
        try:
            description = load_description_file(path, "any")
        except LaunchError:
            raise
        except Exception as exc:
            raise user_error(exc, SourceLocation(str(path))) from None
        lines = tuple(describe_entities(description.entities))
        top = IncludeLaunchDescription(
            _Loaded(path, description), launch_arguments=list((args or {}).items())
        )
        visit_entities(context, [top])
        return lines, _arguments(description, context)


def load_launch(
    path: Path,
    *,
    args: Mapping[str, str] | None = None,
    packages: PackageIndex | None = None,
    environ: Mapping[str, str] | None = None,
    command_timeout_s: float = COMMAND_TIMEOUT_S,
) -> Ros2Launch:
    """Load a ROS 2 launch file and work out what ``ros2 launch`` would start.

    Args:
        path: A ``.launch.py`` / ``.launch.xml`` / ``.launch.yaml`` file (by suffix; plain
            ``.py`` / ``.xml`` / ``.yaml`` too).
        args: Command-line launch arguments (``name:=value``), as ``ros2 launch`` passes them
            to the top-level include.
        packages: Where packages are found (robomodel's shipped ones are added last, and the
            workspace around ``path``).
        environ: The launch environment (default ``os.environ``; never modified).
        command_timeout_s: The longest a ``$(command ...)`` / ``Command`` may run.

    Returns:
        The declared arguments, the steps in start order and the files loaded.

    Raises:
        LaunchError: for every problem in a launch file, at file:line with the include stack.
    """
    path = Path(os.path.abspath(path))
    env = dict(os.environ if environ is None else environ)
    index = packages if packages is not None else PackageIndex(environ=env)
    session = Session(
        packages=launch_package_index(index).with_workspace_of(path),
        command_timeout_s=command_timeout_s,
        events=EVENTS,
    )
    try:
        lines, arguments = _visit(path, session, env, args)
    except BaseException:
        for temporary in session.temporary_files:  # nothing will read them
            temporary.unlink(missing_ok=True)
        raise
    return Ros2Launch(
        path=path,
        arguments=arguments,
        steps=tuple(session.steps),
        files=tuple(session.files),
        warnings=tuple(session.warnings),
        description=lines,
        temporary_files=tuple(session.temporary_files),
    )
