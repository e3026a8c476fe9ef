"""An RViz configuration (``.rviz``) as plain data: displays, Global Options, the view.

The parts robomodel reads and writes have fields (Fixed Frame, Frame Rate, Background Color,
every display's Class, Name and Enabled, the current view); everything else (each display's
other settings, Panels, Tools, Window Geometry, ...) is kept as read, so that a file written
by RViz and saved again by robomodel keeps what robomodel does not know about, as RViz keeps
the settings of a display whose plugin it cannot load. Nested maps are read-only
(``MappingProxyType``) and sequences tuples, so a config cannot change through an alias.
"""

from __future__ import annotations

import enum
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

__all__ = [
    "RvizConfig",
    "RvizDialect",
    "RvizDisplay",
    "RvizView",
    "freeze",
    "thaw",
]


class RvizDialect(enum.Enum):
    """Which RViz the class names are for: ``rviz/RobotModel`` (ROS 1) or
    ``rviz_default_plugins/RobotModel`` (ROS 2)."""

    ROS1 = "ros1"
    ROS2 = "ros2"

    def display_class(self, kind: str) -> str:
        """The class name of a display kind (``Grid``, ``RobotModel``, ``TF``, ``Orbit``)."""
        return f"{'rviz' if self is RvizDialect.ROS1 else 'rviz_default_plugins'}/{kind}"


def freeze(tree: Any) -> Any:
    """``tree`` with every map read-only and every sequence a tuple."""
    if isinstance(tree, Mapping):
        return MappingProxyType({k: freeze(v) for k, v in tree.items()})
    if isinstance(tree, list | tuple):
        return tuple(freeze(v) for v in tree)
    return tree


def thaw(tree: Any) -> Any:
    """A frozen tree as plain dicts and lists again."""
    if isinstance(tree, Mapping):
        return {k: thaw(v) for k, v in tree.items()}
    if isinstance(tree, tuple | list):
        return [thaw(v) for v in tree]
    return tree


@dataclass(frozen=True, slots=True)
class RvizDisplay:
    """One entry of ``Visualization Manager > Displays``.

    Attributes:
        class_name: ``Class`` (``rviz/TF``, ``rviz_default_plugins/RobotModel``, ...).
        name: ``Name`` as shown in RViz's Displays panel.
        enabled: ``Enabled`` (RViz writes it as ``Value`` too).
        settings: Every other key, as read (``Alpha``, ``Topic``, ``Links``, ...).
    """

    class_name: str
    name: str
    enabled: bool
    settings: Mapping[str, Any]

    @property
    def kind(self) -> str:
        """The class without its plugin package: ``RobotModel`` for both RViz versions."""
        return self.class_name.rsplit("/", 1)[-1]

    def with_settings(
        self, changes: Mapping[str, Any], *, enabled: bool | None = None
    ) -> RvizDisplay:
        """A copy with ``Enabled`` and the settings in ``changes`` changed."""
        settings = dict(self.settings)
        settings.update({k: freeze(v) for k, v in changes.items()})
        return RvizDisplay(
            self.class_name,
            self.name,
            self.enabled if enabled is None else enabled,
            MappingProxyType(settings),
        )


@dataclass(frozen=True, slots=True)
class RvizView:
    """``Views > Current``: the camera (``rviz/Orbit``: Distance, Focal Point, Pitch, Yaw)."""

    class_name: str
    settings: Mapping[str, Any]

    @property
    def is_orbit(self) -> bool:
        return self.class_name.rsplit("/", 1)[-1] == "Orbit"


@dataclass(frozen=True, slots=True)
class RvizConfig:
    """A whole ``.rviz`` file.

    Attributes:
        fixed_frame: Global Options > Fixed Frame (None: not in the file).
        frame_rate_hz: Global Options > Frame Rate (None: not in the file).
        background_rgb: Global Options > Background Color (``48; 48; 48``), 0..255 each.
        displays: Visualization Manager > Displays, in order.
        view: Views > Current (None: not in the file).
        other: The rest of the file with the parts above taken out.
    """

    fixed_frame: str | None
    frame_rate_hz: float | None
    background_rgb: tuple[int, int, int] | None
    displays: tuple[RvizDisplay, ...]
    view: RvizView | None
    other: Mapping[str, Any]

    @property
    def dialect(self) -> RvizDialect | None:
        """ROS 2 when any class is an RViz 2 plugin's, ROS 1 when any is ``rviz/...``."""
        classes = [d.class_name for d in self.displays]
        if self.view is not None:
            classes.append(self.view.class_name)
        classes += [str(p.get("Class", "")) for p in self.other.get("Panels") or () if _is_map(p)]
        if any(c.startswith(("rviz_default_plugins/", "rviz_common/")) for c in classes):
            return RvizDialect.ROS2
        if any(c.startswith("rviz/") for c in classes):
            return RvizDialect.ROS1
        return None

    def last(self, kind: str) -> int | None:
        """The index of the last display of ``kind`` (the one whose settings the viewer
        shows, as later displays draw over earlier ones), or None."""
        found = [i for i, d in enumerate(self.displays) if d.kind == kind]
        return found[-1] if found else None


def _is_map(value: Any) -> bool:
    return isinstance(value, Mapping)
