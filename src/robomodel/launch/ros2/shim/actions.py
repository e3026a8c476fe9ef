"""``launch.actions``: the actions of the ``launch`` package.

The launch-configuration actions are defined in :mod:`.configuration_actions`, the environment
actions in :mod:`.environment_actions`; this module defines grouping, opaque functions and
includes, and offers all of them (``__all__`` is what ``launch.actions`` holds).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Mapping
from typing import Any

from robomodel.launch.ros2.shim.action import (
    Action,
    LaunchDescription,
    StaticRole,
    launch_arguments,
    visit_entities,
)
from robomodel.launch.ros2.shim.configuration_actions import (
    DeclareLaunchArgument,
    PopLaunchConfigurations,
    PushLaunchConfigurations,
    ResetLaunchConfigurations,
    SetLaunchConfiguration,
    UnsetLaunchConfiguration,
)
from robomodel.launch.ros2.shim.context import LaunchContext, SubstitutionFailure, WorkBoundError
from robomodel.launch.ros2.shim.environment_actions import (
    AppendEnvironmentVariable,
    PopEnvironment,
    PushEnvironment,
    ResetEnvironment,
    SetEnvironmentVariable,
    UnsetEnvironmentVariable,
)
from robomodel.launch.ros2.shim.sources import AnyLaunchDescriptionSource, LaunchDescriptionSource
from robomodel.launch.ros2.shim.substitutions import (
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

__all__ = [
    "AppendEnvironmentVariable",
    "DeclareLaunchArgument",
    "GroupAction",
    "IncludeLaunchDescription",
    "OpaqueFunction",
    "PopEnvironment",
    "PopLaunchConfigurations",
    "PushEnvironment",
    "PushLaunchConfigurations",
    "ResetEnvironment",
    "ResetLaunchConfigurations",
    "SetEnvironmentVariable",
    "SetLaunchConfiguration",
    "UnsetEnvironmentVariable",
    "UnsetLaunchConfiguration",
]


class GroupAction(Action):
    """Actions in a scope (``scoped``), optionally without the outer configurations."""

    def __init__(
        self,
        actions: Iterable[Any],
        *,
        scoped: bool = True,
        forwarding: bool = True,
        launch_configurations: Mapping[Any, Any] | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        self.actions = actions
        self.scoped = scoped
        self.forwarding = forwarding
        self.launch_configurations = dict(launch_configurations or {})
        self._returned: list[Any] | None = None

    def get_sub_entities(self) -> list[Any]:
        """As upstream: Push/Set/.../Pop around the actions when scoped."""
        if self._returned is None:
            actions = list(self.actions)
            sets = [SetLaunchConfiguration(k, v) for k, v in self.launch_configurations.items()]
            if self.scoped and self.forwarding:
                actions = [
                    PushLaunchConfigurations(), PushEnvironment(), *sets, *actions,
                    PopEnvironment(), PopLaunchConfigurations(),
                ]  # fmt: skip
            elif self.scoped:
                actions = [
                    PushLaunchConfigurations(), PushEnvironment(), ResetEnvironment(),
                    ResetLaunchConfigurations(self.launch_configurations), *actions,
                    PopEnvironment(), PopLaunchConfigurations(),
                ]  # fmt: skip
            else:
                actions = [*sets, *actions]
            self._returned = actions
        return self._returned

    def execute(self, context: LaunchContext) -> list[Any] | None:
        return self.get_sub_entities()


class OpaqueFunction(Action):
    """Call ``function(context, *args, **kwargs)`` and visit the entities it returns."""

    def __init__(
        self,
        *,
        function: Callable[..., Any],
        args: Iterable[Any] | None = None,
        kwargs: Mapping[str, Any] | None = None,
        **left_over: Any,
    ) -> None:
        super().__init__(**left_over)
        if not callable(function):
            raise TypeError("OpaqueFunction's function must be callable")
        self.function = function
        self.args = list(args or [])
        self.kwargs = dict(kwargs or {})

    def execute(self, context: LaunchContext) -> list[Any] | None:
        result = self.function(context, *self.args, **self.kwargs)
        if result is None:
            return None
        return list(result)


class IncludeLaunchDescription(Action):
    """Include another launch file; its arguments become launch configurations (not scoped).

    As upstream (Humble and Jazzy alike), the include sets each ``launch_arguments`` item with
    ``SetLaunchConfiguration`` in the current scope; wrap it in a ``GroupAction`` to scope it.
    A required argument of the included file (no default, not conditional) must be among the
    names given in ``launch_arguments``.
    """

    static_role = StaticRole.INCLUDES

    def __init__(
        self,
        launch_description_source: Any,
        *,
        launch_arguments: Iterable[tuple[Any, Any]] | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        if not isinstance(launch_description_source, LaunchDescriptionSource):
            launch_description_source = AnyLaunchDescriptionSource(launch_description_source)
        self.launch_description_source = launch_description_source
        self.launch_arguments = tuple(launch_arguments or ())

    def get_sub_entities(self) -> list[Any]:
        description = self.launch_description_source.try_get_launch_description_without_context()
        return [description] if description is not None else []

    def _argument_names_without_context(self) -> list[str]:
        try:
            context = LaunchContext()
            return [
                perform_substitutions(context, normalize_to_list_of_substitutions(name))
                for name, _ in self.launch_arguments
            ]
        except WorkBoundError:
            raise
        except Exception:
            return []

    def execute(self, context: LaunchContext) -> list[Any] | None:
        session = context.session
        source = self.launch_description_source
        description = source.get_launch_description(context, self.location)
        location = source.location
        context.extend_locals(
            {
                "current_launch_file_path": os.path.abspath(location),
                "current_launch_file_directory": os.path.dirname(os.path.abspath(location)),
            }
        )
        names = [
            perform_substitutions(context, normalize_to_list_of_substitutions(name))
            for name, _ in self.launch_arguments
        ]
        for argument, conditional, chain in launch_arguments(description.entities):
            if conditional or argument.default_value is not None:
                continue
            given = list(names)
            for include in chain or []:
                given.extend(include._argument_names_without_context())
            if argument.name not in given:
                raise session.error(
                    f"Included launch description missing required argument '{argument.name}' "
                    f"(description: '{argument.description}'), given: [{', '.join(given)}]",
                    self.location if self.location is not None else argument.location,
                )
        sets: list[Any] = [
            SetLaunchConfiguration(name, value) for name, value in self.launch_arguments
        ]
        return [*sets, _IncludeScope(self, description)]


class _IncludeScope(Action):
    """Visits an included description with its include location on the error stack."""

    def __init__(self, include: IncludeLaunchDescription, description: LaunchDescription) -> None:
        super().__init__()
        self.include = include
        self.description = description

    def execute(self, context: LaunchContext) -> list[Any] | None:
        session = context.session
        pushed = self.include.location is not None
        if pushed:
            session.include_stack.append(self.include.location)  # type: ignore[arg-type]
        try:
            visit_entities(context, [self.description])
        finally:
            if pushed:
                session.include_stack.pop()
        return None


def unsupported(name: str) -> type:
    """A class that fails, when constructed, with a clear "not supported" message."""

    def __init__(self: Any, *args: Any, **kwargs: Any) -> None:
        raise SubstitutionFailure(f"{name} is not supported by robomodel launch")

    return type(name.rsplit(".", 1)[-1], (Action,), {"__init__": __init__})
