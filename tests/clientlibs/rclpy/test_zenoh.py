"""rclpy nodes on robomodel's Zenoh bus (rmw_zenoh's wire), in one rclpy context for the
module: topics, a service and an action between the tutorial-style nodes of
test_tutorial_nodes.py; and a tutorial talker run as a script, heard by zenoh-ros2-sdk (an
independent rmw_zenoh implementation) and by a robomodel node."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import rclpy
from rclpy.action import ActionClient
from rclpy.executors import MultiThreadedExecutor

from tests.clientlibs.rclpy.test_tutorial_nodes import (
    AddTwoIntsClient,
    AddTwoIntsServer,
    FibonacciActionServer,
    MinimalPublisher,
    MinimalSubscriber,
    ParameterNode,
)
from tests.conftest import ROBOMODEL, ROOT, end_process, unique_domain
from tests.timing import scale, scaled

TALKER = Path(__file__).with_name("nodes") / "publisher_member_function.py"
SDK_AGENT = ROOT / "tests/ros2wire/sdk_agent.py"


@pytest.fixture(scope="module")
def zenoh_rclpy(tutorial_interfaces: Path) -> Iterator[MultiThreadedExecutor]:
    """``rclpy.init()`` on the Zenoh bus (a domain of the module's own) for the whole module,
    and a multi-threaded executor to spin its nodes."""
    rclpy.init(args=["test"], domain_id=int(unique_domain()))
    executor = MultiThreadedExecutor(num_threads=4)
    yield executor
    executor.shutdown()
    rclpy.try_shutdown()


def _spin_until(executor: Any, condition: Any, what: str) -> None:
    deadline = time.monotonic() + scaled(30)
    while not condition():
        assert time.monotonic() < deadline, f"timed out waiting for {what}"
        executor.spin_once(timeout_sec=0.05)


def test_talker_and_listener(zenoh_rclpy: MultiThreadedExecutor) -> None:
    subscriber = MinimalSubscriber()
    publisher = MinimalPublisher()
    zenoh_rclpy.add_node(subscriber)  # an executor runs only its own nodes' callbacks
    zenoh_rclpy.add_node(publisher)
    _spin_until(zenoh_rclpy, lambda: len(subscriber.heard) >= 5, "five messages")
    numbers = [int(m.data.rsplit(" ", 1)[1]) for m in subscriber.heard]
    assert numbers == list(range(numbers[0], numbers[0] + len(numbers)))  # in order, none lost
    assert dict(publisher.get_topic_names_and_types())["/topic"] == ["std_msgs/msg/String"]
    assert publisher.count_subscribers("topic") == 1
    assert {"minimal_publisher", "minimal_subscriber"} <= set(publisher.get_node_names())
    publisher.destroy_node()
    subscriber.destroy_node()


def test_add_two_ints(zenoh_rclpy: MultiThreadedExecutor) -> None:
    server = AddTwoIntsServer()
    client = AddTwoIntsClient()  # waits for the service in the graph
    zenoh_rclpy.add_node(server)
    zenoh_rclpy.add_node(client)
    future = client.send_request(20, 22)
    zenoh_rclpy.spin_until_future_complete(future, timeout_sec=scaled(20))
    assert future.result().sum == 42
    assert ("/add_two_ints", ["tutorial_interfaces/srv/AddTwoInts"]) in (
        client.get_service_names_and_types()
    )
    client.destroy_node()
    server.destroy_node()


def test_fibonacci_with_feedback_and_cancel(zenoh_rclpy: MultiThreadedExecutor) -> None:
    from action_msgs.msg import GoalStatus
    from tutorial_interfaces.action import Fibonacci

    server = FibonacciActionServer()
    node = rclpy.create_node("fibonacci_action_client")
    client = ActionClient(node, Fibonacci, "fibonacci")
    zenoh_rclpy.add_node(server)
    zenoh_rclpy.add_node(node)
    assert client.wait_for_server(timeout_sec=scaled(20))
    feedback: list[list[int]] = []
    sent = client.send_goal_async(
        Fibonacci.Goal(order=5), lambda m: feedback.append(list(m.feedback.partial_sequence))
    )
    zenoh_rclpy.spin_until_future_complete(sent, timeout_sec=scaled(20))
    result = sent.result().get_result_async()
    zenoh_rclpy.spin_until_future_complete(result, timeout_sec=scaled(20))
    assert result.result().status == GoalStatus.STATUS_SUCCEEDED
    assert list(result.result().result.sequence) == [0, 1, 1, 2, 3, 5]
    _spin_until(zenoh_rclpy, lambda: len(feedback) == 4, "the feedback")
    assert feedback[-1] == [0, 1, 1, 2, 3, 5]
    endless = client.send_goal_async(Fibonacci.Goal(order=1_000_000))
    zenoh_rclpy.spin_until_future_complete(endless, timeout_sec=scaled(20))
    canceling = endless.result().cancel_goal_async()
    zenoh_rclpy.spin_until_future_complete(canceling, timeout_sec=scaled(20))
    assert len(canceling.result().goals_canceling) == 1
    ended = endless.result().get_result_async()
    zenoh_rclpy.spin_until_future_complete(ended, timeout_sec=scaled(20))
    assert ended.result().status == GoalStatus.STATUS_CANCELED
    node.destroy_node()
    server.destroy_node()


def test_robomodel_param_reaches_the_node_s_parameters(zenoh_rclpy: MultiThreadedExecutor) -> None:
    node = ParameterNode()
    zenoh_rclpy.add_node(node)
    domain = str(zenoh_rclpy.context.get_domain_id())

    def param(*args: str) -> str:
        proc = subprocess.Popen([*ROBOMODEL, "param", *args, "--domain-id", domain],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)  # fmt: skip
        _spin_until(zenoh_rclpy, lambda: proc.poll() is not None, f"robomodel param {args[0]}")
        out, err = proc.communicate()
        assert proc.returncode == 0, err
        return out

    assert param("get", "/minimal_param_node", "my_parameter") == "String value is: world\n"
    assert "Set parameter successful" in param("set", "/minimal_param_node", "speed", "3.5")
    assert node.get_parameter("speed").value == 3.5
    assert node.seen[-1] == [("speed", 3.5)]  # the node's callback was asked
    node.destroy_node()


@pytest.fixture(scope="module")
def talker_script(zenoh_rclpy: MultiThreadedExecutor) -> Iterator[str]:
    """The tutorial talker run as ``python3 publisher_member_function.py`` in the module's
    domain, with a namespace given by ``--ros-args``; yields the domain."""
    domain = str(zenoh_rclpy.context.get_domain_id())
    env = {**os.environ, "ROS_DOMAIN_ID": domain}
    env.pop("ROBOMODEL_RCLPY_BUS", None)
    proc = subprocess.Popen(
        [sys.executable, str(TALKER), "--ros-args", "-r", "__ns:=/lesson"],
        env=env, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    assert proc.stderr is not None
    line = proc.stderr.readline()
    assert "[INFO] [" in line and '[lesson.minimal_publisher]: Publishing: "Hello World: 0"' in line
    yield domain
    # Ctrl-C: rclpy's handler stops the context, KeyboardInterrupt reaches the tutorial's
    # except clause: a prompt, clean exit that says nothing more than the talker's lines
    assert end_process(proc, timeout_s=5.0) == 0
    rest = proc.stderr.read().splitlines()
    assert all("]: Publishing: " in line for line in rest), rest[-5:]


def test_a_robomodel_node_hears_the_talker_script(
    zenoh_rclpy: MultiThreadedExecutor, talker_script: str
) -> None:
    from robomodel.runtime.msg import String

    node = rclpy.create_node("robomodel_listener")
    heard: list[Any] = []
    node.robomodel_node.create_subscription(String, "/lesson/topic", heard.append, 10)
    _spin_until(zenoh_rclpy, lambda: len(heard) >= 2, "the talker script's messages")
    assert heard[0].data.startswith("Hello World: ")
    assert ("minimal_publisher", "/lesson") in node.get_node_names_and_namespaces()
    node.destroy_node()


def test_zenoh_ros2_sdk_hears_the_talker_script(
    talker_script: str, tmp_path_factory: pytest.TempPathFactory
) -> None:
    from tests.ros2wire.msgtext import write_definitions
    from tests.ros2wire.test_sdk_wire import _sdk_python

    definitions = write_definitions(tmp_path_factory.mktemp("msgs"), ["std_msgs/msg/String"])
    proc = subprocess.run(
        [_sdk_python(), str(SDK_AGENT), "--messages", str(definitions), "--domain", talker_script,
         "subscribe", "/lesson/topic", "std_msgs/msg/String", str(scaled(20)), "3"],
        capture_output=True, text=True, timeout=scaled(60), cwd=definitions,
        env={**os.environ, "ROBOMODEL_TEST_TIMEOUT_SCALE": str(scale())},
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr[-2000:]
    heard = [json.loads(line) for line in proc.stdout.splitlines() if line.startswith("{")]
    assert len(heard) == 3
    numbers = [int(m["data"].rsplit(" ", 1)[1]) for m in heard]
    assert numbers == list(range(numbers[0], numbers[0] + 3))


def test_a_raw_subscription_hears_the_serialized_message(
    zenoh_rclpy: MultiThreadedExecutor,
) -> None:
    """demo_nodes_py's listener_serialized: ``raw=True`` hands over the CDR bytes (with their
    encapsulation header) as rmw serialized them."""
    from std_msgs.msg import String

    from robomodel.runtime.msg.cdr import deserialize

    listener = rclpy.create_node("serialized_subscriber")
    heard: list[Any] = []
    subscription = listener.create_subscription(String, "raw_chatter", heard.append, 10, raw=True)
    talker = rclpy.create_node("raw_talker")
    publisher = talker.create_publisher(String, "raw_chatter", 10)
    zenoh_rclpy.add_node(listener)
    zenoh_rclpy.add_node(talker)
    deadline = time.monotonic() + scaled(30)
    while not heard:
        assert time.monotonic() < deadline, "timed out waiting for a serialized message"
        publisher.publish(String(data="Hello World: raw"))
        zenoh_rclpy.spin_once(timeout_sec=0.05)
    assert isinstance(heard[0], bytes) and heard[0][:2] == b"\x00\x01"  # CDR, little endian
    assert deserialize(heard[0], String).data == "Hello World: raw"
    assert subscription.raw and listener.count_publishers("raw_chatter") == 1
    listener.destroy_node()
    talker.destroy_node()
