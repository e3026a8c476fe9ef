"""foxglove_bridge on the in-process bus with a raw ``foxglove.sdk.v1`` client: a channel's
schema is the type's ros2msg text and its messages are the CDR robomodel's codec makes, the
server's connections have Nagle's algorithm off, a client channel with an invalid name is
refused with one line while a valid one publishes, bad settings are one-line errors."""

from __future__ import annotations

import json
import logging
import os
import socket
import struct
from collections.abc import Iterator
from typing import Any

import pytest
from websockets.sync.client import connect

from robomodel.bag.typedefs import ros2msg_definition
from robomodel.bridges import BridgeError
from robomodel.bridges.exceptions import ClientError
from robomodel.bridges.foxglove_bridge import (
    SEND_BUFFER_BYTES,
    FoxgloveBridge,
    _RefusedSubscriptions,
)
from robomodel.bridges.rosapi import Ros1Params
from robomodel.description.packages import PackageIndex
from robomodel.launch.param_server import ParamServer
from robomodel.runtime import Context
from robomodel.runtime.msg import get_message_type
from robomodel.runtime.msg.cdr import serialize
from tests.bridges.bus_thread import spun
from tests.bridges.foxglove_ws import advertised, next_binary, next_op, registered, subscribe
from tests.timing import wait_until

LINES: list[str] = []
PARAMS = ParamServer()

# the graph read ten times a second: a test that waits for reads waits less
GRAPH_PERIOD_S = 0.1


@pytest.fixture(scope="module")
def bridge() -> Iterator[FoxgloveBridge]:
    with spun(Context("inproc")) as context:
        found = FoxgloveBridge(context, Ros1Params(PARAMS), dialect="ros2",
                               package_index=PackageIndex(), port=0, log=LINES.append,
                               graph_period_s=GRAPH_PERIOD_S)  # fmt: skip
        try:
            yield found
        finally:
            found.stop()


def _server_sockets(port: int) -> list[tuple[int, int]]:
    """TCP_NODELAY and SO_SNDBUF of each of this process's TCP sockets on ``port`` (listener,
    connections)."""
    found = []
    for name in os.listdir("/proc/self/fd"):
        try:
            if not os.readlink(f"/proc/self/fd/{name}").startswith("socket:"):
                continue
            sock = socket.socket(fileno=os.dup(int(name)))
        except OSError:
            continue
        with sock:
            inet = sock.family == socket.AF_INET and sock.type == socket.SOCK_STREAM
            if inet and sock.getsockname()[1] == port:
                found.append(
                    (
                        sock.getsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY),
                        sock.getsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF),
                    )
                )
    return found


def test_channel_schema_and_cdr_messages(bridge: FoxgloveBridge) -> None:
    vector = get_message_type("geometry_msgs/msg/Vector3Stamped")
    node = bridge.context.create_node("talker")
    publisher = bridge._on_bus(lambda: node.create_publisher(vector, "/wind"))
    msg = vector(vector=get_message_type("geometry_msgs/msg/Vector3")(x=1.5, y=-2.0, z=0.25))
    with connect(f"ws://127.0.0.1:{bridge.port}", subprotocols=["foxglove.sdk.v1"]) as ws:
        assert next_op(ws, "serverInfo")["supportedEncodings"] == ["cdr"]
        asked = socket.socket()  # the kernel's answer to the bridge's request, on this machine
        asked.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, SEND_BUFFER_BYTES)
        with asked:
            send_buffer = asked.getsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF)
        assert _server_sockets(bridge.port) == [(1, send_buffer)] * 2  # listener, connection
        channel = registered(ws, bridge, "/wind")
        assert channel["encoding"] == "cdr" and channel["schemaEncoding"] == "ros2msg"
        assert channel["schema"] == ros2msg_definition(vector)
        subscribe(ws, 7, channel["id"])
        wait_until(lambda: publisher.get_subscription_count() == 1, 10, what="the bus subscription")
        bridge.context.executor.post(lambda: publisher.publish(msg))
        frame = next_binary(ws)
        assert frame[0] == 1 and struct.unpack_from("<I", frame, 1)[0] == 7
        assert frame[13:] == serialize(msg)


def test_a_subscription_the_sdk_refused_gets_the_topic_advertised_again(
    bridge: FoxgloveBridge,
) -> None:
    """The Foxglove SDK sends a new channel's advertisement before it registers the channel, and
    refuses a subscription that comes in between with a line in its log. The bridge reads that
    line (its text checked here against the SDK's own, for a channel that does not exist),
    advertises the topic anew, and the client's subscription to the new channel gets data."""
    string = get_message_type("std_msgs/msg/String")
    node = bridge.context.create_node("again_talker")
    publisher = bridge._on_bus(lambda: node.create_publisher(string, "/again"))
    sdk_lines: list[str] = []
    capture = logging.Handler(logging.ERROR)
    capture.emit = lambda record: sdk_lines.append(record.getMessage())  # type: ignore[method-assign]
    logging.getLogger("foxglove").addHandler(capture)
    try:
        with connect(f"ws://127.0.0.1:{bridge.port}", subprotocols=["foxglove.sdk.v1"]) as ws:
            next_op(ws, "serverInfo")
            first = advertised(ws, "/again")
            subscribe(ws, 1, 2**31)
            assert "Unknown channel ID: 2147483648" in next_op(ws, "status")["message"]
            said = wait_until(
                lambda: [m for m in sdk_lines if _RefusedSubscriptions.PATTERN.search(m)],
                10,
                what="the SDK's line for a subscription to a channel it does not know",
            )
            assert said[0].endswith(f"unknown channel: {2**31}")
            # the same line for the channel of /again, as the SDK writes it in the race
            logging.getLogger("foxglove.websocket.connected_client").error(
                "Client %s attempted to subscribe to unknown channel: %d",
                "127.0.0.1:1",
                first["id"],
            )
            assert next_op(ws, "unadvertise")["channelIds"] == [first["id"]]
            again = registered(ws, bridge, "/again")
            assert again["id"] != first["id"] and again["schema"] == first["schema"]
            subscribe(ws, 2, again["id"])
            wait_until(
                lambda: publisher.get_subscription_count() == 1, 10, what="the bus subscription"
            )
            bridge.context.executor.post(lambda: publisher.publish(string(data="here")))
            frame = next_binary(ws)
            assert struct.unpack_from("<I", frame, 1)[0] == 2
            assert frame[13:] == serialize(string(data="here"))
    finally:
        logging.getLogger("foxglove").removeHandler(capture)
    assert any(line.startswith("foxglove_bridge: advertising /again again") for line in LINES)


def test_refused_subscriptions_note_the_bridge_s_channels_and_newer_ones_only() -> None:
    """The SDK's line comes while a new channel is being made, before the bridge knows its id:
    ids above the newest of the bridge's are noted, older ones not its own are not, and no
    more than MAX_NOTED are kept between two reads."""
    refusals = _RefusedSubscriptions()
    refusals.watch(frozenset({3, 7}))
    log = logging.getLogger("test.refusals")
    log.propagate = False
    log.addHandler(refusals)
    try:
        for channel_id in (2, 3, 5, 8, 9):
            log.error("Client %s attempted to subscribe to unknown channel: %d", "c:1", channel_id)
        log.error("Client c:1 sent something else about channel: 11")
        assert refusals.take() == {3, 8, 9}
        assert refusals.take() == set()
        for channel_id in range(100, 100 + 2 * _RefusedSubscriptions.MAX_NOTED):
            log.error("Client c:1 attempted to subscribe to unknown channel: %d", channel_id)
        assert len(refusals.take()) == _RefusedSubscriptions.MAX_NOTED
    finally:
        log.removeHandler(refusals)


def test_a_bus_subscription_not_made_in_time_is_made_at_the_next_graph_read(
    bridge: FoxgloveBridge, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A busy bus that does not make a topic's subscription when the first client subscribes
    costs one line: the next read of the graph makes it, and the client gets its data."""
    string = get_message_type("std_msgs/msg/String")
    node = bridge.context.create_node("busy_talker")
    publisher = bridge._on_bus(lambda: node.create_publisher(string, "/busy"))
    subscribe_on_bus = bridge._subscribe
    calls: list[str] = []

    def busy_once(name: str, topic: Any) -> Any:
        calls.append(name)
        if len(calls) == 1:
            raise ClientError("the bus did not answer in time")
        return subscribe_on_bus(name, topic)

    monkeypatch.setattr(bridge, "_subscribe", busy_once)
    with connect(f"ws://127.0.0.1:{bridge.port}", subprotocols=["foxglove.sdk.v1"]) as ws:
        next_op(ws, "serverInfo")
        subscribe(ws, 3, registered(ws, bridge, "/busy")["id"])
        wait_until(lambda: publisher.get_subscription_count() == 1, 10, what="the bus subscription")
        bridge.context.executor.post(lambda: publisher.publish(string(data="late")))
        frame = next_binary(ws)
        assert frame[13:] == serialize(string(data="late"))
    assert calls == ["/busy", "/busy"]
    assert (
        "foxglove_bridge: subscribing to /busy on the bus failed: the bus did not answer in "
        "time; trying again at the next read of the graph" in LINES
    )


def test_client_publish_takes_valid_names_only(bridge: FoxgloveBridge) -> None:
    string = get_message_type("std_msgs/msg/String")
    heard: list[str] = []
    node = bridge.context.create_node("listener")
    bridge._on_bus(
        lambda: node.create_subscription(string, "/said", lambda m: heard.append(m.data))
    )
    with connect(f"ws://127.0.0.1:{bridge.port}", subprotocols=["foxglove.sdk.v1"]) as ws:
        next_op(ws, "serverInfo")
        channels = [
            {"id": 1, "topic": "/bad name", "encoding": "cdr", "schemaName": "std_msgs/msg/String",
             "schema": "string data", "schemaEncoding": "ros2msg"},
            {"id": 2, "topic": "/said", "encoding": "cdr", "schemaName": "std_msgs/msg/String",
             "schema": "string data", "schemaEncoding": "ros2msg"},
        ]  # fmt: skip
        ws.send(json.dumps({"op": "advertise", "channels": channels}))
        payload = serialize(string(data="through foxglove"))
        wait_until(lambda: any("/bad name" in line for line in LINES), 10, what="the refusal")
        for channel_id in (1, 2):  # clientMessageData: opcode 1, channel id, payload
            ws.send(struct.pack("<BI", 1, channel_id) + payload)
        wait_until(lambda: heard == ["through foxglove"], 10, what="the valid channel's message")
    refusals = [line for line in LINES if "/bad name" in line]
    assert len(refusals) == 1 and "invalid topic name '/bad name'" in refusals[0], LINES


def test_parameters_get_set_and_subscribe(bridge: FoxgloveBridge) -> None:
    PARAMS.set("/gain", 1.5)
    with connect(f"ws://127.0.0.1:{bridge.port}", subprotocols=["foxglove.sdk.v1"]) as ws:
        next_op(ws, "serverInfo")
        ws.send(json.dumps({"op": "getParameters", "parameterNames": ["/gain"], "id": "g"}))
        assert next_op(ws, "parameterValues")["parameters"] == [
            {"name": "/gain", "type": "float64", "value": 1.5}
        ]
        ws.send(json.dumps({"op": "subscribeParameterUpdates", "parameterNames": ["/gain"]}))
        ws.send(json.dumps({"op": "setParameters", "id": "s",
                            "parameters": [{"name": "/gain", "value": 2.5}]}))  # fmt: skip
        assert next_op(ws, "parameterValues")["parameters"][0]["value"] == 2.5
        assert PARAMS.get("/gain") == 2.5
        PARAMS.set("/gain", 3.5)  # changed by someone else: the subscriber hears it
        while (update := next_op(ws, "parameterValues"))["parameters"][0]["value"] != 3.5:
            assert update["parameters"][0]["value"] == 2.5, update


def test_bad_settings_are_one_line_errors(bridge: FoxgloveBridge) -> None:
    context = bridge.context
    with pytest.raises(
        BridgeError, match="unknown capabilities telepathy; they are: clientPublish"
    ):
        FoxgloveBridge(context, Ros1Params(ParamServer()), dialect="ros2",
                       package_index=PackageIndex(), port=0, capabilities=["telepathy"])  # fmt: skip
    with pytest.raises(BridgeError, match=f"cannot listen on 127.0.0.1:{bridge.port}"):
        FoxgloveBridge(context, Ros1Params(ParamServer()), dialect="ros2",
                       package_index=PackageIndex(), port=bridge.port, name="second")  # fmt: skip


def test_a_graph_read_in_part_or_not_at_all_closes_no_channel(
    bridge: FoxgloveBridge, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A master that does not answer in time, or a graph a bound cut short, leaves every
    channel open (with a client's subscription on it); one line says the read failed."""
    from robomodel.runtime.transport.base import Graph

    vector = get_message_type("geometry_msgs/msg/Vector3Stamped")
    node = bridge.context.create_node("gusty")
    bridge._on_bus(lambda: node.create_publisher(vector, "/gust"))
    with connect(f"ws://127.0.0.1:{bridge.port}", subprotocols=["foxglove.sdk.v1"]) as ws:
        channel = advertised(ws, "/gust")
        reads: list[Graph] = []
        bad = [Graph(unreadable="the master did not answer", complete=False)] * 3
        bad += [Graph(complete=False)] * 2  # an empty listing that says it is incomplete

        def failing_graph(timeout_s: float = 1.0) -> Graph:
            reads.append(bad[min(len(reads), len(bad) - 1)])
            return reads[-1]

        said = len(LINES)
        monkeypatch.setattr(bridge.context, "graph", failing_graph)
        wait_until(lambda: len(reads) >= len(bad) + 1, 20, what="the bridge's graph reads")
        monkeypatch.undo()
        seen: list[Any] = []
        try:
            while True:
                seen.append(ws.recv(timeout=0.2))
        except TimeoutError:
            pass
        gone = [json.loads(f) for f in seen if isinstance(f, str) and '"unadvertise"' in f]
        assert all(channel["id"] not in g["channelIds"] for g in gone)
        failures = [line for line in LINES[said:] if "reading the graph failed" in line]
        assert failures == ["foxglove_bridge: reading the graph failed: the master did not answer"]
