"""The bounds every bridge keeps, whatever its clients send or fail to read.

A client's frame over ``max_frame_bytes`` closes its connection (WebSocket code 1009, as
tornado's ``max_message_size`` does for rosbridge); more than ``max_ops_per_s`` requests a
second (over a burst of as many) close it too (1008, policy violation). Outgoing messages wait
in a queue of at most ``send_buffer_bytes`` per client (foxglove_bridge's ``send_buffer_limit``,
whose default this is): when it is full the oldest are dropped and counted, so a slow client
costs bounded memory. ``max_clients`` connections at once, each with at most
``max_endpoints`` subscriptions, advertisements, advertised services and actions.

rosbridge's ``fragment`` operation: a client's fragmented message is held until its last
fragment came, at most ``max_fragment_bytes`` of fragments per client (a reassembled message is
a frame, so it is bounded as one), ``max_fragmented_messages`` messages at once, each of at most
``max_fragments`` fragments; fragments older than ``fragment_timeout_s`` (rosbridge's
``fragment_timeout``) are forgotten. Outgoing, ``fragment_size`` is at least
``min_fragment_bytes``. ``png`` compression takes messages of at most ``max_png_bytes`` of JSON
(larger ones go as plain JSON).
"""

from __future__ import annotations

from dataclasses import dataclass

from robomodel.bridges.exceptions import BridgeError

__all__ = ["BridgeLimits"]


@dataclass(frozen=True, slots=True)
class BridgeLimits:
    """A bridge's bounds (see the module docstring)."""

    max_frame_bytes: int = 10_000_000
    max_ops_per_s: float = 5_000.0
    send_buffer_bytes: int = 10_000_000
    max_clients: int = 64
    max_endpoints: int = 1_000
    max_fragment_bytes: int = 10_000_000
    max_fragmented_messages: int = 16
    max_fragments: int = 10_000
    fragment_timeout_s: float = 600.0
    min_fragment_bytes: int = 100
    max_png_bytes: int = 10_000_000

    def __post_init__(self) -> None:
        for name in ("max_frame_bytes", "max_ops_per_s", "send_buffer_bytes", "max_clients",
                     "max_endpoints", "max_fragment_bytes", "max_fragmented_messages",
                     "max_fragments", "fragment_timeout_s", "min_fragment_bytes",
                     "max_png_bytes"):  # fmt: skip
            value = getattr(self, name)
            if isinstance(value, bool) or not value > 0:
                raise BridgeError(f"bridge limit {name} must be a positive number, got {value!r}")
