"""A raw ``foxglove.sdk.v1`` client's steps, for the tests of foxglove_bridge in this process:
the next control message of an op, a topic's channel, a subscription, the next data frame."""

from __future__ import annotations

import json
from typing import Any

from tests.timing import scaled, wait_until


def next_op(ws: Any, op: str) -> dict[str, Any]:
    """The next JSON control message whose ``op`` is ``op`` (the others are passed over)."""
    while True:
        frame = ws.recv(timeout=scaled(10))
        if isinstance(frame, str) and json.loads(frame)["op"] == op:
            return json.loads(frame)  # type: ignore[no-any-return]


def advertised(ws: Any, topic: str) -> dict[str, Any]:
    """The channel of ``topic`` in the next advertisement that has one (the bridge advertises
    a topic at the read of the graph after it appeared)."""
    while True:
        found = [c for c in next_op(ws, "advertise")["channels"] if c["topic"] == topic]
        if found:
            return found[0]  # type: ignore[no-any-return]


def registered(ws: Any, bridge: Any, topic: str) -> dict[str, Any]:
    """The channel of ``topic`` in the next advertisement that has one, once the bridge holds
    it: the Foxglove SDK sends a channel's advertisement before it registers the channel, and
    refuses a subscription in between (which the bridge repairs by advertising the topic again,
    a step these tests do not follow); the bridge holds the channel once it is registered."""
    channel = advertised(ws, topic)

    def held() -> bool:
        with bridge._lock:
            found = bridge._topics.get(topic)
            return found is not None and found.channel.id() == channel["id"]

    wait_until(held, 10, what=f"the bridge's channel {channel['id']} of {topic}")
    return channel


def subscribe(ws: Any, subscription: int, channel: int) -> None:
    ws.send(
        json.dumps(
            {"op": "subscribe", "subscriptions": [{"id": subscription, "channelId": channel}]}
        )
    )


def next_binary(ws: Any) -> bytes:
    """The next binary frame (``messageData``: opcode, subscription, time, payload)."""
    frame = ws.recv(timeout=scaled(10))
    while isinstance(frame, str):
        frame = ws.recv(timeout=scaled(10))
    return frame  # type: ignore[no-any-return]
