"""rclpy APIs past the tutorials that the upstream example programs use, on robomodel's
in-process bus: guard conditions (examples_rclpy_guard_conditions), a callback group of the
user's (examples_rclpy_executors' custom_callback_group), an executor of the user's built on
``wait_for_ready_callbacks`` (its custom_executor), pre-set parameter callbacks
(demo_nodes_py's set_parameters_callback) and a coroutine callback awaiting a tf2 lookup
(examples_tf2_py's async_waits_for_transform)."""

from __future__ import annotations

import threading
from concurrent.futures import ThreadPoolExecutor
from typing import Any

import pytest
import rclpy
from rclpy.callback_groups import CallbackGroup
from rclpy.executors import Executor, ShutdownException, SingleThreadedExecutor
from rclpy.node import Node
from rclpy.parameter import Parameter

from tests.timing import scaled, wait_until


def test_a_guard_condition_runs_its_callback_on_the_node_s_executor(rclpy_inproc: None) -> None:
    node = rclpy.create_node("guarded")
    executor = rclpy.executors.SingleThreadedExecutor()  # rclpy.executors: there once a node is
    executor.add_node(node)
    threads: list[threading.Thread] = []
    guard = node.create_guard_condition(lambda: threads.append(threading.current_thread()))
    assert list(node.guards) == [guard]
    trigger = threading.Thread(target=lambda: (guard.trigger(), guard.trigger()))
    trigger.start()
    trigger.join(scaled(10))
    executor.spin_once(timeout_sec=scaled(10))
    assert threads == [threading.current_thread()]  # on the spinning thread
    executor.spin_once(timeout_sec=0.05)
    assert len(threads) == 1  # two triggers before it ran: one call, as rclpy's
    node.destroy_guard_condition(guard)
    guard.trigger()
    executor.spin_once(timeout_sec=0.05)
    assert len(threads) == 1


class TokenBucketGroup(CallbackGroup):
    """Lets ``tokens`` callbacks run, then refuses; counts what it was told."""

    def __init__(self, tokens: int) -> None:
        super().__init__()
        self.tokens = tokens
        self.ended: list[Any] = []

    def can_execute(self, entity: Any) -> bool:
        return self.tokens > 0

    def beginning_execution(self, entity: Any) -> bool:
        if self.tokens <= 0:
            return False
        self.tokens -= 1
        return True

    def ending_execution(self, entity: Any) -> None:
        self.ended.append(entity)


def test_a_callback_group_of_the_user_s_decides_which_callbacks_run(rclpy_inproc: None) -> None:
    node = rclpy.create_node("throttled")
    group = TokenBucketGroup(tokens=3)
    ticks: list[int] = []
    timer = node.create_timer(0.001, lambda: ticks.append(len(ticks)), callback_group=group)
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    wait_until(lambda: executor.spin_once(0.01) or len(ticks) >= 3, 10, what="three ticks")
    for _ in range(20):  # the timer goes on firing; the group refuses every one
        executor.spin_once(0.002)
    assert ticks == [0, 1, 2] and group.ended == [timer, timer, timer]
    group.tokens = 1
    wait_until(lambda: executor.spin_once(0.01) or len(ticks) >= 4, 10, what="a fourth tick")
    assert ticks == [0, 1, 2, 3]


class PriorityExecutor(Executor):
    """An executor of the user's: the nodes in ``fast`` get a pool, the others one thread."""

    def __init__(self) -> None:
        super().__init__()
        self.fast: set[Node] = set()
        self.pool = ThreadPoolExecutor(max_workers=2, thread_name_prefix="fast")
        self.single = ThreadPoolExecutor(max_workers=1, thread_name_prefix="slow")

    def spin_once(self, timeout_sec: float | None = None) -> None:
        try:
            handler, _entity, node = self.wait_for_ready_callbacks(timeout_sec=timeout_sec)
        except StopIteration:
            pass
        else:
            (self.pool if node in self.fast else self.single).submit(handler)


def test_an_executor_of_the_user_s_takes_callbacks_with_wait_for_ready_callbacks(
    rclpy_inproc: None,
) -> None:
    from std_msgs.msg import String

    fast, slow = rclpy.create_node("fast"), rclpy.create_node("slow")
    ran_on: dict[str, str] = {}
    fast.create_subscription(
        String, "/estop", lambda m: ran_on.__setitem__("fast", threading.current_thread().name), 10
    )
    slow_timer = slow.create_timer(
        0.01, lambda: ran_on.__setitem__("slow", threading.current_thread().name)
    )
    publisher = slow.create_publisher(String, "/estop", 10)
    executor = PriorityExecutor()
    executor.fast.add(fast)
    executor.add_node(fast)
    executor.add_node(slow)
    ended: list[BaseException] = []

    def spin() -> None:
        try:
            executor.spin()
        except ShutdownException as exc:  # as rclpy's: out of wait_for_ready_callbacks
            ended.append(exc)

    spinner = threading.Thread(target=spin, daemon=True)
    spinner.start()
    publisher.publish(String(data="stop"))
    wait_until(lambda: len(ran_on) == 2, 10, what="both callbacks")
    assert ran_on["fast"].startswith("fast") and ran_on["slow"].startswith("slow")
    _handler, entity, node = _one_ready(slow_timer, slow)
    assert entity is slow_timer and node is slow
    executor.shutdown()
    spinner.join(scaled(10))
    # spin ends: out of wait_for_ready_callbacks with ShutdownException when that was waiting,
    # or at its loop's check when the 10 ms timer had just handed a callback out (as rclpy's)
    assert not spinner.is_alive()
    assert all(isinstance(exc, ShutdownException) for exc in ended)
    with pytest.raises(ShutdownException):
        executor.wait_for_ready_callbacks(timeout_sec=0.01)
    with pytest.raises(RuntimeError, match="override spin_once"):
        SingleThreadedExecutor().wait_for_ready_callbacks(timeout_sec=0.01)


def _one_ready(timer: Any, node: Node) -> tuple[Any, Any, Any]:
    """What wait_for_ready_callbacks hands out for ``node``'s timer, from an executor of the
    user's that is not spinning."""
    executor = PriorityExecutor()
    executor.add_node(node)
    handler, entity, owner = executor.wait_for_ready_callbacks(timeout_sec=scaled(10))
    handler()
    assert handler.done() and handler.exception() is None
    executor.remove_node(node)
    return handler, entity, owner


def test_pre_set_parameter_callbacks_change_what_is_set_remote_sets_too(
    rclpy_inproc: None,
) -> None:
    node = rclpy.create_node("pre_set")
    node.declare_parameter("param1", 0.0)
    node.declare_parameter("param2", 0.0)
    seen: list[list[str]] = []

    def also_param2(parameters: list[Parameter]) -> list[Parameter]:
        extra = [Parameter("param2", Parameter.Type.DOUBLE, 4.0)]
        return parameters + (extra if any(p.name == "param1" for p in parameters) else [])

    def record(parameters: list[Parameter]) -> Any:
        from rcl_interfaces.msg import SetParametersResult

        seen.append(sorted(p.name for p in parameters))
        return SetParametersResult(successful=True)

    node.add_pre_set_parameters_callback(also_param2)
    node.add_on_set_parameters_callback(record)
    assert node.set_parameters([Parameter("param1", value=1.5)])[0].successful
    assert node.get_parameter("param2").value == 4.0 and seen == [["param1", "param2"]]
    node.set_parameters([Parameter("param2", value=0.0)])
    # a remote set (the parameter services, as `ros2 param set` calls them) goes through it too
    from robomodel.runtime import Node as RobomodelNode

    assert isinstance(node.robomodel_node, RobomodelNode)
    assert node.robomodel_node.set_parameters({"param1": 2.5}).successful
    assert node.get_parameter("param2").value == 4.0
    node.remove_pre_set_parameters_callback(also_param2)
    node.add_pre_set_parameters_callback(lambda parameters: [])
    result = node.set_parameters([Parameter("param1", value=3.0)])[0]
    assert not result.successful and "cannot be empty" in result.reason
    assert node.get_parameter("param1").value == 2.5


def test_a_coroutine_callback_awaits_a_tf2_lookup(rclpy_inproc: None) -> None:
    import tf2_ros
    from geometry_msgs.msg import TransformStamped

    node = rclpy.create_node("async_waits")
    buffer = tf2_ros.Buffer()
    tf2_ros.TransformListener(buffer, node)
    got: list[Any] = []

    async def on_timer() -> None:
        timer.cancel()
        got.append(await buffer.lookup_transform_async("odom", "base", rclpy.time.Time()))

    timer = node.create_timer(0.01, on_timer)
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    wait_until(lambda: executor.spin_once(0.01) or timer.is_canceled(), 10, what="the timer")
    assert got == []  # suspended: no transform yet
    sent = TransformStamped()
    sent.header.frame_id, sent.child_frame_id = "odom", "base"
    sent.transform.translation.x, sent.transform.rotation.w = 2.0, 1.0
    tf2_ros.StaticTransformBroadcaster(node).sendTransform(sent)
    wait_until(lambda: executor.spin_once(0.01) or got, 10, what="the awaited transform")
    assert got[0].transform.translation.x == 2.0 and got[0].child_frame_id == "base"
