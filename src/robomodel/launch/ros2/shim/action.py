"""The base of every action, ``LaunchDescription``, the visitor that executes them and the
static walk that finds their declared arguments (``--show-args``)."""

from __future__ import annotations

import traceback
from collections.abc import Iterable
from enum import Enum
from typing import Any, ClassVar

from robomodel.errors import SourceLocation
from robomodel.launch.model import LaunchError
from robomodel.launch.ros2.shim.context import LaunchContext, caller_location, current_session

__all__ = [
    "Action",
    "LaunchDescription",
    "LaunchDescriptionEntity",
    "StaticRole",
    "launch_arguments",
    "object_text",
    "user_error",
    "visit_entities",
]


class StaticRole(Enum):
    """What the static walk for declared arguments (:func:`launch_arguments`) does with an
    entity: the class of an action says it, as upstream's ``isinstance`` checks do."""

    OTHER = "other"
    DECLARES_ARGUMENT = "declares_argument"  # DeclareLaunchArgument: collected
    INCLUDES = "includes"  # IncludeLaunchDescription: starts an include chain
    RESETS = "resets"  # ResetLaunchConfigurations: the branch stops here


class LaunchDescriptionEntity:
    """Anything a launch description holds."""

    static_role: ClassVar[StaticRole] = StaticRole.OTHER

    def visit(self, context: LaunchContext) -> list[Any] | None:
        """Execute and return the entities to visit next."""
        return None

    def describe_sub_entities(self) -> list[Any]:
        """Entities visited unconditionally (for ``--show-args``)."""
        return []

    def describe_conditional_sub_entities(self) -> list[tuple[str, list[Any]]]:
        """Entities visited only on some condition (event handlers)."""
        return []


class Action(LaunchDescriptionEntity):
    """``launch.Action``: an optional ``condition`` and where it was written."""

    def __init__(self, *, condition: Any = None, **unknown: Any) -> None:
        if unknown:
            names = ", ".join(sorted(unknown))
            raise TypeError(f"{type(self).__name__}() got unexpected keyword argument(s): {names}")
        self.condition = condition
        self.location: SourceLocation | None = caller_location(3)

    def visit(self, context: LaunchContext) -> list[Any] | None:
        if self.condition is None or self.condition.evaluate(context):
            return self.execute(context)
        return None

    def execute(self, context: LaunchContext) -> list[Any] | None:
        """What the action does."""
        return None

    def get_sub_entities(self) -> list[Any]:
        """Sub-entities known without a context."""
        return []

    def describe_sub_entities(self) -> list[Any]:
        return self.get_sub_entities()


class LaunchDescription(LaunchDescriptionEntity):
    """``launch.LaunchDescription``: a list of entities."""

    def __init__(
        self, initial_entities: Iterable[Any] | None = None, *, deprecated_reason: str | None = None
    ) -> None:
        self.entities: list[Any] = list(initial_entities) if initial_entities is not None else []
        self.deprecated_reason = deprecated_reason
        self.location = caller_location(2)

    def visit(self, context: LaunchContext) -> list[Any] | None:
        if self.deprecated_reason is not None:
            session = current_session()
            if session is not None:
                session.warn(f"launch description is deprecated: {self.deprecated_reason}")
        return self.entities

    def describe_sub_entities(self) -> list[Any]:
        return self.entities

    def add_entity(self, entity: Any) -> None:
        """Append an entity."""
        self.entities.append(entity)

    def add_action(self, action: Any) -> None:
        """Append an action."""
        self.entities.append(action)

    def get_launch_arguments(self, conditional_inclusion: bool = False) -> list[Any]:
        """The ``DeclareLaunchArgument`` actions found statically (see ``--show-args``)."""
        return [arg for arg, _, _ in launch_arguments(self.entities, conditional_inclusion)]


def launch_arguments(
    entities: list[Any], conditional_inclusion: bool = False
) -> list[tuple[Any, bool, list[Any] | None]]:
    """``(DeclareLaunchArgument, conditionally_included, include chain)`` in order.

    Transcribes ``LaunchDescription.get_launch_arguments_with_include_launch_description_actions``:
    the walk follows ``describe_sub_entities`` (includes whose file can be found without a
    context are loaded), marks declarations under a condition or an event handler as
    conditional, keeps the first declaration of a name and stops a branch at
    ``ResetLaunchConfigurations``.
    """
    found: list[tuple[Any, bool, list[Any] | None]] = []

    def walk(items: list[Any], conditional: bool, chain: list[Any] | None) -> None:
        for entity in items:
            role = getattr(entity, "static_role", StaticRole.OTHER)
            if role is StaticRole.DECLARES_ARGUMENT:
                if any(entity.name == other.name for other, _, _ in found):
                    continue
                found.append((entity, conditional or entity.condition is not None, chain))
            if role is StaticRole.RESETS:
                return
            next_chain = chain
            if role is StaticRole.INCLUDES:
                next_chain = [*(chain or []), entity]
            walk(entity.describe_sub_entities(), False, next_chain)
            for _, sub in entity.describe_conditional_sub_entities():
                walk(sub, True, next_chain)

    walk(entities, conditional_inclusion, None)
    return found


_UPSTREAM_MODULE = {
    "action": "launch.action",
    "actions": "launch.actions",
    "configuration_actions": "launch.actions",
    "environment_actions": "launch.actions",
    "events": "launch.actions",
    "ros": "launch_ros.actions",
}


def object_text(entity: Any) -> str:
    """``<module.snake_name.Class object at 0x0>`` under the upstream module names (how
    launch's introspector names an entity; object addresses differ at every run upstream)."""
    cls = type(entity)
    module = cls.__module__.rsplit(".", 1)[-1]
    snake = "".join("_" + c.lower() if c.isupper() else c for c in cls.__name__).lstrip("_")
    package = _UPSTREAM_MODULE.get(module, "launch.actions")
    if cls.__name__.startswith("OnProcess"):
        package = "launch.event_handlers"
    return f"<{package}.{snake}.{cls.__name__} object at 0x0>"


def user_error(exc: BaseException, fallback: SourceLocation | None) -> LaunchError:
    """A LaunchError for an exception raised by launch-file code or by an action.

    The location is the innermost traceback frame inside a loaded Python launch file, else
    ``fallback`` (the action's location).
    """
    session = current_session()
    location = fallback
    if session is not None:
        for frame, line in traceback.walk_tb(exc.__traceback__):
            if frame.f_code.co_filename in session.python_files:
                location = SourceLocation(frame.f_code.co_filename, line)
    if isinstance(exc, SyntaxError) and exc.filename:
        location = SourceLocation(exc.filename, exc.lineno, exc.offset)
        text = f"SyntaxError: {exc.msg}"
    elif type(exc).__name__ in ("SubstitutionFailure", "InvalidConditionExpressionError"):
        text = str(exc)
    else:
        text = f"{type(exc).__name__}: {exc}"
    stack = tuple(session.include_stack) if session is not None else ()
    return LaunchError(text, location=location, include_stack=stack)


def visit_entities(context: LaunchContext, entities: Iterable[Any]) -> None:
    """Visit entities depth-first in order, as ``LaunchService`` does, with scoped locals."""
    for entity in entities:
        if not isinstance(entity, LaunchDescriptionEntity):
            raise user_error(
                TypeError(f"expected a launch action or LaunchDescription, got {entity!r}"), None
            )
        context.session.charge(1, getattr(entity, "location", None))
        context._push_locals()
        try:
            try:
                sub = entity.visit(context)
            except LaunchError:
                raise
            except RecursionError:
                raise user_error(
                    RuntimeError("launch files nested too deeply"),
                    getattr(entity, "location", None),
                ) from None
            except Exception as exc:
                raise user_error(exc, getattr(entity, "location", None)) from None
            if sub:
                visit_entities(context, sub)
        finally:
            context._pop_locals()
