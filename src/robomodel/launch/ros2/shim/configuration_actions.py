"""``launch.actions`` that declare, set and scope launch configurations (arguments)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from robomodel.launch.ros2.shim.action import Action, StaticRole
from robomodel.launch.ros2.shim.context import LaunchContext
from robomodel.launch.ros2.shim.substitutions import (
    Substitution,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

__all__ = [
    "DeclareLaunchArgument",
    "PopLaunchConfigurations",
    "PushLaunchConfigurations",
    "ResetLaunchConfigurations",
    "SetLaunchConfiguration",
    "UnsetLaunchConfiguration",
]


class DeclareLaunchArgument(Action):
    """Declare an argument: set its default if not given, check its choices."""

    static_role = StaticRole.DECLARES_ARGUMENT

    def __init__(
        self,
        name: str,
        *,
        default_value: Any = None,
        description: str | None = None,
        choices: list[str] | None = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        self.name = name
        self.default_value = (
            None if default_value is None else normalize_to_list_of_substitutions(default_value)
        )
        if choices is not None:
            if len(choices) == 0:
                raise RuntimeError(
                    "Provided choices arg is empty. Use None to ignore the choice list."
                )
            if (
                default_value is not None
                and not isinstance(default_value, (Substitution, list))
                and default_value not in choices
            ):
                raise RuntimeError(
                    f'Provided default_value "{default_value}" is not in provided choices '
                    f'"{choices}".'
                )
        if description is None:
            self.description = "no description given" if choices is None else f"One of: {choices}"
        else:
            self.description = description
            if choices is not None:
                if not self.description.endswith("."):
                    self.description += "."
                self.description += f" Valid choices are: {choices}"
        self.choices = choices

    def execute(self, context: LaunchContext) -> list[Any] | None:
        if self.name not in context.launch_configurations:
            if self.default_value is None:
                raise RuntimeError(f'Required launch argument "{self.name}" was not provided.')
            context.launch_configurations[self.name] = perform_substitutions(
                context, self.default_value
            )
        if self.choices is not None:
            value = context.launch_configurations[self.name]
            if value not in self.choices:
                raise RuntimeError(
                    f'Argument "{self.name}" provided value "{value}" is not valid. '
                    f"Valid options are: {self.choices}"
                )
        return None


class SetLaunchConfiguration(Action):
    """Set a launch configuration (``<let>``)."""

    def __init__(self, name: Any, value: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.name = normalize_to_list_of_substitutions(name)
        self.value = normalize_to_list_of_substitutions(value)

    def execute(self, context: LaunchContext) -> list[Any] | None:
        name = perform_substitutions(context, self.name)
        context.launch_configurations[name] = perform_substitutions(context, self.value)
        return None


class UnsetLaunchConfiguration(Action):
    """Remove a launch configuration."""

    def __init__(self, name: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.name = normalize_to_list_of_substitutions(name)

    def execute(self, context: LaunchContext) -> list[Any] | None:
        context.launch_configurations.pop(perform_substitutions(context, self.name), None)
        return None


class PushLaunchConfigurations(Action):
    """Start a launch-configuration scope."""

    def execute(self, context: LaunchContext) -> list[Any] | None:
        context._push_launch_configurations()
        return None


class PopLaunchConfigurations(Action):
    """End a launch-configuration scope."""

    def execute(self, context: LaunchContext) -> list[Any] | None:
        context._pop_launch_configurations()
        return None


class ResetLaunchConfigurations(Action):
    """Clear the launch configurations, keeping the given ones (evaluated before clearing)."""

    static_role = StaticRole.RESETS

    def __init__(
        self, launch_configurations: Mapping[Any, Any] | None = None, **kwargs: Any
    ) -> None:
        super().__init__(**kwargs)
        self.launch_configurations = launch_configurations

    def execute(self, context: LaunchContext) -> list[Any] | None:
        keep: dict[str, Any] = {}
        for name, value in (self.launch_configurations or {}).items():
            key = perform_substitutions(context, normalize_to_list_of_substitutions(name))
            keep[key] = perform_substitutions(context, normalize_to_list_of_substitutions(value))
        context._reset_launch_configurations(keep)
        return None
