"""Live reload: polling the modification times of a description and the files it includes,
or following the description another process publishes on a topic.

Polling (a few times a second) needs no extra dependency and works the same on every
platform and filesystem, including editors that save by renaming a new file into place.
"""

from __future__ import annotations

import os
import threading
from collections.abc import Iterable
from typing import Any

__all__ = ["FileWatcher", "TopicWatcher"]

_Stamp = tuple[int, int] | None
_UNREAD: _Stamp = (-1, -1)  # no file has it: a baseline that any state differs from


def _stamp(path: str) -> _Stamp:
    try:
        st = os.stat(path)
    except OSError:
        return None
    return (st.st_mtime_ns, st.st_size)


class FileWatcher:
    """Remembers (mtime, size) of a set of files and reports when any of them changed."""

    def __init__(self, paths: Iterable[str] = ()) -> None:
        self._stamps: dict[str, _Stamp] = {}
        self.watch(paths)

    @property
    def paths(self) -> tuple[str, ...]:
        return tuple(self._stamps)

    def watch(self, paths: Iterable[str]) -> None:
        """Watch exactly ``paths`` from now on, taking their current state as the baseline."""
        self._stamps = {os.path.abspath(p): _stamp(os.path.abspath(p)) for p in paths}

    def add(self, paths: Iterable[str]) -> None:
        """Also watch ``paths`` (baseline: their current state), keeping the others."""
        for path in paths:
            full = os.path.abspath(path)
            self._stamps.setdefault(full, _stamp(full))

    def unread(self) -> None:
        """Forget the baselines: the next :meth:`changed` reports every file, even one that
        does not exist (a description not read yet is read, or its error shown, by the
        viewer's next reload check)."""
        self._stamps = dict.fromkeys(self._stamps, _UNREAD)

    def changed(self) -> tuple[str, ...]:
        """Files that changed (or appeared or vanished) since the last call; updates baselines."""
        changed = []
        for path, old in self._stamps.items():
            new = _stamp(path)
            if new != old:
                self._stamps[path] = new
                changed.append(path)
        return tuple(changed)


class TopicWatcher:
    """The latest robot description on a topic (``std_msgs/String``, transient local, as
    robot_state_publisher publishes ``/robot_description``): ``changed`` reports a new one.

    The same interface as :class:`FileWatcher`, so a session reloads from either.
    """

    def __init__(self, topic: str) -> None:
        self.topic = topic
        self.text: str | None = None
        self._new = False
        self._lock = threading.Lock()
        self._subscription: Any = None

    @property
    def paths(self) -> tuple[str, ...]:
        return ()

    def subscribe(self, node: Any) -> None:
        from robomodel.runtime.msg import String
        from robomodel.runtime.qos import latched

        self._subscription = node.create_subscription(
            String, self.topic, self._on_description, latched()
        )

    def unsubscribe(self) -> None:
        """End the subscription (a robot removed from the viewer)."""
        if self._subscription is not None:
            self._subscription.destroy()
            self._subscription = None

    def _on_description(self, msg: Any) -> None:
        with self._lock:
            if msg.data != self.text:
                self.text, self._new = msg.data, True

    def watch(self, paths: Iterable[str]) -> None:
        """Nothing to watch on disk (a description from a topic has no files)."""

    def add(self, paths: Iterable[str]) -> None:
        """Likewise."""

    def changed(self) -> tuple[str, ...]:
        with self._lock:
            new, self._new = self._new, False
        return (self.topic,) if new else ()


class ParamWatcher(TopicWatcher):
    """The robot description in a ROS 1 master's parameter ``name``, as RViz 1's RobotModel
    reads its Robot Description: read once it exists, asked again every second until then
    (robot_model_display.cpp, ``load``). A thread asks, so the viewer's loop never waits on
    the master.

    Args:
        name: The parameter's global name.
        master_uri: The master's XML-RPC URI.
        period_s: How long to wait before asking again.
    """

    def __init__(self, name: str, master_uri: str, period_s: float = 1.0) -> None:
        super().__init__(name)
        self.master_uri = master_uri
        self.period_s = period_s
        self._stop = threading.Event()

    def subscribe(self, node: Any) -> None:
        thread = threading.Thread(target=self._read, name=f"param {self.topic}", daemon=True)
        thread.start()

    def _read(self) -> None:
        from types import SimpleNamespace

        from robomodel.runtime.transport.ros1.param_client import MasterParams
        from robomodel.runtime.transport.ros1.param_tree import ParamServerError

        params = MasterParams(self.master_uri, caller_id="/robomodel_viewer")
        while not self._stop.is_set():
            try:
                text = params.get(self.topic)
            except ParamServerError:  # not (yet) set, or the master does not answer
                text = None
            if isinstance(text, str):
                self._on_description(SimpleNamespace(data=text))
                return
            self._stop.wait(self.period_s)

    def unsubscribe(self) -> None:
        self._stop.set()
