"""What the viewer is given to show (a description file or topic) and why a load failed."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from robomodel.errors import Diagnostic, InputError, RobomodelError

__all__ = ["DisplayOptions", "LoadFailure", "RobotSource"]


@dataclass(frozen=True, slots=True)
class RobotSource:
    """A description file to view, its xacro arguments and its frame prefix; or, with
    ``topic``, the description another process publishes there (RViz's RobotModel with
    Description Source: Topic), reloaded whenever a new one arrives.

    ``namespace`` (the bus namespace of the robot's nodes), ``joint_states_topic`` (the resolved
    topic its sliders publish on) and ``external`` come from a launch file's nodes: a
    joint_state_publisher_gui in ``/r1`` publishes on ``/r1/joint_states``. None: the
    viewer's defaults (its options' ``external``, ``joint_states`` in the namespace).
    ``description_name`` is the ROS 1 parameter a launch read the description from (an RViz 1
    RobotModel's Robot Description names it).
    """

    path: str
    mappings: Mapping[str, str] = field(default_factory=dict)
    prefix: str = ""
    topic: str | None = None
    namespace: str | None = None
    joint_states_topic: str | None = None
    external: bool | None = None
    description_name: str | None = None


@dataclass(frozen=True, slots=True)
class LoadFailure:
    """Why the last load failed: the error and the include/macro stack notes.

    ``diagnostics`` holds the located error first, then its notes (empty for errors without a
    location, whose text is ``message``).
    """

    message: str
    diagnostics: tuple[Diagnostic, ...] = ()

    @property
    def path(self) -> str | None:
        return self.diagnostics[0].location.path if self.diagnostics else None

    @classmethod
    def from_error(cls, exc: RobomodelError) -> LoadFailure:
        if isinstance(exc, InputError):
            return cls(exc.diagnostic.format(), (exc.diagnostic, *exc.notes))
        return cls(str(exc))


@dataclass(slots=True)
class DisplayOptions:
    """RViz's RobotModel properties, shared by every robot."""

    alpha: float = 1.0
    show_visual: bool = True
    show_collision: bool = False
