"""Service introspection (``configure_introspection``): a service's and a client's events on
``<service>/_service_event``, as demo_nodes_py's introspection demo turns them on, on the
in-process bus (the Zenoh bus adds the client's GID and sequence number, which the upstream
demo's run shows)."""

from __future__ import annotations

import time
from typing import Any

import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import qos_profile_system_default
from rclpy.service_introspection import ServiceIntrospectionState

from tests.timing import scaled


def add_two_ints() -> Any:
    """AddTwoInts as rclpy's classes are (rosidl's, with ``Event``), whichever flavour this
    process's imports chose (the whole suite imports rospy too, which makes them genpy's)."""
    from robomodel.clientlibs.messages import service_class

    return service_class("tutorial_interfaces/srv/AddTwoInts", "rosidl")


class Adder(Node):
    def __init__(self) -> None:
        super().__init__("adder")
        self.srv = self.create_service(add_two_ints(), "add_two_ints", self.add)

    def add(self, request: Any, response: Any) -> Any:
        response.sum = request.a + request.b
        return response


def test_the_service_and_client_events_of_one_call(rclpy_inproc: None) -> None:
    AddTwoInts = add_two_ints()
    adder = Adder()
    caller = rclpy.create_node("caller")
    client = caller.create_client(AddTwoInts, "add_two_ints")
    events: list[Any] = []
    caller.create_subscription(AddTwoInts.Event, "/add_two_ints/_service_event", events.append, 10)
    executor = SingleThreadedExecutor()
    executor.add_node(adder)
    executor.add_node(caller)

    adder.srv.configure_introspection(
        adder.get_clock(), qos_profile_system_default, ServiceIntrospectionState.CONTENTS
    )
    client.configure_introspection(
        caller.get_clock(), qos_profile_system_default, ServiceIntrospectionState.METADATA
    )
    before_ns = adder.get_clock().now().nanoseconds
    future = client.call_async(AddTwoInts.Request(a=2, b=3))
    executor.spin_until_future_complete(future, timeout_sec=scaled(10))
    assert future.result().sum == 5
    deadline = time.monotonic() + scaled(10)
    while len(events) < 4 and time.monotonic() < deadline:
        executor.spin_once(timeout_sec=0.05)

    kinds = sorted(event.info.event_type for event in events)
    assert kinds == [0, 1, 2, 3]  # sent, received, response sent, response received
    by_kind = {event.info.event_type: event for event in events}
    assert [r.a for r in by_kind[1].request] == [2] and list(by_kind[1].response) == []
    assert [r.sum for r in by_kind[2].response] == [5]  # the service's: contents
    assert list(by_kind[0].request) == [] and list(by_kind[3].response) == []  # metadata
    stamp = by_kind[1].info.stamp
    assert stamp.sec * 10**9 + stamp.nanosec >= before_ns

    adder.srv.configure_introspection(
        adder.get_clock(), qos_profile_system_default, ServiceIntrospectionState.OFF
    )
    client.configure_introspection(
        caller.get_clock(), qos_profile_system_default, ServiceIntrospectionState.OFF
    )
    assert caller.count_publishers("/add_two_ints/_service_event") == 0  # publishers gone
    events.clear()
    future = client.call_async(AddTwoInts.Request(a=1, b=1))
    executor.spin_until_future_complete(future, timeout_sec=scaled(10))
    executor.spin_once(timeout_sec=0.1)
    assert future.result().sum == 2 and events == []
