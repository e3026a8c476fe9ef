"""Robot Steering (rqt_robot_steering): two sliders and a stop button publishing Twist.

As rqt_robot_steering (robot_steering.py ``_on_parameter_changed`` / ``_send_twist``): the
command is re-sent every 100 ms while it is non-zero, and a zero command is sent once, so that
other sources (a joystick, a planner) can take over when the sliders are at rest. The topic is
typed in (default ``/cmd_vel``); TwistStamped is published instead when chosen.

A dead-man switch, which rqt_robot_steering (a window on the robot's own desktop) does not need:
when the last browser page leaves, the sliders go to zero and a zero command is sent once; then
nothing is published until a page moves a slider again. A robot never keeps driving on the
command of a page that is gone.
"""

from __future__ import annotations

from typing import Any

from robomodel.errors import RobomodelError
from robomodel.runtime.msg import Header, Twist, TwistStamped, Vector3
from robomodel.runtime.node import Publisher
from robomodel.viewer.tools.base import ToolContext

__all__ = ["SteeringCommand", "SteeringTool"]

_PERIOD_S = 0.1  # rqt_robot_steering's QTimer: 100 ms
_DEFAULT_TOPIC = "/cmd_vel"
_TWIST = "geometry_msgs/msg/Twist"


class SteeringCommand:
    """The zero-once rule: what to publish for a slider state (None: nothing)."""

    def __init__(self) -> None:
        self.zero_sent = False

    def twist(self, linear_mps: float, angular_radps: float) -> Twist | None:
        if linear_mps == 0.0 and angular_radps == 0.0:
            if self.zero_sent:
                return None
            self.zero_sent = True
        else:
            self.zero_sent = False
        return Twist(Vector3(x=linear_mps), Vector3(z=angular_radps))


class SteeringTool:
    """The "Robot Steering" folder (built inside the caller's container)."""

    def __init__(self, tools: ToolContext) -> None:
        self.tools = tools
        gui = tools.server.gui
        self.command = SteeringCommand()
        self.published = 0
        self.armed = True  # False once the last page left, until a page moves a slider
        self._pages_seen = False
        self._publisher: Publisher[Any] | None = None
        self._key: tuple[str, bool] = ("", False)
        self.topic = gui.add_text(
            "Steering topic", _DEFAULT_TOPIC, hint="geometry_msgs/Twist topic"
        )
        self.stamped = gui.add_checkbox("TwistStamped", False)
        self.linear_max = gui.add_number("Max linear [m/s]", 1.0, min=0.01, max=100.0, step=0.01)
        self.angular_max = gui.add_number(
            "Max angular [rad/s]", 3.0, min=0.01, max=100.0, step=0.01
        )
        self.linear = gui.add_slider(
            "Linear x [m/s]", min=-1.0, max=1.0, step=0.01, initial_value=0.0
        )
        self.angular = gui.add_slider(
            "Angular z [rad/s]", min=-3.0, max=3.0, step=0.01, initial_value=0.0
        )
        self.stop = gui.add_button("Stop", hint="both velocities to zero")
        self.stop.on_click(lambda _e: self.halt())
        self.linear.on_update(self._moved)
        self.angular.on_update(self._moved)
        self.linear_max.on_update(lambda _e: self._set_range(self.linear, self.linear_max))
        self.angular_max.on_update(lambda _e: self._set_range(self.angular, self.angular_max))
        tools.post(lambda: tools.node.create_timer(_PERIOD_S, self.tick))

    def follow_graph(self, topics: dict[str, set[str]]) -> None:
        """While the topic box still shows the default, follow the robot's velocity topic.

        rqt_robot_steering starts on ``/cmd_vel``; a ros2_control diff-drive robot listens on
        ``/<controller>/cmd_vel`` (or ``cmd_vel_unstamped``) instead, so when nothing uses
        ``/cmd_vel`` the first such Twist topic in the graph is chosen. An edited box is kept.
        """
        if self.topic.value != _DEFAULT_TOPIC or _DEFAULT_TOPIC in topics:
            return
        for name in sorted(topics):
            if name.endswith(("/cmd_vel", "/cmd_vel_unstamped")) and _TWIST in topics[name]:
                self.topic.value = name
                return

    @staticmethod
    def _set_range(slider: Any, limit: Any) -> None:
        high = abs(float(limit.value)) or 1.0
        slider.min, slider.max = -high, high
        slider.value = min(max(float(slider.value), -high), high)

    def halt(self) -> None:
        self.linear.value = 0.0
        self.angular.value = 0.0

    def _moved(self, event: Any) -> None:
        if getattr(event, "client", None) is not None:  # a page moved it, not the program
            self.armed = True

    def _watch_pages(self) -> None:
        """The dead-man switch: the last page leaving stops the robot and disarms steering."""
        pages = len(self.tools.server.get_clients())
        if pages:
            self._pages_seen = True
        elif self._pages_seen:
            self._pages_seen = False
            self.armed = False
            self.halt()

    def tick(self) -> None:
        """Every 100 ms on the loop thread: publish the sliders' command (zero once); only the
        zero while disarmed (see :meth:`_watch_pages`)."""
        self._watch_pages()
        linear, angular = float(self.linear.value), float(self.angular.value)
        if not self.armed:
            linear = angular = 0.0
        if self._publisher is None and linear == 0.0 and angular == 0.0:
            return  # nothing moved yet: no publisher in the graph, so the topic can still follow
        twist = self.command.twist(linear, angular)
        if twist is None:
            return
        publisher = self._ensure_publisher()
        if publisher is None:
            return
        if self._key[1]:
            publisher.publish(TwistStamped(Header(self.tools.node.now(), ""), twist))
        else:
            publisher.publish(twist)
        self.published += 1

    def _ensure_publisher(self) -> Publisher[Any] | None:
        key = (str(self.topic.value).strip(), bool(self.stamped.value))
        if key == self._key and self._publisher is not None:
            return self._publisher
        if self._publisher is not None:
            self._publisher.destroy()
            self._publisher = None
        self._key = key
        if not key[0]:
            return None
        try:
            self._publisher = self.tools.node.create_publisher(
                TwistStamped if key[1] else Twist, key[0], 10
            )
        except RobomodelError:  # an invalid topic name: nothing is published
            return None
        return self._publisher
