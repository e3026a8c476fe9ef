"""Robots that a RobotModel display names and the viewer did not load: loaded from the bus
or from their file.

RViz's RobotModel display draws the robot of its Description Topic: RViz 2 subscribes to it
(``std_msgs/msg/String``, transient local, as robot_state_publisher publishes it; RViz 2's
robot_model_display.cpp), RViz 1 reads the parameter of that name from the master, again
every second while it does not exist (RViz 1's robot_model_display.cpp, ``load``). The
viewer's own robots (its files, a launch's) answer to their topics already; for any other
topic an enabled RobotModel display names, :class:`TopicRobots` opens a session that follows
it (the session of ``view --description-topic``: reloaded when a new description arrives,
drawn from TF like the other robots, no publishers of its own) and closes it when no enabled
RobotModel display names that topic any more (removed, disabled, or another topic), as RViz
unsubscribes and clears its robot.

Description Source ``File`` likewise: RViz 2 reads its Description File when the display is
enabled or the file's name set (robot_model_display.cpp, ``load_urdf_from_file``) and draws
its links where TF has them, publishing nothing. For a file the viewer did not load, the same
kind of session opens on that file (its FileWatcher reads it at the viewer's next reload check
and again whenever it or a file it includes changes; RViz 2 reads it only then). robomodel's
loader reads URDF or xacro, as ``view`` does (RViz 2: URDF only); a load error is the
display's status with the file:line the loader gives, a missing file's "No such file or
directory" among them (RViz 2 says "URDF is empty" or "URDF failed Model parse").
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from typing import Any

from robomodel.viewer.displays.base import Display
from robomodel.viewer.displays.robot_model import RobotModelDisplay, topic_name
from robomodel.viewer.reload import FileWatcher, ParamWatcher
from robomodel.viewer.session import RobotSession, RobotSource

__all__ = ["TopicRobots"]

_Key = tuple[str, str]  # ("Topic", global name) or ("File", absolute path)


class TopicRobots:
    """The sessions opened for RobotModel displays' topics and files (loop thread).

    Args:
        viewer: The viewer (its ``sessions`` list is replaced, never changed in place, as
            other threads may be iterating the old one; ``options``, ``context``).
        node: The viewer's node (the subscriptions' owner).
        forget: Called with a closed session's number (the viewer drops what it kept).
    """

    def __init__(self, viewer: Any, node: Any, forget: Callable[[int], None]) -> None:
        self._viewer = viewer
        self._node = node
        self._forget = forget
        self.sessions: dict[_Key, RobotSession] = {}
        self._next_number = len(viewer.sessions)

    def sync(self, displays: Sequence[Display]) -> None:
        """Open a session for each topic or file an enabled RobotModel display names that no
        robot of the viewer's is described on; close those no display names any more."""
        mine = set(map(id, self.sessions.values()))
        own = [s for s in self._viewer.sessions if id(s) not in mine]
        wanted: set[_Key] = set()
        for display in displays:
            if isinstance(display, RobotModelDisplay) and display.enabled:
                key = _wanted(display, own)
                if key is not None:
                    wanted.add(key)
        for key in sorted(set(self.sessions) - wanted):
            self._close(key)
        for key in sorted(wanted - set(self.sessions)):
            self._open(key)

    def _open(self, key: _Key) -> None:
        viewer = self._viewer
        kind, name = key
        source = (
            RobotSource(name, external=True)
            if kind == "File"
            else RobotSource("", topic=name, external=True)
        )
        # external: RViz publishes nothing for its robot; the description's own nodes do
        session = RobotSession(
            self._next_number,
            source,
            index=viewer.options.package_index,
            external=True,
            state_publisher=False,
        )
        self._next_number += 1
        master_uri = getattr(viewer.context.transport, "master_uri", None)
        if isinstance(session.watcher, FileWatcher):
            session.watcher.unread()  # read (or its error shown) at the next reload check
        elif viewer.options.bus == "ros1" and master_uri is not None:
            session.watcher = ParamWatcher(name, master_uri)
        session.start_nodes(viewer.context, self._node)
        self.sessions[key] = session
        viewer.sessions = [*viewer.sessions, session]

    def _close(self, key: _Key) -> None:
        session = self.sessions.pop(key)
        session.close()
        session.close_nodes()
        self._viewer.sessions = [s for s in self._viewer.sessions if s is not session]
        self._forget(session.number)

    def close(self) -> None:
        for key in list(self.sessions):
            self.sessions.pop(key).close_nodes()


def _wanted(display: RobotModelDisplay, own: Sequence[RobotSession]) -> _Key | None:
    """The topic or file ``display`` names when none of the viewer's robots ``own`` is
    described there (None: one is, or it names nothing)."""
    if any(display.describes(s) for s in own):
        return None
    if display.option("Description Source") == "File":
        path = str(display.option("Description File"))
        # RViz 2's load_urdf: an empty Description File loads nothing
        return ("File", os.path.abspath(path)) if path.strip() else None
    name = topic_name(str(display.option("Description Topic")))
    return ("Topic", name) if name != "/" else None
