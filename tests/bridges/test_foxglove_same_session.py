"""foxglove_bridge on Zenoh in the process of the nodes it forwards, as ``robomodel launch``
runs it beside robot_state_publisher and the simulation: a latched topic published before the
client subscribed arrives once, and each later message once, from the publishers themselves
(``robomodel.runtime.transport._zenoh_local``)."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from websockets.sync.client import connect

from robomodel.bridges.foxglove_bridge import FoxgloveBridge
from robomodel.bridges.rosapi import Ros1Params
from robomodel.description.packages import PackageIndex
from robomodel.launch.param_server import ParamServer
from robomodel.runtime import Context, latched
from robomodel.runtime.msg import Int32, String
from robomodel.runtime.msg.cdr import serialize
from tests.bridges.bus_thread import spun
from tests.bridges.foxglove_ws import next_binary, registered, subscribe
from tests.conftest import unique_domain
from tests.timing import wait_until


@pytest.fixture
def bridge() -> Iterator[FoxgloveBridge]:
    with spun(Context("zenoh", domain_id=int(unique_domain()))) as context:
        found = FoxgloveBridge(context, Ros1Params(ParamServer()), dialect="ros2",
                               package_index=PackageIndex(), port=0, graph_period_s=0.1)  # fmt: skip
        try:
            yield found
        finally:
            found.stop()


def test_latched_and_live_messages_of_the_bridges_own_process_arrive_once(
    bridge: FoxgloveBridge,
) -> None:
    node = bridge.context.create_node("robot_state_publisher")
    description = bridge._on_bus(
        lambda: node.create_publisher(String, "/robot_description", latched())
    )
    bridge._on_bus(lambda: description.publish(String("<robot name='r'/>")))
    with connect(f"ws://127.0.0.1:{bridge.port}", subprotocols=["foxglove.sdk.v1"]) as ws:
        subscribe(ws, 1, registered(ws, bridge, "/robot_description")["id"])
        frame = next_binary(ws)
        assert frame[1] == 1 and frame[13:] == serialize(String("<robot name='r'/>"))
        # made now, the topic comes in an advertisement of its own
        counter = bridge._on_bus(lambda: node.create_publisher(Int32, "/counter"))
        subscribe(ws, 2, registered(ws, bridge, "/counter")["id"])
        wait_until(lambda: counter.get_subscription_count() == 1, 10, what="the bus subscription")
        for n in range(20):
            bridge._on_bus(lambda n=n: counter.publish(Int32(n)))
        payloads = [next_binary(ws) for _ in range(20)]
        assert [(f[1], f[13:]) for f in payloads] == [(2, serialize(Int32(n))) for n in range(20)]
        # nothing twice: the next frame is a new message, not a copy through Zenoh
        bridge._on_bus(lambda: counter.publish(Int32(100)))
        assert next_binary(ws)[13:] == serialize(Int32(100))
