"""Robots that a RobotModel display names and the viewer did not load: loaded from the bus.

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
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from robomodel.viewer.displays.base import Display
from robomodel.viewer.displays.robot_model import RobotModelDisplay, topic_name
from robomodel.viewer.reload import ParamWatcher
from robomodel.viewer.session import RobotSession, RobotSource

__all__ = ["TopicRobots"]


class TopicRobots:
    """The sessions opened for RobotModel displays' topics (loop thread).

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
        self.sessions: dict[str, RobotSession] = {}
        self._next_number = len(viewer.sessions)

    def sync(self, displays: Sequence[Display]) -> None:
        """Open a session for each topic an enabled RobotModel display names that no robot of
        the viewer's is described on; close those no display names any more."""
        mine = set(map(id, self.sessions.values()))
        own = [s for s in self._viewer.sessions if id(s) not in mine]
        wanted: set[str] = set()
        for display in displays:
            if not isinstance(display, RobotModelDisplay) or not display.enabled:
                continue
            if display.option("Description Source") != "Topic":
                continue
            name = topic_name(str(display.option("Description Topic")))
            if name != "/" and not any(name in s.description_names for s in own):
                wanted.add(name)
        for topic in sorted(set(self.sessions) - wanted):
            self._close(topic)
        for topic in sorted(wanted - set(self.sessions)):
            self._open(topic)

    def _open(self, topic: str) -> None:
        viewer = self._viewer
        # external: RViz publishes nothing for its robot; the description's own nodes do
        session = RobotSession(
            self._next_number,
            RobotSource("", topic=topic, external=True),
            index=viewer.options.package_index,
            external=True,
            state_publisher=False,
        )
        self._next_number += 1
        master_uri = getattr(viewer.context.transport, "master_uri", None)
        if viewer.options.bus == "ros1" and master_uri is not None:
            session.watcher = ParamWatcher(topic, master_uri)
        session.start_nodes(viewer.context, self._node)
        self.sessions[topic] = session
        viewer.sessions = [*viewer.sessions, session]

    def _close(self, topic: str) -> None:
        session = self.sessions.pop(topic)
        session.close()
        session.close_nodes()
        self._viewer.sessions = [s for s in self._viewer.sessions if s is not session]
        self._forget(session.number)

    def close(self) -> None:
        for topic in list(self.sessions):
            self.sessions.pop(topic).close_nodes()
