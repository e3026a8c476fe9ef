"""The rosbridge server's ROS 2 operations beyond the core set, on the in-process bus, driven by
a raw WebSocket client: ``cbor``, ``cbor-raw`` and ``png`` compression (read back with cbor2
and Pillow, decoders the bridge does not use), fragments both ways with their bounds, the
action operations as client and as server, and ``call_service``'s ``timeout``."""

from __future__ import annotations

import base64
import io
import json
import struct
import threading
import time
from collections.abc import Iterator
from typing import Any

import cbor2
import pytest
from PIL import Image
from websockets.sync.client import connect

from robomodel.bridges import BridgeLimits
from robomodel.bridges.rosapi import Ros1Params
from robomodel.bridges.rosbridge import RosbridgeServer
from robomodel.launch.param_server import ParamServer
from robomodel.runtime import Context
from robomodel.runtime.action_client import ActionClient
from robomodel.runtime.action_server import ActionServer
from robomodel.runtime.msg import get_message_type
from robomodel.runtime.msg._resolver import resolve_action
from robomodel.runtime.msg.cdr import payload_decoder
from robomodel.runtime.msg.schema import get_service_type
from robomodel.runtime.transport.base import Deferred
from tests.timing import scaled, wait_until


class _Bridge:
    def __init__(self) -> None:
        self.context = Context("inproc")
        self._stop = threading.Event()
        self._spinner = threading.Thread(
            target=lambda: self.context.spin(until=self._stop.is_set), daemon=True
        )
        self._spinner.start()
        limits = BridgeLimits(
            max_frame_bytes=200_000, max_ops_per_s=5_000, max_fragment_bytes=50_000,
            max_fragmented_messages=2, max_fragments=100, max_png_bytes=20_000,
        )  # fmt: skip
        self.server = RosbridgeServer(
            self.context, Ros1Params(ParamServer()), dialect="ros2", port=0, limits=limits,
            log=lambda line: None,
        )  # fmt: skip
        self.url = f"ws://127.0.0.1:{self.server.port}"
        self.node = self.context.create_node("wire")

    def publisher(self, type_name: str, topic: str) -> Any:
        msg_type = get_message_type(type_name)
        return self.server.on_bus(lambda: self.node.create_publisher(msg_type, topic))

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


def gripper_command() -> Any:
    return resolve_action("control_msgs/action/GripperCommand", "control_msgs/GripperCommand")


def _next(ws: Any, op: str) -> Any:
    """The next frame of operation ``op`` (binary frames are CBOR)."""
    while True:
        frame = ws.recv(timeout=scaled(10))
        message = cbor2.loads(frame) if isinstance(frame, bytes) else json.loads(frame)
        if message["op"] == op:
            return message


def _subscribed(bridge: _Bridge, ws: Any, publisher: Any, **subscribe: Any) -> None:
    ws.send(json.dumps({"op": "subscribe", **subscribe}))
    wait_until(lambda: publisher.get_subscription_count() >= 1, 5, what="the subscription")


def _joint_state() -> Any:
    msg = get_message_type("sensor_msgs/msg/JointState")(
        name=["a", "b"], position=[1.5, -2.25], velocity=[0.0, 3.0], effort=[]
    )
    msg.header.stamp.sec, msg.header.stamp.nanosec = 12, 34
    return msg


def test_cbor_is_rosbridges_typed_arrays(bridge: _Bridge) -> None:
    states = bridge.publisher("sensor_msgs/msg/JointState", "/cbor_states")
    ints = bridge.publisher("std_msgs/msg/Int16MultiArray", "/cbor_ints")
    image = bridge.publisher("sensor_msgs/msg/Image", "/cbor_image")
    with connect(bridge.url) as ws:
        for topic, publisher in (("/cbor_states", states), ("/cbor_ints", ints),
                                 ("/cbor_image", image)):  # fmt: skip
            _subscribed(bridge, ws, publisher, topic=topic, compression="cbor")
        bridge.context.executor.post(lambda: states.publish(_joint_state()))
        got = _next(ws, "publish")
        ints_type = get_message_type("std_msgs/msg/Int16MultiArray")
        bridge.context.executor.post(lambda: ints.publish(ints_type(data=[-3, 7, 300])))
        got_ints = _next(ws, "publish")
        image_type = get_message_type("sensor_msgs/msg/Image")
        frame = image_type(height=1, width=3, encoding="mono8", step=3, data=b"\x01\x02\xff")
        bridge.context.executor.post(lambda: image.publish(frame))
        got_image = _next(ws, "publish")
    assert got["topic"] == "/cbor_states"
    msg = got["msg"]
    assert msg["header"]["stamp"] == {"sec": 12, "nanosec": 34}
    assert msg["name"] == ["a", "b"]
    assert msg["position"] == cbor2.CBORTag(86, struct.pack("<2d", 1.5, -2.25))
    assert msg["effort"] == cbor2.CBORTag(86, b"")
    assert got_ints["msg"]["data"] == cbor2.CBORTag(77, struct.pack("<3h", -3, 7, 300))
    assert got_image["msg"]["data"] == b"\x01\x02\xff"  # uint8[] as a byte string


def test_cbor_raw_carries_the_bus_serialisation(bridge: _Bridge) -> None:
    states = bridge.publisher("sensor_msgs/msg/JointState", "/raw_states")
    with connect(bridge.url) as ws:
        _subscribed(bridge, ws, states, topic="/raw_states", compression="cbor-raw")
        bridge.context.executor.post(lambda: states.publish(_joint_state()))
        got = _next(ws, "publish")
    assert got["topic"] == "/raw_states"
    assert set(got["msg"]) == {"secs", "nsecs", "bytes"} and got["msg"]["secs"] > 0
    decode = payload_decoder(get_message_type("sensor_msgs/msg/JointState"))
    assert decode(got["msg"]["bytes"]) == _joint_state()


def test_png_is_the_json_as_pixels_and_large_messages_go_as_json(bridge: _Bridge) -> None:
    strings = bridge.publisher("std_msgs/msg/String", "/png_text")
    string = get_message_type("std_msgs/msg/String")
    with connect(bridge.url, max_size=None) as ws:
        ws.send(json.dumps({"op": "set_level", "level": "warning"}))
        _subscribed(bridge, ws, strings, topic="/png_text", compression="png")
        bridge.context.executor.post(lambda: strings.publish(string(data="héllo png")))
        got = _next(ws, "png")
        image = Image.open(io.BytesIO(base64.b64decode(got["data"])))
        assert image.mode == "RGB" and image.format == "PNG"
        text = image.tobytes().decode("utf-8").replace("\n", "")
        assert json.loads(text) == {"op": "publish", "topic": "/png_text",
                                    "msg": {"data": "héllo png"}}  # fmt: skip
        width = image.size[0]
        assert width == int((len(text.encode()) / 3) ** 0.5)  # rosbridge's floor(sqrt(n / 3))
        big = "x" * 30_000  # over the bridge's 20,000 bytes of png
        bridge.context.executor.post(lambda: strings.publish(string(data=big)))
        assert "over png's 20000; such messages go as JSON" in _next(ws, "status")["msg"]
        assert _next(ws, "publish")["msg"]["data"] == big


def test_fragment_size_fragments_what_the_client_is_sent(bridge: _Bridge) -> None:
    strings = bridge.publisher("std_msgs/msg/String", "/long_text")
    string = get_message_type("std_msgs/msg/String")
    text = "".join(chr(65 + i % 26) for i in range(1000))
    with connect(bridge.url) as ws:
        ws.send(json.dumps({"op": "subscribe", "topic": "/too_small", "type": "std_msgs/String",
                            "fragment_size": 10}))  # fmt: skip
        assert "fragment_size must be a whole number >= 100, got 10" in _next(ws, "status")["msg"]
        _subscribed(bridge, ws, strings, topic="/long_text", fragment_size=300)
        bridge.context.executor.post(lambda: strings.publish(string(data=text)))
        fragments = [_next(ws, "fragment")]
        while len(fragments) < fragments[0]["total"]:
            fragments.append(_next(ws, "fragment"))
    assert [f["num"] for f in fragments] == list(range(len(fragments)))
    assert all(len(f["data"]) <= 300 for f in fragments) and len(fragments) == 4
    assert len({f["id"] for f in fragments}) == 1 and fragments[0]["id"]  # roslibjs needs an id
    joined = json.loads("".join(f["data"] for f in fragments))
    assert joined == {"op": "publish", "topic": "/long_text", "msg": {"data": text}}


def _fragments(message: dict[str, Any], size: int, message_id: str) -> list[str]:
    text = json.dumps(message)
    parts = [text[i : i + size] for i in range(0, len(text), size)]
    return [json.dumps({"op": "fragment", "id": message_id, "num": n, "total": len(parts),
                        "data": part}) for n, part in enumerate(parts)]  # fmt: skip


def test_a_clients_fragments_are_joined_within_bounds(bridge: _Bridge) -> None:
    string = get_message_type("std_msgs/msg/String")
    heard: list[str] = []
    node = bridge.context.create_node("fragment_listener")
    bridge.server.on_bus(
        lambda: node.create_subscription(string, "/joined", lambda m: heard.append(m.data))
    )
    publish = {"op": "publish", "topic": "/joined", "type": "std_msgs/msg/String",
               "msg": {"data": "joined " * 40}}  # fmt: skip
    with connect(bridge.url) as ws:
        ws.send(json.dumps({"op": "advertise", "topic": "/joined", "type": "std_msgs/String"}))
        parts = _fragments(publish, 50, "m1")
        for part in reversed(parts):  # any order
            ws.send(part)
        wait_until(lambda: heard == ["joined " * 40], 5, what="the joined message on the bus")

        too_many = json.dumps({"op": "fragment", "id": "m2", "num": 0, "total": 101, "data": "x"})
        ws.send(too_many)
        assert "'total' 101; a message has 1 to 100 fragments" in _next(ws, "status")["msg"]
        for message_id in ("a", "b", "c"):  # two messages may be joined at once
            ws.send(json.dumps({"op": "fragment", "id": message_id, "num": 0, "total": 3,
                                "data": "{"}))  # fmt: skip
        assert "2 messages are being joined already" in _next(ws, "status")["msg"]
        big = "y" * 40_000
        ws.send(json.dumps({"op": "fragment", "id": "a", "num": 1, "total": 3, "data": big}))
        ws.send(json.dumps({"op": "fragment", "id": "b", "num": 1, "total": 3, "data": big}))
        status = _next(ws, "status")["msg"]
        assert "would pass 50000 bytes; the message is dropped" in status
        held = [s.reassembly.held_bytes for s in list(bridge.server._sessions)]
        assert 40_001 in held  # "a" is kept, "b" went
        inner = _fragments({"op": "set_level", "level": "info"}, 10, "inner")
        for part in _fragments({"op": "fragment", "id": "x", "num": 0, "total": 1,
                                "data": inner[0]}, 60, "outer"):  # fmt: skip
            ws.send(part)
        assert "a message in fragments may not be a fragment" in _next(ws, "status")["msg"]


class _Goal:
    """A GripperCommand goal that runs until told, with feedback."""

    def __init__(self, position: float) -> None:
        self.position = position
        self.state = 2  # executing
        self.action = gripper_command()

    def status(self) -> int:
        return self.state

    def result(self) -> Any:
        return self.action.Result(position=self.position, reached_goal=self.state == 4)

    def feedback(self) -> Any:
        return self.action.Feedback(position=self.position / 2)

    def cancel(self) -> bool:
        self.state = 5
        return True


def test_send_action_goal_gets_feedback_result_and_cancels(bridge: _Bridge) -> None:
    goals: list[_Goal] = []

    def accept(goal: Any) -> _Goal:
        goals.append(_Goal(goal.command.position))
        return goals[-1]

    server = bridge.server.on_bus(
        lambda: ActionServer(bridge.node, gripper_command(), "/gripper", accept)
    )
    try:
        with connect(bridge.url) as ws:
            ws.send(json.dumps({"op": "send_action_goal", "id": "g1", "action": "/gripper",
                                "action_type": "control_msgs/action/GripperCommand",
                                "args": {"command": {"position": 0.8}},
                                "feedback": True}))  # fmt: skip
            feedback = _next(ws, "action_feedback")
            assert feedback["id"] == "g1" and feedback["values"]["position"] == 0.4
            goals[0].state = 4  # succeeded
            result = _next(ws, "action_result")
            assert result["id"] == "g1" and result["status"] == 4 and result["result"] is True
            assert result["values"]["position"] == 0.8 and result["values"]["reached_goal"]

            ws.send(json.dumps({"op": "send_action_goal", "id": "g2", "action": "/gripper",
                                "action_type": "control_msgs/GripperCommand",
                                "args": [{"position": 0.1, "max_effort": 1.0}]}))  # fmt: skip
            wait_until(lambda: len(goals) == 2, 10, what="the second goal")
            ws.send(json.dumps({"op": "cancel_action_goal", "id": "g2", "action": "/gripper"}))
            cancelled = _next(ws, "action_result")
            assert cancelled["id"] == "g2" and cancelled["status"] == 5

            ws.send(json.dumps({"op": "send_action_goal", "id": "g3", "action": "/nobody",
                                "action_type": "control_msgs/action/GripperCommand"}))  # fmt: skip
            failed = _next(ws, "action_result")
            assert failed["result"] is False and failed["status"] == 0
            assert "/nobody/_action/send_goal" in failed["values"]
    finally:
        bridge.server.on_bus(server.destroy)


def test_advertise_action_serves_goals_of_the_bus(bridge: _Bridge) -> None:
    action = gripper_command()
    client = ActionClient(bridge.context, action, "/served_gripper")
    outcome: dict[str, Any] = {}
    feedback: list[float] = []
    with connect(bridge.url) as ws:
        ws.send(json.dumps({"op": "advertise_action", "action": "/served_gripper",
                            "type": "control_msgs/action/GripperCommand"}))  # fmt: skip
        feedback_type = action.FeedbackMessage
        bridge.server.on_bus(
            lambda: bridge.node.create_subscription(
                feedback_type, "/served_gripper/_action/feedback",
                lambda m: feedback.append(m.feedback.position),
            )
        )  # fmt: skip

        def run() -> None:
            command = get_message_type("control_msgs/msg/GripperCommand")(position=0.3)
            goal_id, accepted = client.send_goal(action.Goal(command=command))
            outcome["accepted"] = accepted
            outcome["result"] = client.get_result(goal_id, timeout_s=scaled(20))

        wait_until(
            lambda: "/served_gripper/_action/send_goal"
            in bridge.context.graph(timeout_s=0.3).services,
            10, what="the advertised action's services",
        )  # fmt: skip
        caller = threading.Thread(target=run, daemon=True)
        caller.start()
        goal = _next(ws, "send_action_goal")
        assert goal["action"] == "/served_gripper"
        assert goal["args"]["command"]["position"] == 0.3
        ws.send(json.dumps({"op": "action_feedback", "id": goal["id"], "action": "/served_gripper",
                            "values": {"position": 0.15}}))  # fmt: skip
        wait_until(lambda: feedback == [0.15], 10, what="the client's feedback on the bus")
        ws.send(json.dumps({"op": "action_result", "id": goal["id"], "action": "/served_gripper",
                            "values": {"position": 0.3, "reached_goal": True}, "status": 4,
                            "result": True}))  # fmt: skip
        caller.join(scaled(20))
        ws.send(json.dumps({"op": "action_result", "id": "nobody", "action": "/served_gripper",
                            "status": 4, "result": True}))  # fmt: skip
        assert "no goal with id 'nobody' runs" in _next(ws, "status")["msg"]
    assert outcome["accepted"] is True
    status, result = outcome["result"]
    assert status == 4 and result.position == 0.3 and result.reached_goal is True


def test_call_service_timeout(bridge: _Bridge) -> None:
    trigger = get_service_type("std_srvs/srv/Trigger")
    waiting: list[Deferred] = []

    def never(_: Any) -> Deferred:
        waiting.append(Deferred())
        return waiting[-1]

    server = bridge.server.on_bus(lambda: bridge.node.create_service(trigger, "/slow", never))
    try:
        with connect(bridge.url) as ws:
            started_s = time.monotonic()
            ws.send(json.dumps({"op": "call_service", "id": "t1", "service": "/slow",
                                "type": "std_srvs/srv/Trigger", "timeout": 0.3}))  # fmt: skip
            reply = _next(ws, "service_response")
            assert reply["id"] == "t1" and reply["result"] is False and waiting
            assert time.monotonic() - started_s < 9.0  # not the 10 s of a call without one
            ws.send(json.dumps({"op": "call_service", "id": "t2", "service": "/slow",
                                "type": "std_srvs/srv/Trigger", "timeout": "soon"}))  # fmt: skip
            assert "'timeout' must be a number of seconds, got 'soon'" in _next(ws, "status")["msg"]
    finally:
        bridge.server.on_bus(server.destroy)
