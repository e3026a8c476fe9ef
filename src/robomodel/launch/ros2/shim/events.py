"""Processes, timers, logs, shutdown and event handlers, recorded as launch steps.

Event handlers are evaluated eagerly: the entities of ``OnProcessStart`` / ``OnProcessExit``
are visited when the handler is registered (or, if the target has not started yet, right after
the target's step is recorded) with the launch configurations current at registration, and
every step they record carries ``after_start_of`` / ``after_exit_of`` = the target's step index.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from types import SimpleNamespace
from typing import Any

from robomodel.errors import SourceLocation
from robomodel.launch.ros2.model import LaunchStep, StepKind
from robomodel.launch.ros2.shim.action import Action, object_text, visit_entities
from robomodel.launch.ros2.shim.context import (
    EventDispatch,
    LaunchContext,
    Trigger,
    caller_location,
)
from robomodel.launch.ros2.shim.substitutions import (
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

__all__ = [
    "EVENTS",
    "EmitEvent",
    "ExecuteProcess",
    "LogInfo",
    "OnProcessExit",
    "OnProcessStart",
    "RegisterEventHandler",
    "Shutdown",
    "ShutdownEvent",
    "TimerAction",
    "emit_event",
    "record_step",
    "register_handler",
]


def record_step(
    context: LaunchContext,
    action: Any,
    kind: StepKind,
    location: SourceLocation | None,
    **fields: Any,
) -> int:
    """Append a step for ``action`` with the current trigger; run handlers waiting for it."""
    session = context.session
    trigger = context.trigger
    step = LaunchStep(
        kind=kind,
        delay_s=trigger.delay_s,
        after_exit_of=trigger.after_exit_of,
        after_start_of=trigger.after_start_of,
        location=location,
        **fields,
    )
    index = len(session.steps)
    session.steps.append(step)
    session.step_of[id(action)] = index
    session.keep_alive.append(action)
    for handler, snapshot in session.pending.pop(id(action), []):
        _fire(context, handler, index, snapshot)
    return index


def _entities_of(handler: Any, target: Any) -> list[Any]:
    entities = handler.entities
    if callable(entities):
        event = SimpleNamespace(action=target, returncode=0, pid=0, cmd=[], text=b"")
        entities = entities(event, None)
    if entities is None:
        return []
    if not isinstance(entities, Iterable):
        return [entities]
    return list(entities)


def _fire(context: LaunchContext, handler: Any, index: int, snapshot: Any) -> None:
    configs, environ, changes = snapshot
    saved = context.trigger
    context._push_launch_configurations()
    context._push_environment()
    context._reset_launch_configurations(configs)
    context.environment, context.env_changes = dict(environ), dict(changes)
    if handler.on_exit:
        context.trigger = Trigger(after_exit_of=index)
    else:
        context.trigger = Trigger(after_start_of=index)
    try:
        visit_entities(context, _entities_of(handler, handler.target_action))
    finally:
        context.trigger = saved
        context._pop_environment()
        context._pop_launch_configurations()


def register_handler(context: LaunchContext, handler: Any, location: SourceLocation | None) -> None:
    """Evaluate ``handler``'s entities now or when its target's step is recorded."""
    session = context.session
    target = getattr(handler, "target_action", None)
    if not isinstance(handler, _ProcessHandler):
        session.warn(
            f"{location}: event handler {type(handler).__name__} is not supported by robomodel "
            "launch; its actions are not run"
        )
        return
    if target is None or not isinstance(target, Action):
        session.warn(
            f"{location}: {type(handler).__name__} without a target action (or with a matcher "
            "function) is not supported by robomodel launch; its actions are not run"
        )
        return
    snapshot = (
        dict(context.launch_configurations),
        dict(context.environment),
        dict(context.env_changes),
    )
    if id(target) in session.step_of:
        _fire(context, handler, session.step_of[id(target)], snapshot)
    else:
        session.pending.setdefault(id(target), []).append((handler, snapshot))
        session.keep_alive.append(target)


class _ProcessHandler:
    on_exit = False

    def __init__(self, *, target_action: Any = None, entities: Any = None, **kwargs: Any) -> None:
        self.target_action = target_action
        self.entities = entities
        self.location = caller_location(3)

    def describe(self) -> tuple[str, list[Any]]:
        name = type(self).__name__
        entities = self.entities if isinstance(self.entities, list) else []
        return f"{name}(matcher='{object_text(self.target_action)}')", entities


class OnProcessStart(_ProcessHandler):
    """Run ``on_start`` entities when ``target_action`` starts."""

    def __init__(self, *, target_action: Any = None, on_start: Any = None, **kwargs: Any) -> None:
        super().__init__(target_action=target_action, entities=on_start, **kwargs)


class OnProcessExit(_ProcessHandler):
    """Run ``on_exit`` entities when ``target_action`` exits."""

    on_exit = True

    def __init__(self, *, target_action: Any = None, on_exit: Any = None, **kwargs: Any) -> None:
        super().__init__(target_action=target_action, entities=on_exit, **kwargs)


def unsupported_handler(name: str) -> type:
    """An event handler class robomodel records a warning for."""
    return type(name, (), {"__init__": lambda self, *a, **k: None})


class RegisterEventHandler(Action):
    """Register an event handler (see the module docstring for the eager evaluation)."""

    def __init__(self, event_handler: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.event_handler = event_handler

    def execute(self, context: LaunchContext) -> list[Any] | None:
        register_handler(context, self.event_handler, self.location)
        return None

    def describe_conditional_sub_entities(self) -> list[tuple[str, list[Any]]]:
        entities = getattr(self.event_handler, "entities", None)
        if isinstance(entities, list):
            return [(type(self.event_handler).__name__, entities)]
        return []


class TimerAction(Action):
    """Visit ``actions`` ``period`` seconds later (delays add up when nested)."""

    def __init__(
        self, *, period: Any, actions: Iterable[Any], cancel_on_shutdown: Any = True, **kwargs: Any
    ) -> None:
        super().__init__(**kwargs)
        self.period = (
            float(period)
            if isinstance(period, (int, float))
            else normalize_to_list_of_substitutions(period)
        )
        self.actions = list(actions)

    def describe_conditional_sub_entities(self) -> list[tuple[str, list[Any]]]:
        return [("TimerAction", self.actions)]

    def execute(self, context: LaunchContext) -> list[Any] | None:
        period = self.period
        if not isinstance(period, float):
            text = perform_substitutions(context, period)
            try:
                period = float(text)
            except ValueError:
                raise ValueError(f"TimerAction period '{text}' is not a number") from None
        saved = context.trigger
        context.trigger = Trigger(saved.delay_s + period, saved.after_exit_of, saved.after_start_of)
        try:
            visit_entities(context, self.actions)
        finally:
            context.trigger = saved
        return None


class LogInfo(Action):
    """Log a message (recorded as a ``log`` step)."""

    def __init__(self, *, msg: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.msg = normalize_to_list_of_substitutions(msg)

    def execute(self, context: LaunchContext) -> list[Any] | None:
        record_step(
            context, self, "log", self.location, message=perform_substitutions(context, self.msg)
        )
        return None


class ShutdownEvent:
    """``launch.events.Shutdown``."""

    name = "launch.events.Shutdown"

    def __init__(self, *, reason: Any = "reason not given", due_to_sigint: bool = False) -> None:
        self.reason = reason
        self.due_to_sigint = due_to_sigint


def emit_event(context: LaunchContext, event: Any, action: Any) -> None:
    """A Shutdown event records a shutdown step; other events are ignored with a warning."""
    if isinstance(event, ShutdownEvent):
        reason = event.reason
        if not isinstance(reason, str):
            reason = perform_substitutions(context, normalize_to_list_of_substitutions(reason))
        record_step(context, action if action is not None else event, "shutdown",
                    getattr(action, "location", None), message=reason)  # fmt: skip
    else:
        context.session.warn(f"event {type(event).__name__} is not modelled by robomodel launch")


class EmitEvent(Action):
    """Emit an event (only ``Shutdown`` has an effect here)."""

    def __init__(self, *, event: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.event = event

    def execute(self, context: LaunchContext) -> list[Any] | None:
        emit_event(context, self.event, self)
        return None


class Shutdown(EmitEvent):
    """Shut the launch down (a ``shutdown`` step with the reason)."""

    def __init__(self, *, reason: Any = "reason not given", **kwargs: Any) -> None:
        super().__init__(event=ShutdownEvent(reason=reason), **kwargs)


class ExecuteProcess(Action):
    """Run a command (a ``process`` step with the substituted command line)."""

    def __init__(
        self,
        *,
        cmd: Iterable[Any],
        name: Any = None,
        cwd: Any = None,
        env: Any = None,
        additional_env: Any = None,
        shell: bool = False,
        output: Any = "log",
        **kwargs: Any,
    ) -> None:
        extra = {k: kwargs.pop(k) for k in list(kwargs) if k != "condition"}
        super().__init__(**kwargs)
        self.cmd = [normalize_to_list_of_substitutions(c) for c in cmd]
        self.name = name
        self.cwd = cwd
        self.env = env
        self.additional_env = additional_env
        self.shell = shell
        self.output = output
        self.extra = extra

    def execute(self, context: LaunchContext) -> list[Any] | None:
        command = tuple(perform_substitutions(context, c) for c in self.cmd)
        record_step(context, self, "process", self.location, command=command)
        return None


Callback = Callable[..., Any]


EVENTS = EventDispatch(register_handler, emit_event)
"""What a ``LaunchContext`` of ``load_launch`` does with the event handlers and events given
to it (``register_event_handler``, ``emit_event``)."""
