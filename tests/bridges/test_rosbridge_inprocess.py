"""The rosbridge server on the in-process bus, driven by a raw WebSocket client: rosbridge's
JSON mapping, a slow client's bounded queue against a 1 kHz topic, and the refusals (an
oversized frame, a flood, an invalid name), each with its one line."""

from __future__ import annotations

import base64
import json
import math
import threading
import time
from collections.abc import Iterator
from typing import Any

import pytest
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect

from robomodel.bridges import BridgeLimits
from robomodel.bridges.json_mapping import message_from_json, message_to_json
from robomodel.bridges.rosapi import Ros1Params
from robomodel.bridges.rosbridge import RosbridgeServer
from robomodel.launch.param_server import ParamServer
from robomodel.runtime import Context
from robomodel.runtime.msg import get_message_type
from tests.timing import scaled, wait_until

SEND_BUFFER = 200_000


class _Bridge:
    def __init__(self) -> None:
        self.context = Context("inproc")
        self.lines: list[str] = []
        self.params = ParamServer()
        self._stop = threading.Event()
        self._spinner = threading.Thread(
            target=lambda: self.context.spin(until=self._stop.is_set), daemon=True
        )
        self._spinner.start()
        limits = BridgeLimits(
            max_frame_bytes=100_000, max_ops_per_s=200, send_buffer_bytes=SEND_BUFFER
        )
        self.server = RosbridgeServer(
            self.context, Ros1Params(self.params), dialect="ros1", port=0, limits=limits,
            log=self.lines.append,
        )  # fmt: skip
        self.url = f"ws://127.0.0.1:{self.server.port}"

    def close(self) -> None:
        self.server.stop()
        self._stop.set()
        self.context.executor.post(lambda: None)
        self._spinner.join(timeout=5)
        self.context.shutdown()


@pytest.fixture(scope="module")
def bridge() -> Iterator[_Bridge]:
    found = _Bridge()
    try:
        yield found
    finally:
        found.close()


def _reply(ws: Any, op: str) -> dict[str, Any]:
    while True:
        message = json.loads(ws.recv(timeout=scaled(5)))
        if message["op"] == op:
            return message  # type: ignore[no-any-return]


def test_json_mapping_is_rosbridges_per_ros_version() -> None:
    image_type = get_message_type("sensor_msgs/msg/Image")
    image = image_type(height=1, width=2, encoding="mono8", step=2, data=b"\x00\xff")
    image.header.stamp.sec, image.header.stamp.nanosec = 3, 7
    ros2 = message_to_json(image, "ros2")
    assert ros2["data"] == base64.b64encode(b"\x00\xff").decode()
    assert ros2["header"]["stamp"] == {"sec": 3, "nanosec": 7}
    ros1 = message_to_json(image, "ros1")
    assert ros1["header"]["stamp"] == {"secs": 3, "nsecs": 7}
    assert message_from_json(image_type, ros1, "ros1") == image
    assert message_from_json(image_type, ros2, "ros2") == image
    listed = message_from_json(image_type, {"data": [0, 255]}, "ros2")
    assert listed.data == b"\x00\xff"  # a byte array given as numbers, as roslibjs may
    nan = message_to_json(get_message_type("std_msgs/msg/Float64")(data=math.nan), "ros2")
    assert json.dumps(nan, allow_nan=False) == '{"data": null}'


def test_publish_subscribe_and_rosapi_params_through_the_bridge(bridge: _Bridge) -> None:
    string = get_message_type("std_msgs/msg/String")
    received: list[str] = []
    node = bridge.context.create_node("listener")
    bridge.server.on_bus(
        lambda: node.create_subscription(string, "/chatter", lambda m: received.append(m.data))
    )
    with connect(bridge.url) as ws:
        ws.send(json.dumps({"op": "advertise", "topic": "/chatter", "type": "std_msgs/String"}))
        ws.send(json.dumps({"op": "publish", "topic": "/chatter", "msg": {"data": "hello"}}))
        wait_until(lambda: received == ["hello"], 5, what="the bus hears the client")
        ws.send(json.dumps({"op": "call_service", "id": "t", "service": "/rosapi/topic_type",
                            "args": {"topic": "/chatter"}}))  # fmt: skip
        assert _reply(ws, "service_response")["values"] == {"type": "std_msgs/String"}  # ROS 1
        ws.send(json.dumps({"op": "call_service", "id": "s", "service": "/rosapi/set_param",
                            "args": {"name": "/gain", "value": "[1, 2.5]"}}))  # fmt: skip
        assert _reply(ws, "service_response")["result"] is True
        assert bridge.params.get("/gain") == [1, 2.5]
        ws.send(json.dumps({"op": "call_service", "id": "g", "service": "/rosapi/get_param",
                            "args": {"name": "/gain"}}))  # fmt: skip
        assert json.loads(_reply(ws, "service_response")["values"]["value"]) == [1, 2.5]
        ws.send(json.dumps({"op": "subscribe", "topic": "/bad name", "type": "std_msgs/String"}))
        status = _reply(ws, "status")
        assert status["level"] == "error" and "invalid topic name '/bad name'" in status["msg"]


def test_throttle_rate_and_status_levels(bridge: _Bridge) -> None:
    int32 = get_message_type("std_msgs/msg/Int32")
    node = bridge.context.create_node("ticker")
    publisher = bridge.server.on_bus(lambda: node.create_publisher(int32, "/tick"))
    count = [0]

    def tick() -> None:
        count[0] += 1
        publisher.publish(int32(data=count[0]))

    with connect(bridge.url) as ws:
        ws.send(json.dumps({"op": "set_level", "level": "warning"}))
        ws.send(json.dumps({"op": "subscribe", "topic": "/tick", "type": "std_msgs/Int32",
                            "compression": "zip"}))  # fmt: skip
        assert "compression 'zip'; the compressions are: none, png" in _reply(ws, "status")["msg"]
        ws.send(json.dumps({"op": "subscribe", "topic": "/tick", "type": "std_msgs/Int32",
                            "throttle_rate": 200}))  # fmt: skip
        wait_until(lambda: publisher.get_subscription_count() == 1, 5, what="the subscription")
        timer = bridge.server.on_bus(lambda: node.create_timer(0.002, tick))
        first = _reply(ws, "publish")["msg"]["data"]
        started_s = time.monotonic()
        wait_until(lambda: count[0] >= first + 400, 30, what="400 more ticks")
        bridge.server.on_bus(timer.cancel)
        elapsed_s = time.monotonic() - started_s
        received = [first]
        while True:
            try:
                received.append(json.loads(ws.recv(timeout=0.5))["msg"]["data"])
            except TimeoutError:
                break
    # one message per 200 ms at most: the ticks between are not sent
    assert 2 <= len(received) <= elapsed_s / 0.2 + 2, (received, elapsed_s)
    assert len(received) < (count[0] - first) / 4, received


def test_a_slow_client_of_a_1khz_topic_loses_messages_not_memory(bridge: _Bridge) -> None:
    joint_state = get_message_type("sensor_msgs/msg/JointState")
    node = bridge.context.create_node("fast")
    publisher = bridge.server.on_bus(lambda: node.create_publisher(joint_state, "/joint_states"))
    # ~70 kB of JSON a message: more a second than the socket buffers hold
    msg = joint_state(name=["joint"], position=[0.123456789] * 5000)
    with connect(bridge.url, max_size=None, max_queue=1, close_timeout=1) as ws:
        ws.send(json.dumps({"op": "subscribe", "topic": "/joint_states",
                            "type": "sensor_msgs/JointState"}))  # fmt: skip
        wait_until(lambda: publisher.get_subscription_count() == 1, 5, what="the subscription")
        timer = bridge.server.on_bus(
            lambda: node.create_timer(0.001, lambda: publisher.publish(msg))
        )
        peak = [0]

        def dropped() -> bool:  # the client reads nothing meanwhile
            waiting = sum(s.outbox.waiting_bytes for s in list(bridge.server._sessions))
            peak[0] = max(peak[0], waiting)
            return bridge.server.dropped() > 20

        wait_until(dropped, 30, what="a slow client's dropped messages", interval_s=0.01)
        timer.cancel()
        assert 0 < peak[0] <= SEND_BUFFER
        first = json.loads(ws.recv(timeout=scaled(5)))
        assert first["op"] == "publish" and len(first["msg"]["position"]) == 5000


def test_oversized_frames_and_floods_are_refused_with_one_line_each(bridge: _Bridge) -> None:
    with connect(bridge.url, max_size=None) as ws:
        ws.send("x" * 200_000)
        with pytest.raises(ConnectionClosed):
            ws.recv(timeout=scaled(5))
    with connect(bridge.url) as ws, pytest.raises(ConnectionClosed):
        for _ in range(2000):
            ws.send(json.dumps({"op": "set_level", "level": "error"}))
        ws.recv(timeout=scaled(5))

    # the module's other tests log lines of their own (a slow client's drops), before or after
    # this one as the workers take them: the refusals are counted by their words
    def refusals() -> tuple[list[str], list[str]]:
        return (
            [line for line in bridge.lines if "over 100000 bytes" in line],
            [line for line in bridge.lines if "more than 200 operations a second" in line],
        )

    wait_until(lambda: all(refusals()), 5, what=lambda: f"the refusals' lines: {bridge.lines}")
    frames, floods = refusals()
    assert len(frames) == 1 and len(floods) == 1, bridge.lines
