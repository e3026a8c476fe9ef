"""What a launch file describes, as plain frozen data shared by the ROS 1 and ROS 2 front-ends.

A front-end (``robomodel.launch.ros1``, ``robomodel.launch.ros2``) turns a file into
:class:`NodeSpec` values and parameters; the runner (``robomodel.launch.runner``) maps each
``NodeSpec`` onto a robomodel component through ``robomodel.launch.nodes``.

Names follow ROS conventions: a namespace is absolute and ends with ``/`` as roslaunch keeps it
(``/``, ``/rrbot/``); ``NodeSpec.fqn`` is the node's fully qualified name (``/rrbot/spawner``).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

from robomodel.errors import RobomodelError, SourceLocation

__all__ = ["Dialect", "LaunchError", "NodeSpec", "ParamSource"]

Dialect = Literal["ros1", "ros2"]


class LaunchError(RobomodelError):
    """A launch file that cannot be loaded or run: what was wrong, where, and the include stack.

    ``location`` is the file:line:column of the offending element or expression and
    ``include_stack`` the locations of the ``<include>`` / ``IncludeLaunchDescription`` chain
    that led there, outermost first.
    """

    def __init__(
        self,
        message: str,
        *,
        location: SourceLocation | None = None,
        include_stack: tuple[SourceLocation, ...] = (),
    ) -> None:
        self.message = message
        self.location = location
        self.include_stack = include_stack
        text = f"{location}: {message}" if location is not None else message
        for included_from in reversed(include_stack):
            text += f"\n  included from {included_from}"
        super().__init__(text)


@dataclass(frozen=True, slots=True)
class ParamSource:
    """One ROS 2 parameter source of a node, in the order the launch file gives them.

    Either ``values`` (a dict, names possibly dotted) or ``file`` (a YAML parameter file with
    ``/**`` / node-name keys), never both.
    """

    values: Mapping[str, Any] | None = None
    file: Path | None = None
    allow_substs: bool = False


@dataclass(frozen=True, slots=True)
class NodeSpec:
    """One node of a launch file, fully substituted.

    ROS 1 nodes read their parameters from the parameter server (``parameters`` stays empty);
    ROS 2 nodes get theirs from ``parameters`` (global ``SetParameter`` values first).
    """

    dialect: Dialect
    package: str
    executable: str  # ROS 1 ``type``, ROS 2 ``executable``
    name: str | None  # None: ROS 2 node without name= (the executable picks it)
    namespace: str = "/"
    args: tuple[str, ...] = ()  # command-line arguments, already split
    remaps: tuple[tuple[str, str], ...] = ()  # (from, to), scope remaps first, in order
    parameters: tuple[ParamSource, ...] = ()
    env: tuple[tuple[str, str], ...] = ()
    required: bool = False
    respawn: bool = False
    respawn_delay_s: float = 0.0
    output: str | None = None  # "screen" / "log" / None
    launch_prefix: str | None = None
    cwd: str | None = None
    clear_params: bool = False
    ros_arguments: tuple[str, ...] = ()  # ROS 2 ``ros_arguments``
    location: SourceLocation | None = None
    extra: Mapping[str, Any] = field(default_factory=dict)

    @property
    def fqn(self) -> str:
        """Fully qualified node name: namespace + name (``/rrbot/controller_spawner``)."""
        ns = self.namespace if self.namespace.endswith("/") else self.namespace + "/"
        return ns + (self.name or self.executable)
