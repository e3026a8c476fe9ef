"""What a display exchanges with the viewer: its context, subscriptions, placements, status.

The plain values of the :class:`~robomodel.viewer.displays.base.Display` contract (see
:mod:`robomodel.viewer.displays.base`), apart from the class and its registry; import them
from there or from :mod:`robomodel.viewer.displays`.
"""

from __future__ import annotations

import enum
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel.runtime.qos import Durability, QoSProfile

__all__ = [
    "DisplayContext",
    "DisplayStatus",
    "FrameLookup",
    "Placement",
    "StatusLevel",
    "SubscriptionSpec",
    "stamp_ns",
]


class StatusLevel(enum.Enum):
    """RViz's status levels (``rviz::StatusProperty``)."""

    OK = "ok"
    WARN = "warn"
    ERROR = "error"


@dataclass(frozen=True, slots=True)
class DisplayStatus:
    """A display's status line (``level``, ``text``), as RViz's Status row shows it."""

    level: StatusLevel
    text: str

    @classmethod
    def ok(cls, text: str = "OK") -> DisplayStatus:
        return cls(StatusLevel.OK, text)

    @classmethod
    def warn(cls, text: str) -> DisplayStatus:
        return cls(StatusLevel.WARN, text)

    @classmethod
    def error(cls, text: str) -> DisplayStatus:
        return cls(StatusLevel.ERROR, text)

    def worst(self, other: DisplayStatus) -> DisplayStatus:
        """The more severe of the two (self when equal)."""
        order = (StatusLevel.OK, StatusLevel.WARN, StatusLevel.ERROR)
        return other if order.index(other.level) > order.index(self.level) else self


@dataclass(frozen=True, slots=True)
class Placement:
    """Where a frame is in the fixed frame: ``T_fixed_frame`` (4x4) or why it has none."""

    T_fixed_frame: NDArray[np.float64] | None
    reason: str = ""

    @property
    def found(self) -> bool:
        return self.T_fixed_frame is not None


FrameLookup = Callable[[str, int], Placement]
"""``lookup(frame_id, stamp_ns)``: the frame's pose in the fixed frame at ``stamp_ns`` (0:
the latest), or the reason (RViz's "No transform from [frame] to [fixed]")."""


def stamp_ns(stamp: Any) -> int:
    """A message's ``header.stamp`` [ns] (ROS 2 ``sec``/``nanosec``; ROS 1 ``secs``/``nsecs``)."""
    sec = getattr(stamp, "sec", getattr(stamp, "secs", 0))
    nanosec = getattr(stamp, "nanosec", getattr(stamp, "nsecs", 0))
    return int(sec) * 1_000_000_000 + int(nanosec)


@dataclass(frozen=True, slots=True)
class SubscriptionSpec:
    """A subscription a display wants: ``callback`` gets each message of ``type_name`` on
    ``topic`` (``depth``: the queue size; ``transient_local``: latched, as RViz's Durability
    Policy "Transient Local"), or with ``qos`` when given (RViz 2's policies, see
    :mod:`~robomodel.viewer.displays.topic_qos`)."""

    topic: str
    type_name: str
    callback: Callable[[Any], None] = field(compare=False)
    depth: int = 10
    transient_local: bool = False
    key: str = "Topic"  # which subscription of the display, for specs that equal otherwise
    qos: QoSProfile | None = None

    @property
    def qos_profile(self) -> QoSProfile:
        """The profile subscribed with: ``qos``, else ``depth`` and the durability."""
        if self.qos is not None:
            return self.qos
        durability = Durability.TRANSIENT_LOCAL if self.transient_local else Durability.VOLATILE
        return QoSProfile(self.depth, durability)


@dataclass
class DisplayContext:
    """What a display gets from the viewer.

    Attributes:
        scene: viser's scene API (``server.scene``).
        gui: viser's GUI API (``server.gui``), for displays with page controls.
        fixed_frame: Returns the current Fixed Frame.
        topic_types: Returns the types the graph shows for a topic (empty when unknown).
        post: Runs a callable on the loop thread (from a GUI callback).
        now_ns: The bus's current time [ns] (marker lifetimes, decay times).
        load_mesh: Reads a mesh URI (``package://``, ``file://``, a path) into
            :class:`~robomodel.viewer.meshes.MeshPart` s, cached; raises
            :class:`~robomodel.errors.RobomodelError` (None: no meshes in this viewer).
        view_wxyz: The page's camera orientation in the fixed frame (the last one moved;
            None before a page connects), for view-facing text (None: no page).
        robots: The viewer's robots (its :class:`~robomodel.viewer.session.RobotSession` s),
            for the RobotModel display (None: a viewer without robots).
        clients: The connected pages (viser clients), whose cameras the Camera display
            moves (None: no page).
        frame_rate_hz: RViz's Global Options > Frame Rate (the viewer's), at which the Image
            display shows new images.
    """

    scene: Any
    gui: Any
    fixed_frame: Callable[[], str]
    topic_types: Callable[[str], frozenset[str]]
    post: Callable[[Callable[[], object]], None]
    now_ns: Callable[[], int]
    load_mesh: Callable[[str], tuple[Any, ...]] | None = None
    view_wxyz: Callable[[], tuple[float, float, float, float] | None] | None = None
    robots: Callable[[], Sequence[Any]] | None = None
    clients: Callable[[], Sequence[Any]] | None = None
    frame_rate_hz: Callable[[], float] = lambda: 30.0  # RViz's default Frame Rate
