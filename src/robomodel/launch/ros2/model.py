"""What a ROS 2 launch file starts, as plain frozen data (the front-end's output)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Literal

from robomodel.errors import SourceLocation
from robomodel.launch.model import NodeSpec

__all__ = ["DeclaredArgument", "LaunchStep", "Ros2Launch", "StepKind"]

StepKind = Literal["node", "process", "shutdown", "log"]


@dataclass(frozen=True, slots=True)
class DeclaredArgument:
    """One ``DeclareLaunchArgument`` / ``<arg>`` as ``ros2 launch --show-args`` lists it.

    Attributes:
        name: The argument's name.
        default: The default value substituted with the configurations current where it was
            declared (None: no default, the argument is required).
        description: The description text (launch's default: "no description given").
        choices: The allowed values, or None.
        default_description: The default as launch describes it (``'x'``,
            ``LaunchConfig('y')``), which ``--show-args`` prints.
        conditional: True when the declaration sits under a condition or an event handler
            (``--show-args`` marks it with ``*``).
    """

    name: str
    default: str | None
    description: str
    choices: tuple[str, ...] | None
    default_description: str | None = None
    conditional: bool = False


@dataclass(frozen=True, slots=True)
class LaunchStep:
    """One thing ``ros2 launch`` starts or does, in start order.

    Attributes:
        kind: ``node`` (a launch_ros ``Node``), ``process`` (``ExecuteProcess``), ``shutdown``
            or ``log``.
        node: The node, for ``kind == "node"``.
        command: The substituted command line, for ``kind == "process"``.
        message: The ``LogInfo`` text, or the ``Shutdown`` reason.
        delay_s: Seconds after its trigger (start, or the event below) from ``TimerAction``
            periods, summed when nested. [s]
        after_exit_of: Index in :attr:`Ros2Launch.steps` of the process whose exit starts this.
        after_start_of: Index of the process whose start starts this.
        location: Where the action was written.
    """

    kind: StepKind
    node: NodeSpec | None = None
    command: tuple[str, ...] = ()
    message: str = ""
    delay_s: float = 0.0
    after_exit_of: int | None = None
    after_start_of: int | None = None
    location: SourceLocation | None = None


@dataclass(frozen=True, slots=True)
class Ros2Launch:
    """A loaded ROS 2 launch file.

    Attributes:
        path: The top-level launch file.
        arguments: Every declared argument ``--show-args`` lists, in order.
        steps: What ``ros2 launch`` starts, in order.
        files: The launch files loaded (the top-level one first, then includes).
        warnings: Soft problems (unsupported handlers, missing parameter files, ...).
        description: The top-level entities as ``ros2 launch --print`` lists them (one string
            per line, indented by four spaces per level, before tree drawing).
        temporary_files: The ``launch_params_*.yaml`` files written for parameter files with
            ``allow_substs`` (the nodes read them when they start); remove them with
            :meth:`remove_temporary_files` once the launch has ended.
    """

    path: Path
    arguments: tuple[DeclaredArgument, ...]
    steps: tuple[LaunchStep, ...]
    files: tuple[Path, ...]
    warnings: tuple[str, ...] = ()
    description: tuple[str, ...] = ()
    temporary_files: tuple[Path, ...] = ()

    def remove_temporary_files(self) -> None:
        """Delete :attr:`temporary_files` (those already gone are skipped)."""
        for path in self.temporary_files:
            path.unlink(missing_ok=True)
