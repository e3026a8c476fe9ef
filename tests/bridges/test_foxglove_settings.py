"""foxglove_bridge's settings on the in-process bus with ROS 2 nodes' parameters, driven by a
raw ``foxglove.sdk.v1`` client: the whitelists (whole names, ignoring case, as foxglove_bridge
matches them) for services, parameters, client topics and asset URIs; parameter updates from
``/parameter_events`` (every change, not a sample of them); the ``time`` capability with
``use_sim_time``."""

from __future__ import annotations

import json
import struct
from collections.abc import Iterator
from typing import Any

import pytest
from websockets.sync.client import connect

from robomodel.bridges.foxglove_bridge import FoxgloveBridge
from robomodel.bridges.rosapi import Ros2Params
from robomodel.description.packages import PackageIndex
from robomodel.runtime import Context
from robomodel.runtime.msg import get_message_type
from robomodel.runtime.msg.cdr import serialize
from robomodel.runtime.msg.schema import get_service_type
from tests.bridges.bus_thread import spun
from tests.bridges.foxglove_ws import next_op
from tests.conftest import EXAMPLES
from tests.timing import scaled, wait_until

LINES: list[str] = []
# the graph read ten times a second: a test that waits for reads waits less
GRAPH_PERIOD_S = 0.1


@pytest.fixture(scope="module")
def bridge() -> Iterator[FoxgloveBridge]:
    with spun(Context("inproc")) as context:
        params = Ros2Params(context, lambda: sorted(context.graph(timeout_s=0.3).nodes), 2.0)
        found = FoxgloveBridge(
            context, params, dialect="ros2",
            package_index=PackageIndex(package_paths=[EXAMPLES], use_environment=False),
            port=0, log=LINES.append, use_sim_time=True,
            service_whitelist=["/ALLOWED/.*"], param_whitelist=[r"/tuned\..*"],
            client_topic_whitelist=["/said"],
            asset_uri_allowlist=[r"^PACKAGE://two_link_arm/.*\.urdf$"],
            graph_period_s=GRAPH_PERIOD_S,
        )  # fmt: skip
        try:
            yield found
        finally:
            found.stop()


def _connected(bridge: FoxgloveBridge) -> Any:
    return connect(f"ws://127.0.0.1:{bridge.port}", subprotocols=["foxglove.sdk.v1"])


def _binary(ws: Any, opcode: int) -> bytes:
    while True:
        frame = ws.recv(timeout=scaled(10))
        if isinstance(frame, bytes) and frame[0] == opcode:
            return frame  # type: ignore[no-any-return]


def test_time_capability_follows_clock(bridge: FoxgloveBridge) -> None:
    clock = get_message_type("rosgraph_msgs/msg/Clock")
    node = bridge.context.create_node("sim")
    publisher = bridge._on_bus(lambda: node.create_publisher(clock, "/clock"))
    wait_until(lambda: publisher.get_subscription_count() >= 1, 10, what="the /clock subscription")
    with _connected(bridge) as ws:
        assert "time" in next_op(ws, "serverInfo")["capabilities"]
        assert bridge.node.get_parameter("use_sim_time") is True
        stamp = clock()
        stamp.clock.sec, stamp.clock.nanosec = 42, 500_000_000
        bridge.context.executor.post(lambda: publisher.publish(stamp))
        frame = _binary(ws, 2)  # time: opcode 2, u64 nanoseconds
        assert struct.unpack_from("<Q", frame, 1)[0] == 42_500_000_000


def test_service_whitelist(bridge: FoxgloveBridge) -> None:
    trigger = get_service_type("std_srvs/srv/Trigger")
    node = bridge.context.create_node("servers")
    for name in ("/allowed/reset", "/hidden/reset"):
        bridge._on_bus(
            lambda name=name: node.create_service(trigger, name, lambda _: trigger.Response())
        )
    with _connected(bridge) as ws:
        next_op(ws, "serverInfo")
        offered: set[str] = set()
        while "/allowed/reset" not in offered:  # the graph is read every GRAPH_PERIOD_S
            offered |= {s["name"] for s in next_op(ws, "advertiseServices")["services"]}
    assert "/hidden/reset" not in offered and not any("parameter" in s for s in offered)


def test_client_topic_whitelist(bridge: FoxgloveBridge) -> None:
    string = get_message_type("std_msgs/msg/String")
    heard: list[str] = []
    node = bridge.context.create_node("listener")
    bridge._on_bus(
        lambda: node.create_subscription(string, "/said", lambda m: heard.append(m.data))
    )
    with _connected(bridge) as ws:
        next_op(ws, "serverInfo")
        channels = [
            {"id": 1, "topic": "/other", "encoding": "cdr", "schemaName": "std_msgs/msg/String",
             "schema": "string data", "schemaEncoding": "ros2msg"},
            {"id": 2, "topic": "/said", "encoding": "cdr", "schemaName": "std_msgs/msg/String",
             "schema": "string data", "schemaEncoding": "ros2msg"},
        ]  # fmt: skip
        ws.send(json.dumps({"op": "advertise", "channels": channels}))
        wait_until(lambda: any("/other" in line for line in LINES), 10, what="the refusal")
        payload = serialize(string(data="listed"))
        for channel_id in (1, 2):
            ws.send(struct.pack("<BI", 1, channel_id) + payload)
        wait_until(lambda: heard == ["listed"], 10, what="the listed channel's message")
    assert any("cannot publish on /other: not on client_topic_whitelist" in x for x in LINES)


def test_param_whitelist_and_parameter_events(bridge: FoxgloveBridge) -> None:
    tuned = bridge.context.create_node("tuned")
    secret = bridge.context.create_node("secret")
    bridge._on_bus(lambda: (tuned.declare_parameter("gain", 1.0),
                            secret.declare_parameter("key", "hunter2")))  # fmt: skip
    with _connected(bridge) as ws:
        next_op(ws, "serverInfo")
        ws.send(json.dumps({"op": "getParameters", "parameterNames": [], "id": "all"}))
        names = {p["name"] for p in next_op(ws, "parameterValues")["parameters"]}
        assert "/tuned.gain" in names and not any(n.startswith("/secret") for n in names)
        ws.send(json.dumps({"op": "setParameters", "id": "s",
                            "parameters": [{"name": "/secret.key", "value": "x"}]}))  # fmt: skip
        refused = next_op(ws, "parameterValues")
        assert refused["id"] == "s" and refused["parameters"] == []
        assert any("may not set /secret.key: not on param_whitelist" in x for x in LINES)
        assert secret.get_parameter("key") == "hunter2"

        ws.send(json.dumps({"op": "subscribeParameterUpdates",
                            "parameterNames": ["/tuned.gain", "/secret.key"]}))  # fmt: skip
        wait_until(lambda: bridge._events_subscription is not None, 10, what="the events")
        # two changes within one of the ROS 1 path's 1 s polls: both are heard, in order
        bridge._on_bus(lambda: (tuned.set_parameters({"gain": 2.0}),
                                tuned.set_parameters({"gain": 1.0}),
                                secret.set_parameters({"key": "y"})))  # fmt: skip
        values = [next_op(ws, "parameterValues")["parameters"] for _ in range(2)]
    assert values == [[{"name": "/tuned.gain", "type": "float64", "value": 2.0}],
                      [{"name": "/tuned.gain", "type": "float64", "value": 1.0}]]  # fmt: skip


def test_asset_uri_allowlist(bridge: FoxgloveBridge) -> None:
    def fetch(ws: Any, uri: str, request_id: int) -> tuple[int, bytes]:
        ws.send(json.dumps({"op": "fetchAsset", "uri": uri, "requestId": request_id}))
        frame = _binary(ws, 4)  # fetchAssetResponse: id, status, error length, error, data
        assert struct.unpack_from("<I", frame, 1)[0] == request_id
        status, error_length = struct.unpack_from("<BI", frame, 5)
        return status, frame[10 + error_length :]

    urdf = (EXAMPLES / "two_link_arm" / "urdf" / "two_link_arm.urdf").read_bytes()
    with _connected(bridge) as ws:
        next_op(ws, "serverInfo")
        assert fetch(ws, "package://two_link_arm/urdf/two_link_arm.urdf", 1) == (0, urdf)
        assert fetch(ws, "package://two_link_arm/urdf/two_link_arm.urdf.xacro", 2)[0] == 1
        assert fetch(ws, "package://two_link_arm/urdf/../urdf/two_link_arm.urdf", 3)[0] == 1
