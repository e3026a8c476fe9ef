"""``/gazebo/model_states`` and ``/gazebo/link_states`` at Gazebo's rate, by ROS version.

- ROS 1 (gazebo_ros_api_plugin.cpp, noetic-devel): each topic at every world update while it
  has subscribers, none while it has none (the plugin connects its world-update callback on a
  topic's first subscriber and disconnects it on the last); a queue of 10.
- ROS 2 (gazebo_ros_state.cpp, ros2 branch): both at the plugin's ``update_rate``, 100 Hz by
  default, subscribed or not; ``KeepLast(1)``.

The ROS 1 callbacks are gated by the publishers' ``get_subscription_count()`` (kept up to date by
the transport, so asking at every step is cheap): while nobody subscribes they neither run nor
break up the stretches that MuJoCo steps in one call (:mod:`robomodel.sim.schedule`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from robomodel.runtime.msg.types.gazebo_msgs import LinkStates, ModelStates

if TYPE_CHECKING:
    from robomodel.runtime.node import Node, Publisher
    from robomodel.sim.engine import Simulation
    from robomodel.sim.states import WorldStates

__all__ = ["GAZEBO_ROS_STATE_RATE_HZ", "publish_states"]

GAZEBO_ROS_STATE_RATE_HZ = 100.0
"""ROS 2's gazebo_ros_state ``update_rate`` default."""


def publish_states(sim: Simulation, node: Node, states: WorldStates, *, ros_version: int) -> None:
    """Schedule the two topics on ``sim``, published by ``node``, as ``ros_version``'s
    gazebo_ros does."""
    depth = 10 if ros_version == 1 else 1
    models = node.create_publisher(ModelStates, "/gazebo/model_states", depth)
    links = node.create_publisher(LinkStates, "/gazebo/link_states", depth)
    if ros_version == 1:
        pairs: tuple[tuple[Publisher[Any], Callable[[], Any]], ...] = (
            (models, states.model_states),
            (links, states.link_states),
        )
        for pub, build in pairs:
            sim.every(0.0, _publishing(pub, build), order=1, active=_has_subscribers(pub))
        return

    def publish(_time_s: float) -> None:
        models.publish(states.model_states())
        links.publish(states.link_states())

    sim.every(GAZEBO_ROS_STATE_RATE_HZ, publish, order=1)


def _publishing(publisher: Publisher[Any], build: Callable[[], Any]) -> Callable[[float], None]:
    def publish(_time_s: float) -> None:
        publisher.publish(build())

    return publish


def _has_subscribers(publisher: Publisher[Any]) -> Callable[[], bool]:
    def active() -> bool:
        return publisher.get_subscription_count() > 0

    return active
