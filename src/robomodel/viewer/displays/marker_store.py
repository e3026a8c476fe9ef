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

from robomodel.viewer.limits import MAX_MARKERS, MAX_MARKERS_PER_NAMESPACE

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
    notes: list[str] = field(default_factory=list)  # markers refused over a bound
    _versions: int = 0
    _per_namespace: dict[str, int] = field(default_factory=dict)

    def apply(self, msg: Any, now_ns: int) -> None:
        """One marker message (loop thread)."""
        key: MarkerKey = (str(msg.ns), int(msg.id))
        action = int(msg.action)
        if action == ADD and not _finite(msg):
            self._error(f"{key[0]}/{key[1]}: Contains invalid floating point values (nans or infs)")
        elif action == ADD:
            if key not in self.markers and not self._room_for(key[0]):
                return
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
            self._remove(key)
        elif action == DELETEALL:
            if key[0]:  # RViz 2 (marker_common.cpp deleteMarkersInNamespace): only that ns
                for other in [k for k in self.markers if k[0] == key[0]]:
                    self._remove(other)
            else:
                self.markers.clear()
                self._per_namespace.clear()
        else:
            self._error(f"Unknown marker action: {action}")  # rviz's words

    def _room_for(self, ns: str) -> bool:
        """Whether a new marker fits in ``ns`` (counted if so); over a bound, a note says
        which markers are not drawn."""
        held = self._per_namespace.get(ns, 0)
        if held >= MAX_MARKERS_PER_NAMESPACE:
            self._note(f"{ns}: more than {MAX_MARKERS_PER_NAMESPACE} markers in the namespace; "
                       "new ids are not drawn")  # fmt: skip
            return False
        if len(self.markers) >= MAX_MARKERS:
            self._note(f"more than {MAX_MARKERS} markers; new ones are not drawn")
            return False
        self._per_namespace[ns] = held + 1
        return True

    def _remove(self, key: MarkerKey) -> None:
        if self.markers.pop(key, None) is not None:
            self._per_namespace[key[0]] -= 1

    def _note(self, text: str) -> None:
        if text not in self.notes:
            self.notes.append(text)
            del self.notes[:-10]

    def _error(self, text: str) -> None:
        self.errors.append(text)
        del self.errors[:-10]

    def expire(self, now_ns: int) -> list[MarkerKey]:
        """Remove the markers whose lifetime is over; their keys."""
        gone = [k for k, e in self.markers.items() if e.expires_ns is not None and e.expires_ns <= now_ns]  # fmt: skip
        for key in gone:
            self._remove(key)
        return gone

    def shown(self) -> dict[MarkerKey, MarkerEntry]:
        """The markers of enabled namespaces."""
        return {k: e for k, e in self.markers.items() if self.namespaces.get(k[0], True)}

    def clear(self) -> None:
        self.markers.clear()
        self.errors.clear()
        self.notes.clear()
        self._per_namespace.clear()
