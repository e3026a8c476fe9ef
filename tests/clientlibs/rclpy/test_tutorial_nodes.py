"""rclpy nodes written as the ROS 2 tutorials write them (a minimal publisher and subscriber
class, the add_two_ints service and client, the fibonacci action with feedback and cancel,
parameters with a callback), on robomodel's in-process bus: the face's logic without Zenoh.
tests/clientlibs/rclpy/test_zenoh.py runs the same kinds of nodes over the Zenoh bus."""

from __future__ import annotations

import threading
import time
from pathlib import Path
from typing import Any

import pytest
import rclpy
from rclpy.action import ActionClient, ActionServer, CancelResponse, GoalResponse
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup, ReentrantCallbackGroup
from rclpy.executors import MultiThreadedExecutor, SingleThreadedExecutor
from rclpy.node import Node

from tests.timing import scaled, wait_until


class MinimalPublisher(Node):
    def __init__(self) -> None:
        super().__init__("minimal_publisher")
        from std_msgs.msg import String

        self.String = String
        self.publisher_ = self.create_publisher(String, "topic", 10)
        self.timer = self.create_timer(0.01, self.timer_callback)
        self.i = 0

    def timer_callback(self) -> None:
        msg = self.String()
        msg.data = f"Hello World: {self.i}"
        self.publisher_.publish(msg)
        self.get_logger().info(f'Publishing: "{msg.data}"')
        self.i += 1


class MinimalSubscriber(Node):
    def __init__(self) -> None:
        super().__init__("minimal_subscriber")
        from std_msgs.msg import String

        self.heard: list[Any] = []
        self.subscription = self.create_subscription(String, "topic", self.listener_callback, 10)

    def listener_callback(self, msg: Any) -> None:
        self.heard.append(msg)


def test_minimal_publisher_and_subscriber(
    rclpy_inproc: None, capfd: pytest.CaptureFixture[str]
) -> None:
    from std_msgs.msg import String

    publisher = MinimalPublisher()
    subscriber = MinimalSubscriber()
    executor = SingleThreadedExecutor()
    executor.add_node(publisher)
    executor.add_node(subscriber)
    deadline = time.monotonic() + scaled(10)
    while len(subscriber.heard) < 3 and time.monotonic() < deadline:
        executor.spin_once(timeout_sec=0.1)
    assert [m.data for m in subscriber.heard[:3]] == [f"Hello World: {i}" for i in range(3)]
    assert all(type(m) is String for m in subscriber.heard)  # the class the user passed
    err = capfd.readouterr().err
    assert "[INFO] [" in err and '] [minimal_publisher]: Publishing: "Hello World: 0"' in err
    assert publisher.count_subscribers("topic") == 1
    assert subscriber.count_publishers("/topic") == 1
    assert ("/topic", ["std_msgs/msg/String"]) in publisher.get_topic_names_and_types()
    assert {"minimal_publisher", "minimal_subscriber"} <= set(publisher.get_node_names())
    [info] = subscriber.get_publishers_info_by_topic("topic")
    assert (info.node_name, info.node_namespace, info.topic_type) == (
        "minimal_publisher", "/", "std_msgs/msg/String"
    )  # fmt: skip
    assert info.qos_profile.depth == 10 and info.endpoint_type.name == "PUBLISHER"
    [info] = publisher.get_subscriptions_info_by_topic("/topic")
    assert info.node_name == "minimal_subscriber"
    publisher.destroy_node()
    subscriber.destroy_node()


def test_sensor_data_qos_reaches_the_bus(rclpy_inproc: None) -> None:
    from rclpy.qos import QoSProfile, ReliabilityPolicy, qos_profile_sensor_data
    from sensor_msgs.msg import LaserScan

    from robomodel.runtime.qos import Durability, Reliability

    node = rclpy.create_node("scanner")
    scans: list[Any] = []
    subscription = node.create_subscription(
        LaserScan, "scan", scans.append, qos_profile_sensor_data
    )
    assert subscription.robomodel_subscription.qos.reliability == Reliability.BEST_EFFORT
    assert subscription.robomodel_subscription.qos.depth == 5
    latched = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE, durability=1)
    publisher = node.create_publisher(LaserScan, "scan", latched)
    assert publisher.robomodel_publisher.qos.durability == Durability.TRANSIENT_LOCAL
    publisher.publish(LaserScan(range_max=30.0))
    rclpy.spin_once(node, timeout_sec=scaled(5))
    assert [s.range_max for s in scans] == [30.0]
    assert node.destroy_subscription(subscription) and not node.destroy_subscription(subscription)
    publisher.publish(LaserScan(range_max=1.0))
    rclpy.spin_once(node, timeout_sec=0.05)
    assert len(scans) == 1  # a destroyed subscription hears no more


def test_publish_refuses_another_type(rclpy_inproc: None) -> None:
    from std_msgs.msg import Int32, String

    node = rclpy.create_node("typed")
    publisher = node.create_publisher(String, "chatter", 10)
    with pytest.raises(TypeError, match="std_msgs/msg/String"):
        publisher.publish(Int32(data=1))


class AddTwoIntsServer(Node):
    def __init__(self) -> None:
        super().__init__("minimal_service")
        from tutorial_interfaces.srv import AddTwoInts

        self.srv = self.create_service(AddTwoInts, "add_two_ints", self.add_two_ints_callback)

    def add_two_ints_callback(self, request: Any, response: Any) -> Any:
        response.sum = request.a + request.b
        self.get_logger().info(f"Incoming request\na: {request.a} b: {request.b}")
        return response


class AddTwoIntsClient(Node):
    def __init__(self) -> None:
        super().__init__("minimal_client_async")
        from tutorial_interfaces.srv import AddTwoInts

        self.cli = self.create_client(AddTwoInts, "add_two_ints")
        while not self.cli.wait_for_service(timeout_sec=1.0):
            self.get_logger().info("service not available, waiting again...")
        self.req = AddTwoInts.Request()

    def send_request(self, a: int, b: int) -> Any:
        self.req.a = a
        self.req.b = b
        return self.cli.call_async(self.req)


def test_add_two_ints_service_and_client(rclpy_inproc: None) -> None:
    server = AddTwoIntsServer()
    client = AddTwoIntsClient()
    executor = SingleThreadedExecutor()
    executor.add_node(server)
    future = client.send_request(41, 1)
    executor.spin_until_future_complete(future, timeout_sec=scaled(10))
    assert future.done() and future.result().sum == 42
    # the synchronous call, from a thread while the executor spins (rclpy's pattern)
    spinner = threading.Thread(target=executor.spin, daemon=True)
    spinner.start()
    from tutorial_interfaces.srv import AddTwoInts

    assert client.cli.call(AddTwoInts.Request(a=-5, b=2), timeout_sec=scaled(10)).sum == -3
    executor.shutdown()
    spinner.join(scaled(10))
    assert not spinner.is_alive()


def test_a_client_without_a_server_waits_and_says_so(rclpy_inproc: None) -> None:
    from tutorial_interfaces.srv import AddTwoInts

    node = rclpy.create_node("lonely")
    client = node.create_client(AddTwoInts, "nobody_serves_this")
    start = time.monotonic()
    assert client.wait_for_service(timeout_sec=0.2) is False
    assert time.monotonic() - start >= 0.2
    assert client.service_is_ready() is False


class FibonacciActionServer(Node):
    def __init__(self) -> None:
        super().__init__("fibonacci_action_server")
        from tutorial_interfaces.action import Fibonacci

        self.Fibonacci = Fibonacci
        self.goals: list[int] = []
        self._action_server = ActionServer(
            self,
            Fibonacci,
            "fibonacci",
            execute_callback=self.execute_callback,
            callback_group=ReentrantCallbackGroup(),
            goal_callback=self.goal_callback,
            cancel_callback=self.cancel_callback,
        )

    def goal_callback(self, goal_request: Any) -> GoalResponse:
        self.goals.append(goal_request.order)
        return GoalResponse.REJECT if goal_request.order < 0 else GoalResponse.ACCEPT

    def cancel_callback(self, goal_handle: Any) -> CancelResponse:
        return CancelResponse.ACCEPT

    def execute_callback(self, goal_handle: Any) -> Any:
        feedback_msg = self.Fibonacci.Feedback()
        feedback_msg.partial_sequence = [0, 1]
        for i in range(1, goal_handle.request.order):
            if goal_handle.is_cancel_requested:
                goal_handle.canceled()
                return self.Fibonacci.Result()
            feedback_msg.partial_sequence = [
                *feedback_msg.partial_sequence,
                feedback_msg.partial_sequence[i] + feedback_msg.partial_sequence[i - 1],
            ]
            goal_handle.publish_feedback(feedback_msg)
            time.sleep(0.01)
        goal_handle.succeed()
        result = self.Fibonacci.Result()
        result.sequence = feedback_msg.partial_sequence
        return result


def _spin_until(executor: Any, condition: Any, what: str) -> None:
    deadline = time.monotonic() + scaled(20)
    while not condition():
        assert time.monotonic() < deadline, f"timed out waiting for {what}"
        executor.spin_once(timeout_sec=0.05)


def test_fibonacci_action_with_feedback(rclpy_inproc: None) -> None:
    from action_msgs.msg import GoalStatus
    from tutorial_interfaces.action import Fibonacci

    server = FibonacciActionServer()
    client_node = rclpy.create_node("fibonacci_action_client")
    client = ActionClient(client_node, Fibonacci, "fibonacci")
    assert client.wait_for_server(timeout_sec=scaled(5))
    executor = MultiThreadedExecutor(num_threads=4)
    executor.add_node(server)
    executor.add_node(client_node)
    feedback: list[list[int]] = []
    goal = Fibonacci.Goal()
    goal.order = 8
    sent = client.send_goal_async(
        goal, feedback_callback=lambda m: feedback.append(list(m.feedback.partial_sequence))
    )
    executor.spin_until_future_complete(sent, timeout_sec=scaled(10))
    handle = sent.result()
    assert handle.accepted
    result = handle.get_result_async()
    executor.spin_until_future_complete(result, timeout_sec=scaled(20))
    assert result.result().status == GoalStatus.STATUS_SUCCEEDED
    assert list(result.result().result.sequence) == [0, 1, 1, 2, 3, 5, 8, 13, 21]
    _spin_until(executor, lambda: len(feedback) >= 7, "the feedback")
    assert feedback[0] == [0, 1, 1] and feedback[-1] == [0, 1, 1, 2, 3, 5, 8, 13, 21]
    assert handle.status == GoalStatus.STATUS_SUCCEEDED
    # a goal the goal callback rejects
    rejected = client.send_goal_async(Fibonacci.Goal(order=-1))
    executor.spin_until_future_complete(rejected, timeout_sec=scaled(10))
    assert rejected.result().accepted is False
    assert server.goals == [8, -1]
    executor.shutdown()


def test_fibonacci_action_canceled(rclpy_inproc: None) -> None:
    from action_msgs.msg import GoalStatus
    from tutorial_interfaces.action import Fibonacci

    server = FibonacciActionServer()
    client_node = rclpy.create_node("fibonacci_cancel_client")
    client = ActionClient(client_node, Fibonacci, "fibonacci")
    executor = MultiThreadedExecutor(num_threads=4)
    executor.add_node(server)
    executor.add_node(client_node)
    feedback: list[Any] = []
    sent = client.send_goal_async(Fibonacci.Goal(order=100_000), feedback_callback=feedback.append)
    executor.spin_until_future_complete(sent, timeout_sec=scaled(10))
    handle = sent.result()
    _spin_until(executor, lambda: len(feedback) >= 2, "feedback before the cancel")
    canceling = handle.cancel_goal_async()
    executor.spin_until_future_complete(canceling, timeout_sec=scaled(10))
    assert len(canceling.result().goals_canceling) == 1
    result = handle.get_result_async()
    executor.spin_until_future_complete(result, timeout_sec=scaled(20))
    assert result.result().status == GoalStatus.STATUS_CANCELED
    executor.shutdown()


def test_a_goal_whose_state_is_not_set_is_aborted(rclpy_inproc: None) -> None:
    from action_msgs.msg import GoalStatus
    from tutorial_interfaces.action import Fibonacci

    node = rclpy.create_node("careless_server")
    ActionServer(node, Fibonacci, "careless", lambda handle: Fibonacci.Result(sequence=[7]))
    client = ActionClient(node, Fibonacci, "careless")
    executor = SingleThreadedExecutor()
    sent = client.send_goal_async(Fibonacci.Goal(order=1))
    executor.spin_until_future_complete(sent, timeout_sec=scaled(10))
    result = sent.result().get_result_async()
    executor.spin_until_future_complete(result, timeout_sec=scaled(10))
    assert result.result().status == GoalStatus.STATUS_ABORTED
    assert list(result.result().result.sequence) == [7]


class ParameterNode(Node):
    def __init__(self, **kwargs: Any) -> None:
        super().__init__("minimal_param_node", **kwargs)
        from rcl_interfaces.msg import ParameterDescriptor, SetParametersResult

        self.SetParametersResult = SetParametersResult
        self.declare_parameter("my_parameter", "world")
        descriptor = ParameterDescriptor(description="How fast it goes [m/s].")
        self.declare_parameter("speed", 1.5, descriptor)
        self.seen: list[list[tuple[str, Any]]] = []
        self.add_on_set_parameters_callback(self.parameter_callback)

    def parameter_callback(self, params: list[Any]) -> Any:
        self.seen.append([(p.name, p.value) for p in params])
        for param in params:
            if param.name == "speed" and param.value < 0:
                return self.SetParametersResult(successful=False, reason="speed must be >= 0")
        return self.SetParametersResult(successful=True)


def test_parameters_with_a_callback(rclpy_inproc: None) -> None:
    from rclpy.parameter import Parameter

    node = ParameterNode()
    assert node.get_parameter("my_parameter").get_parameter_value().string_value == "world"
    assert node.get_parameter("speed").value == 1.5
    assert node.describe_parameter("speed").description == "How fast it goes [m/s]."
    [ok] = node.set_parameters([Parameter("speed", Parameter.Type.DOUBLE, 2.0)])
    assert ok.successful and node.get_parameter("speed").value == 2.0
    [refused] = node.set_parameters([Parameter("speed", value=-1.0)])
    assert not refused.successful and refused.reason == "speed must be >= 0"
    assert node.get_parameter("speed").value == 2.0
    assert node.seen == [[("speed", 2.0)], [("speed", -1.0)]]
    [wrong_type] = node.set_parameters([Parameter("speed", value="fast")])
    assert not wrong_type.successful
    assert node.get_parameter_or("missing", Parameter("missing", value=3)).value == 3
    from rclpy.exceptions import ParameterAlreadyDeclaredException, ParameterNotDeclaredException

    with pytest.raises(ParameterNotDeclaredException):
        node.get_parameter("missing")
    with pytest.raises(ParameterAlreadyDeclaredException):
        node.declare_parameter("speed", 3.0)
    # a change through robomodel's parameter store (what `ros2 param set` reaches) asks too
    assert not node.robomodel_node.set_parameters({"speed": -3.0}).successful
    # the ParameterEvent the change published is robomodel's /parameter_events
    assert node.robomodel_node.set_parameters({"speed": 4.0}).successful
    assert node.get_parameter("speed").value == 4.0


def test_parameter_overrides_from_ros_args(tutorial_interfaces: Path, tmp_path: Path) -> None:
    params = tmp_path / "params.yaml"
    params.write_text(
        "/robot/minimal_param_node:\n  ros__parameters:\n    speed: 7.5\n    my_parameter: file\n"
        "minimal_param_node:\n  ros__parameters:\n    speed: 9.0\n"  # /minimal_param_node's
    )
    rclpy.init(
        args=["node", "--ros-args", "-p", "speed:=1.0", "--params-file", str(params),
              "-p", "my_parameter:=earth", "-r", "__ns:=/robot", "-r", "chatter:=talk",
              "--", "--user-flag"],
        bus="inproc",
    )  # fmt: skip
    try:
        node = ParameterNode()
        assert node.get_parameter("my_parameter").value == "earth"  # -p after the file wins
        assert node.get_parameter("speed").value == 7.5  # the file after -p wins
        assert node.get_namespace() == "/robot"
        assert node.get_fully_qualified_name() == "/robot/minimal_param_node"
        from std_msgs.msg import String

        assert node.create_publisher(String, "chatter", 10).topic_name == "/robot/talk"
        renamed = rclpy.create_node("x", cli_args=["--ros-args", "-r", "__node:=renamed"])
        assert renamed.get_name() == "renamed"
    finally:
        rclpy.shutdown()


def test_undeclared_parameters_and_types(rclpy_inproc: None) -> None:
    from rclpy.exceptions import ParameterUninitializedException
    from rclpy.parameter import Parameter

    node = rclpy.create_node(
        "loose",
        parameter_overrides=[Parameter("gain", value=3)],
        automatically_declare_parameters_from_overrides=True,
    )
    assert node.get_parameter("gain").value == 3
    node.declare_parameter("later", Parameter.Type.INTEGER)
    with pytest.raises(ParameterUninitializedException):
        node.get_parameter("later")
    [wrong] = node.set_parameters([Parameter("later", value="x")])
    assert not wrong.successful
    [ok] = node.set_parameters([Parameter("later", value=5)])
    assert ok.successful and node.get_parameter("later").value == 5
    declared = node.declare_parameters("arm", [("joints", ["a", "b"]), ("rate", 10.0)])
    assert [(p.name, p.value) for p in declared] == [("arm.joints", ["a", "b"]), ("arm.rate", 10.0)]
    assert set(node.get_parameters_by_prefix("arm")) == {"joints", "rate"}


def test_a_parameter_out_of_its_descriptor_s_range_is_refused(rclpy_inproc: None) -> None:
    from rcl_interfaces.msg import IntegerRange, ParameterDescriptor
    from rclpy.exceptions import InvalidParameterValueException
    from rclpy.parameter import Parameter

    node = rclpy.create_node("ranged")
    descriptor = ParameterDescriptor(
        integer_range=[IntegerRange(from_value=0, to_value=10, step=2)]
    )
    node.declare_parameter("level", 4, descriptor)
    assert not node.set_parameters([Parameter("level", value=12)])[0].successful
    assert not node.set_parameters([Parameter("level", value=3)])[0].successful
    assert node.set_parameters([Parameter("level", value=8)])[0].successful
    with pytest.raises(InvalidParameterValueException):
        node.declare_parameter("other", 11, descriptor)


def test_mutually_exclusive_group_runs_one_at_a_time_reentrant_in_parallel(
    rclpy_inproc: None,
) -> None:
    node = rclpy.create_node("groups")
    running = {"exclusive": 0, "reentrant": 0}
    most = {"exclusive": 0, "reentrant": 0}
    calls = {"exclusive": 0, "reentrant": 0}
    lock = threading.Lock()

    def work(kind: str) -> None:
        with lock:
            running[kind] += 1
            calls[kind] += 1
            most[kind] = max(most[kind], running[kind])
        time.sleep(0.05)
        with lock:
            running[kind] -= 1

    exclusive = MutuallyExclusiveCallbackGroup()
    reentrant = ReentrantCallbackGroup()
    for _ in range(3):
        node.create_timer(0.01, lambda: work("exclusive"), callback_group=exclusive)
        node.create_timer(0.01, lambda: work("reentrant"), callback_group=reentrant)
    executor = MultiThreadedExecutor(num_threads=6)
    executor.add_node(node)
    _spin_until(executor, lambda: calls["exclusive"] >= 6 and calls["reentrant"] >= 6, "calls")
    executor.shutdown()
    assert most["exclusive"] == 1
    assert most["reentrant"] >= 2


def test_a_callback_that_raises_comes_out_of_spin(rclpy_inproc: None) -> None:
    node = rclpy.create_node("failing")

    def fail() -> None:
        raise ValueError("the node's own bug")

    node.create_timer(0.01, fail)
    with pytest.raises(ValueError, match="the node's own bug"):
        rclpy.spin(node)


def test_coroutine_callbacks_await_a_service(rclpy_inproc: None) -> None:
    from tutorial_interfaces.srv import AddTwoInts

    server = AddTwoIntsServer()
    node = rclpy.create_node("awaiting")
    client = node.create_client(AddTwoInts, "add_two_ints")
    sums: list[int] = []

    async def tick() -> None:
        response = await client.call_async(AddTwoInts.Request(a=len(sums), b=100))
        sums.append(response.sum)

    timer = node.create_timer(0.01, tick)
    executor = MultiThreadedExecutor(num_threads=2)
    executor.add_node(server)
    executor.add_node(node)
    _spin_until(executor, lambda: len(sums) >= 2, "awaited responses")
    timer.cancel()
    executor.shutdown()
    assert sums[0] == 100


def test_spin_until_future_complete_with_a_task_and_a_timeout(rclpy_inproc: None) -> None:
    from rclpy.task import Future

    node = rclpy.create_node("futures")
    executor = SingleThreadedExecutor()
    task = executor.create_task(lambda a, b: a * b, 6, 7)
    executor.spin_until_future_complete(task, timeout_sec=scaled(5))
    assert task.done() and task.result() == 42
    never = Future()
    start = time.monotonic()
    rclpy.spin_until_future_complete(node, never, timeout_sec=0.1)
    assert not never.done() and time.monotonic() - start >= 0.1
    done: list[Any] = []
    settled = Future()
    settled.add_done_callback(done.append)
    settled.set_result("ok")
    assert done == [settled] and settled.result() == "ok"
    failed = Future()
    failed.set_exception(RuntimeError("boom"))
    with pytest.raises(RuntimeError, match="boom"):
        failed.result()


def test_timer_cancel_reset_and_rate(rclpy_inproc: None) -> None:
    node = rclpy.create_node("timers")
    ticks: list[int] = []
    timer = node.create_timer(0.01, lambda: ticks.append(1))
    assert timer.timer_period_ns == 10_000_000
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    _spin_until(executor, lambda: len(ticks) >= 2, "ticks")
    timer.cancel()
    assert timer.is_canceled() and timer.time_until_next_call() is None
    count = len(ticks)
    executor.spin_once(timeout_sec=0.05)
    assert len(ticks) == count
    timer.reset()
    assert not timer.is_canceled()
    _spin_until(executor, lambda: len(ticks) > count, "ticks after reset")
    rate = node.create_rate(50)
    start = time.monotonic()
    for _ in range(3):
        rate.sleep()
    assert 0.04 <= time.monotonic() - start < scaled(1.0)
    waiting = node.create_timer(10.0, lambda: None, autostart=False)
    assert waiting.is_canceled()


def test_init_shutdown_and_the_context_manager(tutorial_interfaces: Path) -> None:
    from rclpy.exceptions import NotInitializedException

    assert not rclpy.ok()
    with pytest.raises(NotInitializedException):
        rclpy.create_node("too_early")
    with rclpy.init(args=[], bus="inproc"):
        assert rclpy.ok()
        with pytest.raises(RuntimeError, match="only be called once"):
            rclpy.init(args=[], bus="inproc")
        node = rclpy.create_node("inside")
        assert node.get_name() == "inside"
    assert not rclpy.ok()
    rclpy.try_shutdown()  # nothing to do, no error
    with pytest.raises(RuntimeError):
        rclpy.shutdown()
    rclpy.init(args=[], bus="inproc")  # once shut down, the context can start again
    assert rclpy.ok()
    rclpy.shutdown()


def test_spin_ends_when_another_thread_shuts_down(rclpy_inproc: None) -> None:
    from rclpy.executors import ExternalShutdownException

    node = rclpy.create_node("spinner")
    ended: list[BaseException] = []

    def spin() -> None:
        try:
            rclpy.spin(node)
        except ExternalShutdownException as exc:  # as rclpy's single-threaded executor
            ended.append(exc)

    spinner = threading.Thread(target=spin, daemon=True)
    spinner.start()
    wait_until(lambda: spinner.is_alive(), 5, what="the spinning thread")
    rclpy.shutdown()
    spinner.join(scaled(10))
    assert not spinner.is_alive()


def test_an_executor_runs_only_the_callbacks_of_its_own_nodes(rclpy_inproc: None) -> None:
    from std_msgs.msg import String

    mine, other = rclpy.create_node("mine"), rclpy.create_node("other")
    ticks: dict[str, int] = {"mine": 0, "other": 0}
    heard: list[str] = []
    mine.create_timer(0.001, lambda: ticks.__setitem__("mine", ticks["mine"] + 1))
    other.create_timer(0.001, lambda: ticks.__setitem__("other", ticks["other"] + 1))
    other.create_subscription(String, "/for_other", lambda m: heard.append(m.data), 2)
    publisher = mine.create_publisher(String, "/for_other", 10)
    executor = SingleThreadedExecutor()
    executor.add_node(mine)
    for n in range(5):
        publisher.publish(String(data=str(n)))
    wait_until(
        lambda: executor.spin_once(0.01) or ticks["mine"] >= 3,
        10,
        what="the executor's own timer to tick",
        interval_s=0,
    )
    assert ticks["other"] == 0 and heard == []  # parked on `other`, not run
    rclpy.spin_once(other, timeout_sec=scaled(5))  # the global executor holds `other` now
    wait_until(
        lambda: rclpy.spin_once(other, timeout_sec=0.01) or len(heard) >= 2,
        10,
        what="the parked messages",
        interval_s=0,
    )
    assert heard == ["3", "4"]  # the subscription's depth (2) of what waited: the newest
    assert ticks["other"] >= 1


def test_robomodel_s_own_classes_and_rosidl_s_meet_on_the_in_process_bus(
    rclpy_inproc: None,
) -> None:
    from std_msgs.msg import String
    from std_srvs.srv import SetBool

    from robomodel.runtime.msg.types import std_msgs as native_msgs
    from robomodel.runtime.msg.types import std_srvs as native_srvs

    assert String is not native_msgs.String and SetBool is not native_srvs.SetBool
    node = rclpy.create_node("mixed")
    native = node.robomodel_node  # robomodel's own node API, robomodel's own classes
    heard: list[Any] = []
    native_heard: list[Any] = []
    node.create_subscription(String, "/to_rclpy", heard.append, 10)
    native.create_subscription(native_msgs.String, "/to_native", native_heard.append)
    native.create_publisher(native_msgs.String, "/to_rclpy").publish(
        native_msgs.String(data="from robomodel")
    )
    node.create_publisher(String, "/to_native", 10).publish(String(data="from rclpy"))
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    wait_until(
        lambda: executor.spin_once(0.01) or (heard and native_heard),
        10,
        what="both messages",
        interval_s=0,
    )
    assert type(heard[0]) is String and heard[0].data == "from robomodel"
    assert type(native_heard[0]) is native_msgs.String and native_heard[0].data == "from rclpy"

    # a native server answers an rclpy client, and an rclpy server a native caller
    native.create_service(
        native_srvs.SetBool,
        "/native_server",
        lambda req: native_srvs.SetBool.Response(success=req.data, message=type(req).__module__),
    )
    node.create_service(
        SetBool,
        "/rclpy_server",
        lambda req, resp: SetBool.Response(success=not req.data, message=type(req).__module__),
    )
    spinner = threading.Thread(target=executor.spin, daemon=True)
    spinner.start()
    answer = node.create_client(SetBool, "/native_server").call(
        SetBool.Request(data=True), timeout_sec=scaled(10)
    )
    assert type(answer) is SetBool.Response and answer.success
    assert answer.message == native_srvs.SetBool.Request.__module__  # the server's own class
    native_answer = native.create_client(native_srvs.SetBool, "/rclpy_server").call(
        native_srvs.SetBool.Request(data=True), timeout_s=scaled(10)
    )
    assert type(native_answer) is native_srvs.SetBool.Response and not native_answer.success
    assert native_answer.message == SetBool.Request.__module__
    executor.shutdown()
    spinner.join(scaled(10))


def test_ctrl_c_stops_the_context_and_raises_keyboard_interrupt(tutorial_interfaces: Path) -> None:
    import os
    import signal

    from rclpy.signals import SignalHandlerOptions, get_current_signal_handlers_options

    before = signal.getsignal(signal.SIGINT)
    with rclpy.init(args=["test"], bus="inproc"):
        assert get_current_signal_handlers_options() == SignalHandlerOptions.ALL
        node = rclpy.create_node("interrupted")
        node.create_timer(0.01, lambda: os.kill(os.getpid(), signal.SIGINT))
        with pytest.raises(KeyboardInterrupt):
            rclpy.spin(node)
        assert not rclpy.ok()  # the handler stopped the context before Python's raised
    assert signal.getsignal(signal.SIGINT) is before  # put back at shutdown
    assert get_current_signal_handlers_options() == SignalHandlerOptions.NO
