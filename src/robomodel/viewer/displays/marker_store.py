"""The markers a Marker or MarkerArray display holds: add, modify, delete, deleteall, lifetime.

Transcribed from RViz's MarkerCommon (rviz 1 ``marker_display.cpp``, rviz_default_plugins
``marker_common.cpp``): a marker is keyed by ``(ns, id)``; ADD (0, also MODIFY) replaces the
marker of that key; DELETE (2) removes it; DELETEALL (3) removes every marker of the display,
or (RViz 2, a non-empty ``ns``) every marker of that namespace. A lifetime above zero removes
the marker that long after it arrived (RViz 2: above 100 us); zero keeps it until deleted. A
marker with NaN or infinite numbers is refused with RViz's error line. Namespaces are kept with
their enabled state (the display's ``Namespaces`` option), new ones enabled.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["ADD", "DELETE", "DELETEALL", "MarkerEntry", "MarkerStore"]

ADD = 0  # also MODIFY (visualization_msgs/Marker: MODIFY=0)
DELETE = 2
DELETEALL = 3

MarkerKey = tuple[str, int]
_MIN_LIFETIME_NS = 100_000  # marker_common.cpp configureMarker


def _finite(msg: Any) -> bool:
    """rviz's validateFloats: pose, scale, color and points finite."""
    p, q, s, c = msg.pose.position, msg.pose.orientation, msg.scale, msg.color
    values = [p.x, p.y, p.z, q.x, q.y, q.z, q.w, s.x, s.y, s.z, c.r, c.g, c.b, c.a]
    values += [v for pt in msg.points for v in (pt.x, pt.y, pt.z)]
    return bool(np.isfinite(np.asarray(values, dtype=np.float64)).all())


def _duration_ns(duration: Any) -> int:
    sec = getattr(duration, "sec", getattr(duration, "secs", 0))
    nanosec = getattr(duration, "nanosec", getattr(duration, "nsecs", 0))
    return int(sec) * 1_000_000_000 + int(nanosec)


@dataclass
class MarkerEntry:
    """One marker held: the last message for its key and when it expires.

    Attributes:
        msg: The marker message.
        received_ns: When it arrived [ns, bus time].
        expires_ns: When it goes (None: never).
        version: Counts the messages for this key (the drawing is rebuilt when it changes).
    """

    msg: Any
    received_ns: int
    expires_ns: int | None
    version: int = 0


@dataclass
class MarkerStore:
    """Markers by ``(ns, id)``, and the namespaces seen with their enabled state."""

    markers: dict[MarkerKey, MarkerEntry] = field(default_factory=dict)
    namespaces: dict[str, bool] = field(default_factory=dict)
    errors: list[str] = field(default_factory=list)  # bad actions, newest last
    _versions: int = 0

    def apply(self, msg: Any, now_ns: int) -> None:
        """One marker message (loop thread)."""
        key: MarkerKey = (str(msg.ns), int(msg.id))
        action = int(msg.action)
        if action == ADD and not _finite(msg):
            self._error(f"{key[0]}/{key[1]}: Contains invalid floating point values (nans or infs)")
        elif action == ADD:
            lifetime = _duration_ns(msg.lifetime)
            self._versions += 1
            self.markers[key] = MarkerEntry(
                msg,
                now_ns,
                now_ns + lifetime if lifetime > _MIN_LIFETIME_NS else None,
                self._versions,
            )
            self.namespaces.setdefault(key[0], True)
        elif action == DELETE:
            self.markers.pop(key, None)
        elif action == DELETEALL:
            if key[0]:  # RViz 2 (marker_common.cpp deleteMarkersInNamespace): only that ns
                for other in [k for k in self.markers if k[0] == key[0]]:
                    del self.markers[other]
            else:
                self.markers.clear()
        else:
            self._error(f"Unknown marker action: {action}")  # rviz's words

    def _error(self, text: str) -> None:
        self.errors.append(text)
        del self.errors[:-10]

    def expire(self, now_ns: int) -> list[MarkerKey]:
        """Remove the markers whose lifetime is over; their keys."""
        gone = [k for k, e in self.markers.items() if e.expires_ns is not None and e.expires_ns <= now_ns]  # fmt: skip
        for key in gone:
            del self.markers[key]
        return gone

    def shown(self) -> dict[MarkerKey, MarkerEntry]:
        """The markers of enabled namespaces."""
        return {k: e for k, e in self.markers.items() if self.namespaces.get(k[0], True)}

    def clear(self) -> None:
        self.markers.clear()
        self.errors.clear()
