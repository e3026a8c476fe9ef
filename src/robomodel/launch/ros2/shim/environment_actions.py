"""``launch.actions`` that set, unset and scope environment variables."""

from __future__ import annotations

import os
from typing import Any

from robomodel.launch.ros2.shim.action import Action
from robomodel.launch.ros2.shim.context import LaunchContext
from robomodel.launch.ros2.shim.substitutions import (
    coerce_bool,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

__all__ = [
    "AppendEnvironmentVariable",
    "PopEnvironment",
    "PushEnvironment",
    "ResetEnvironment",
    "SetEnvironmentVariable",
    "UnsetEnvironmentVariable",
]


class PushEnvironment(Action):
    """Start an environment scope."""

    def execute(self, context: LaunchContext) -> list[Any] | None:
        context._push_environment()
        return None


class PopEnvironment(Action):
    """End an environment scope."""

    def execute(self, context: LaunchContext) -> list[Any] | None:
        context._pop_environment()
        return None


class ResetEnvironment(Action):
    """Clear the environment."""

    def execute(self, context: LaunchContext) -> list[Any] | None:
        context._reset_environment()
        return None


class SetEnvironmentVariable(Action):
    """Set an environment variable for what follows (nodes, commands, package lookups)."""

    def __init__(self, name: Any, value: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.name = normalize_to_list_of_substitutions(name)
        self.value = normalize_to_list_of_substitutions(value)

    def execute(self, context: LaunchContext) -> list[Any] | None:
        name = perform_substitutions(context, self.name)
        context.set_env(name, perform_substitutions(context, self.value))
        return None


class UnsetEnvironmentVariable(Action):
    """Unset an environment variable."""

    def __init__(self, name: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.name = normalize_to_list_of_substitutions(name)

    def execute(self, context: LaunchContext) -> list[Any] | None:
        context.set_env(perform_substitutions(context, self.name), None)
        return None


class AppendEnvironmentVariable(Action):
    """Append (or prepend) to an environment variable, with ``os.pathsep`` by default."""

    def __init__(
        self,
        name: Any,
        value: Any,
        prepend: Any = False,
        separator: Any = os.pathsep,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        self.name = normalize_to_list_of_substitutions(name)
        self.value = normalize_to_list_of_substitutions(value)
        self.prepend = prepend
        self.separator = normalize_to_list_of_substitutions(separator)

    def execute(self, context: LaunchContext) -> list[Any] | None:
        name = perform_substitutions(context, self.name)
        value = perform_substitutions(context, self.value)
        sep = perform_substitutions(context, self.separator)
        prepend = self.prepend
        if not isinstance(prepend, bool):
            prepend = coerce_bool(
                perform_substitutions(context, normalize_to_list_of_substitutions(prepend))
            )
        old = context.environment.get(name)
        if old:
            value = value + sep + old if prepend else old + sep + value
        context.set_env(name, value)
        return None
