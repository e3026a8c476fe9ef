"""``rclpy.wait_for_message.wait_for_message``: the next message on a topic."""

from __future__ import annotations

import time
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from robomodel.clientlibs.rclpy.node import Node

__all__ = ["wait_for_message"]


def wait_for_message(
    msg_type: Any,
    node: Node,
    topic: str,
    *,
    qos_profile: Any = 1,
    time_to_wait: float = -1,
) -> tuple[bool, Any]:
    """(True, message) for the next message on ``topic``; (False, None) if none came within
    ``time_to_wait`` seconds (negative: wait for ever) or the context shut down."""
    from robomodel.clientlibs.rclpy.executors import SingleThreadedExecutor

    received: list[Any] = []
    subscription = node.create_subscription(msg_type, topic, received.append, qos_profile)
    executor = SingleThreadedExecutor(context=node.context)
    owner = node.executor
    executor.add_node(node)  # the subscription is the node's: its executor runs it
    deadline = None if time_to_wait < 0 else time.monotonic() + time_to_wait
    try:
        while not received and node.context.ok():
            remaining = 0.05 if deadline is None else deadline - time.monotonic()
            if remaining <= 0:
                break
            executor.spin_once(timeout_sec=min(remaining, 0.05))
    finally:
        executor.remove_node(node)
        node.executor = owner
        node.destroy_subscription(subscription)
    return (True, received[0]) if received else (False, None)
