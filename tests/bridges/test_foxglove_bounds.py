"""foxglove_bridge's bounds against raw ``foxglove.sdk.v1`` clients, on the in-process bus: a
client that stops reading a 1 kHz topic of 10 kB messages costs the bridge bounded memory and
loses the oldest messages (its queue is ``send_buffer_limit / 100 kB`` messages); a 64 MiB
client frame closes that client's connection with one line and nothing reaches the bus; a
client publishing faster than ``max_client_messages_per_s`` has the excess dropped, said in
one line."""

from __future__ import annotations

import json
import logging
import struct
import threading
import time
from collections.abc import Iterator
from typing import Any

import pytest
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import ClientConnection, connect

from robomodel.bridges.foxglove_bridge import MAX_CLIENT_FRAME_BYTES, FoxgloveBridge
from robomodel.bridges.rosapi import Ros1Params
from robomodel.description.packages import PackageIndex
from robomodel.launch.param_server import ParamServer
from robomodel.runtime import Context
from robomodel.runtime.msg import get_message_type
from robomodel.runtime.msg.cdr import serialize
from tests.bridges.bus_thread import spun
from tests.bridges.foxglove_ws import next_op, registered, subscribe
from tests.timing import scaled, wait_until

LINES: list[str] = []
SEND_BUFFER_LIMIT = 1_000_000  # bytes: a queue of 10 messages per client
BACKLOG = 10
RATE = 200.0  # client messages a second
STRING = get_message_type("std_msgs/msg/String")
SAID = {"id": 2, "topic": "/said", "encoding": "cdr", "schemaName": "std_msgs/msg/String",
        "schema": "string data", "schemaEncoding": "ros2msg"}  # fmt: skip

# the graph read ten times a second: a test that waits for reads waits less
GRAPH_PERIOD_S = 0.1


@pytest.fixture(scope="module")
def bridge() -> Iterator[FoxgloveBridge]:
    with spun(Context("inproc")) as context:
        found = FoxgloveBridge(context, Ros1Params(ParamServer()), dialect="ros2",
                               package_index=PackageIndex(), port=0, log=LINES.append,
                               graph_period_s=GRAPH_PERIOD_S,
                               send_buffer_limit=SEND_BUFFER_LIMIT,
                               max_client_messages_per_s=RATE)  # fmt: skip
        try:
            yield found
        finally:
            found.stop()


def _client(bridge: FoxgloveBridge, **options: Any) -> ClientConnection:
    ws = connect(f"ws://127.0.0.1:{bridge.port}", subprotocols=["foxglove.sdk.v1"], **options)
    next_op(ws, "serverInfo")
    return ws


def _advertised(bridge: FoxgloveBridge, channel_id: int) -> list[int]:
    """The clients that advertised channel ``channel_id``."""
    with bridge._lock:
        return [client for client, channel in bridge._client_channels if channel == channel_id]


def _rss_mb() -> float:
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    raise AssertionError("no VmRSS in /proc/self/status")


class _Talker:
    """Publishes 10 kB strings on ``/big`` at 1 kHz once started, each starting with its
    8-digit number; never more than 100 ahead of the bus (a loaded machine's executor falls
    behind, and its queue is not the bridge's memory)."""

    def __init__(self, bridge: FoxgloveBridge) -> None:
        node = bridge.context.create_node("big_talker")
        self.publisher = bridge._on_bus(lambda: node.create_publisher(STRING, "/big"))
        self.context = bridge.context
        self.sent = 0
        self.published = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def start(self) -> None:
        self._thread.start()

    def _publish(self) -> None:
        number = self.sent
        self.sent += 1
        msg = STRING(data=f"{number:08d}" + "x" * 10_000)

        def publish() -> None:
            self.publisher.publish(msg)
            self.published += 1

        self.context.executor.post(publish)

    def _run(self) -> None:
        start, tick = time.monotonic(), 0
        while not self._stop.is_set():
            tick += 1
            if self.sent - self.published < 100:
                self._publish()
            self._stop.wait(max(0.0, start + tick / 1000 - time.monotonic()))

    def stop(self) -> int:
        """Stops, then publishes one last message; its number."""
        self._stop.set()
        self._thread.join(timeout=5)
        self._publish()
        return self.sent - 1


def test_a_client_that_stops_reading_costs_bounded_memory(bridge: FoxgloveBridge) -> None:
    talker = _Talker(bridge)
    # max_queue=1: the client library stops reading the socket once it holds a frame
    with _client(bridge, max_queue=1) as ws:
        subscribe(ws, 1, registered(ws, bridge, "/big")["id"])
        wait_until(lambda: talker.publisher.get_subscription_count() == 1, 60, what="subscribed")
        talker.start()
        first = talker.sent
        # a second for the socket buffers to fill, then 25 MB more to a client reading nothing
        wait_until(lambda: talker.sent >= first + 1000, 10, what="a second of messages")
        before_mb, start = _rss_mb(), talker.sent
        wait_until(lambda: talker.sent >= start + 2500, 20, what="2.5 s of messages")
        grown_mb = _rss_mb() - before_mb
        last = talker.stop()
        got: list[int] = []
        while not got or got[-1] != last:
            frame = ws.recv(timeout=scaled(10))
            if isinstance(frame, bytes):  # messageData: opcode, subscription, time, CDR
                got.append(int(frame[13 + 8 : 13 + 16]))
    assert grown_mb < 10, f"the bridge grew {grown_mb:.1f} MB while a client read nothing"
    assert got == sorted(got) and len(got) < (last - first) / 2, (len(got), last - first)
    # the newest messages come last, after the gap the dropped ones left: the SDK's queue of
    # send_buffer_limit / 100 kB messages (and the one its writer held)
    tail = 1
    while tail < len(got) and got[-tail - 1] == got[-tail] - 1:
        tail += 1
    assert tail <= BACKLOG + 2, f"{tail} messages in a row at the end: {got[-tail:][:5]}..."


def test_a_64_mib_frame_closes_that_client(
    bridge: FoxgloveBridge, caplog: pytest.LogCaptureFixture
) -> None:
    heard: list[int] = []
    node = bridge.context.create_node("big_listener")
    bridge._on_bus(
        lambda: node.create_subscription(STRING, "/said", lambda m: heard.append(len(m.data)))
    )
    payload = struct.pack("<BI", 1, SAID["id"]) + serialize(STRING(data="x" * 64 * 2**20))
    with caplog.at_level(logging.WARNING), _client(bridge, max_size=None) as ws:
        ws.send(json.dumps({"op": "advertise", "channels": [SAID]}))
        with pytest.raises(ConnectionClosed):
            ws.send(payload)
            ws.recv(timeout=scaled(10))
        wait_until(lambda: "Message too long" in caplog.text, 10, what="the SDK's refusal")
    refusals = [r.getMessage() for r in caplog.records if "Message too long" in r.getMessage()]
    assert len(refusals) == 1, refusals
    assert f"{len(payload)} > {MAX_CLIENT_FRAME_BYTES}" in refusals[0], refusals
    with _client(bridge) as ws:  # the bridge serves the next client
        ws.send(json.dumps({"op": "advertise", "channels": [SAID]}))
        small = struct.pack("<BI", 1, SAID["id"]) + serialize(STRING(data="small"))
        wait_until(lambda: bool(ws.send(small)) or bool(heard), 10, what="a small message")
    assert heard and max(heard) == len("small"), heard


def test_a_flood_of_client_messages_is_cut_to_the_rate(bridge: FoxgloveBridge) -> None:
    heard = [0]
    node = bridge.context.create_node("flood_listener")

    def count(_: Any) -> None:
        heard[0] += 1

    bridge._on_bus(lambda: node.create_subscription(STRING, "/flood", count, 10_000))
    flood = {**SAID, "id": 3, "topic": "/flood"}
    frame = struct.pack("<BI", 1, 3) + serialize(STRING(data="x" * 100))
    sent = 2000
    with _client(bridge) as ws:
        ws.send(json.dumps({"op": "advertise", "channels": [flood]}))
        wait_until(lambda: _advertised(bridge, 3), 10, what="the client's channel")
        client = _advertised(bridge, 3)[0]
        start = time.monotonic()
        for _ in range(sent):
            ws.send(frame)
        wait_until(lambda: bridge.client_flow(client)[0] == sent, 20,
                   what=lambda: f"the flood at the bridge: {bridge.client_flow(client)}")  # fmt: skip
        elapsed = time.monotonic() - start
        _, dropped = bridge.client_flow(client)
        wait_until(lambda: heard[0] == sent - dropped, 10, what="the admitted messages")
    assert 0 < sent - dropped <= RATE * (1 + elapsed) + 1, (sent - dropped, elapsed)
    said = [line for line in LINES if "messages a second" in line]
    assert said == [f"foxglove_bridge: client {client} publishes more than {RATE:g} messages "
                    "a second: the excess is dropped"], LINES  # fmt: skip
