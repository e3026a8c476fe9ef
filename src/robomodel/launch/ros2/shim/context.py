"""The launch context (``launch.LaunchContext``) and the loader session behind it."""

from __future__ import annotations

import contextvars
import sys
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from types import SimpleNamespace
from typing import Any

from robomodel.description.packages import PackageIndex
from robomodel.errors import SourceLocation
from robomodel.launch.bounds import work_exceeded
from robomodel.launch.model import LaunchError
from robomodel.launch.processes import COMMAND_TIMEOUT_S

__all__ = [
    "EventDispatch",
    "LaunchContext",
    "Session",
    "SubstitutionFailure",
    "caller_location",
    "current_session",
]


class WorkBoundError(LaunchError):
    """The load went past the work bound: never swallowed by the static (``--show-args``)
    walks that ignore the includes they cannot load."""


class SubstitutionFailure(RuntimeError):
    """A substitution could not be performed (``launch.substitutions.SubstitutionFailure``)."""


@dataclass(frozen=True, slots=True)
class EventDispatch:
    """How a load handles events, the part of upstream's ``LaunchService`` a
    ``LaunchContext`` hands them to (:data:`robomodel.launch.ros2.shim.events.EVENTS`).

    Attributes:
        register_handler: ``(context, event handler, where it was registered)``.
        emit_event: ``(context, event, the action that emitted it or None)``.
    """

    register_handler: Callable[[LaunchContext, Any, SourceLocation | None], None]
    emit_event: Callable[[LaunchContext, Any, Any], None]


@dataclass
class Session:
    """State of one ``load_launch`` call, shared by every context and entity it creates.

    Attributes:
        packages: Resolves ``FindPackageShare`` / ``get_package_share_directory``.
        python_files: Launch files executed as Python (to find the user's frame in a stack).
        steps: Recorded steps (``robomodel.launch.ros2.model.LaunchStep``), in start order.
        step_of: ``id(action)`` -> index of its step, for event-handler targets.
        pending: ``id(target)`` -> handlers waiting for that action to start.
        files: Launch files loaded, in order.
        warnings: Soft problems.
        include_stack: Locations of the includes being processed, outermost first.
        work: Units of work done so far (the fan-out bound).
        command_timeout_s: The longest a ``Command`` substitution may run.
        temporary_files: Files written while loading (substituted parameter files).
        events: How events and event handlers given to a context are handled (None: a
            context of this session refuses them).
    """

    packages: PackageIndex
    python_files: set[str] = field(default_factory=set)
    steps: list[Any] = field(default_factory=list)
    step_of: dict[int, int] = field(default_factory=dict)
    pending: dict[int, list[Any]] = field(default_factory=dict)
    files: list[Path] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    include_stack: list[SourceLocation] = field(default_factory=list)
    keep_alive: list[Any] = field(default_factory=list)
    work: int = 0
    command_timeout_s: float = COMMAND_TIMEOUT_S
    temporary_files: list[Path] = field(default_factory=list)
    events: EventDispatch | None = None

    def charge(self, units: int, location: SourceLocation | None) -> None:
        """Count ``units`` of work (robomodel.launch.bounds); past the bound, refuse the load."""
        self.work += units
        problem = work_exceeded(self.work, "action", len(self.files))
        if problem is not None:
            raise WorkBoundError(
                problem, location=location, include_stack=tuple(self.include_stack)
            )

    def warn(self, message: str) -> None:
        """Record a warning once."""
        if message not in self.warnings:
            self.warnings.append(message)

    def error(self, message: str, location: SourceLocation | None) -> LaunchError:
        """A LaunchError at ``location`` with the current include stack."""
        return LaunchError(message, location=location, include_stack=tuple(self.include_stack))


_SESSION: contextvars.ContextVar[Session | None] = contextvars.ContextVar(
    "robomodel_ros2_launch_session", default=None
)


def current_session() -> Session | None:
    """The session of the ``load_launch`` in progress, if any."""
    return _SESSION.get()


@contextmanager
def session_scope(session: Session) -> Iterator[Session]:
    """Make ``session`` current for the shim classes created and performed inside."""
    token = _SESSION.set(session)
    try:
        yield session
    finally:
        _SESSION.reset(token)


def caller_location(depth: int = 2) -> SourceLocation | None:
    """file:line of the innermost frame that belongs to a Python launch file being loaded."""
    session = current_session()
    if session is None:
        return None
    frame = sys._getframe(depth)
    while frame is not None:
        if frame.f_code.co_filename in session.python_files:
            return SourceLocation(frame.f_code.co_filename, frame.f_lineno)
        frame = frame.f_back  # type: ignore[assignment]
    return None


@dataclass
class Trigger:
    """What starts the steps recorded now: a delay after an event (or after launch start)."""

    delay_s: float = 0.0
    after_exit_of: int | None = None
    after_start_of: int | None = None


class LaunchContext:
    """``launch.LaunchContext``: launch configurations, environment and locals, with scopes.

    The environment is a copy of the loader's environment (``launch`` mutates ``os.environ``;
    robomodel never does), so ``SetEnvironmentVariable`` is seen by ``EnvironmentVariable``,
    package lookups and the environment recorded on nodes.
    """

    def __init__(
        self,
        *,
        session: Session | None = None,
        environ: Mapping[str, str] | None = None,
        argv: tuple[str, ...] = (),
    ) -> None:
        self._session = session if session is not None else current_session()
        self.__configs: dict[str, Any] = {}
        self.__config_stack: list[dict[str, Any]] = []
        self.environment: dict[str, str] = dict(environ or {})
        self.__env_stack: list[tuple[dict[str, str], dict[str, str | None]]] = []
        self.__locals: list[dict[str, Any]] = [{}]
        self.argv = list(argv)
        self.trigger = Trigger()
        self.env_changes: dict[str, str | None] = {}
        self.is_shutdown = False
        self.noninteractive = True

    @property
    def session(self) -> Session:
        """The loader session (raises if the context was made outside ``load_launch``)."""
        if self._session is None:
            raise SubstitutionFailure("this LaunchContext is not part of a robomodel launch")
        return self._session

    @property
    def launch_configurations(self) -> dict[str, Any]:
        """The current launch configurations (name -> value)."""
        return self.__configs

    def _push_launch_configurations(self) -> None:
        self.__config_stack.append(self.__configs.copy())

    def _pop_launch_configurations(self) -> None:
        self.__configs = self.__config_stack.pop()

    def _reset_launch_configurations(self, values: Mapping[str, Any]) -> None:
        self.__configs = dict(values)

    def _push_environment(self) -> None:
        self.__env_stack.append((self.environment.copy(), dict(self.env_changes)))

    def _pop_environment(self) -> None:
        self.environment, self.env_changes = self.__env_stack.pop()

    def _reset_environment(self) -> None:
        self.environment = {}
        self.env_changes = {}

    def set_env(self, name: str, value: str | None) -> None:
        """Set (or unset with None) a variable of the launch environment."""
        if value is None:
            self.environment.pop(name, None)
        else:
            self.environment[name] = value
        self.env_changes[name] = value

    @property
    def locals(self) -> SimpleNamespace:
        """Context locals (``current_launch_file_path``, ``current_launch_file_directory``)."""
        merged: dict[str, Any] = {}
        for layer in self.__locals:
            merged.update(layer)
        return SimpleNamespace(**merged)

    def get_locals_as_dict(self) -> dict[str, Any]:
        """The locals as a dict."""
        return dict(vars(self.locals))

    def extend_locals(self, new_locals: Mapping[str, Any]) -> None:
        """Add locals to the current scope."""
        self.__locals[-1].update(new_locals)

    def _push_locals(self) -> None:
        self.__locals.append({})

    def _pop_locals(self) -> None:
        self.__locals.pop()

    def extend_globals(self, new_globals: Mapping[str, Any]) -> None:
        """Add globals (kept with the locals here)."""
        self.__locals[0].update(new_globals)

    def perform_substitution(self, substitution: Any) -> str:
        """Perform one substitution in this context."""
        return str(substitution.perform(self))

    def register_event_handler(self, event_handler: Any, append: bool = False) -> None:
        """Register an event handler: its entities are evaluated now (see the front-end docs)."""
        self._events().register_handler(self, event_handler, None)

    def emit_event_sync(self, event: Any) -> None:
        """Events other than shutdown are not modelled; Shutdown records a shutdown step."""
        self._events().emit_event(self, event, None)

    async def emit_event(self, event: Any) -> None:
        """See :meth:`emit_event_sync`."""
        self.emit_event_sync(event)

    def _events(self) -> EventDispatch:
        events = self.session.events
        if events is None:
            raise SubstitutionFailure(
                "this LaunchContext's session handles no events (it was not made by load_launch)"
            )
        return events
