"""Executor behaviours that upstream ROS 2 programs rely on, on robomodel's in-process bus:
``spin_once`` in a loop of one's own (demo_nodes_py's talker_qos), executors on two threads
(a node's work reaches the executor holding it at once), how SIGTERM and a shutdown from
another thread end a spin, a coroutine callback's exception leaving spin, and an rclpy future
awaited in asyncio (examples_rclpy_minimal_action_client's client_asyncio)."""

from __future__ import annotations

import asyncio
import concurrent.futures
import os
import signal
import statistics
import threading
import time
from pathlib import Path

import pytest
import rclpy
from rclpy.context import Context
from rclpy.executors import (
    ExternalShutdownException,
    MultiThreadedExecutor,
    SingleThreadedExecutor,
)
from rclpy.node import Node
from rclpy.task import Future

from tests.timing import scaled, wait_until


class Ticker(Node):
    """A node whose timer counts its calls, spun by a loop of ``spin_once`` calls."""

    def __init__(self, period_s: float) -> None:
        super().__init__("ticker")
        self.ticks = 0
        self.timer = self.create_timer(period_s, self.tick)

    def tick(self) -> None:
        self.ticks += 1


def test_spin_once_returns_after_a_callback_ran_not_on_a_wake_up(rclpy_inproc: None) -> None:
    """rclpy.spin_once(node) adds the node to the global executor (which wakes it) and waits
    for one callback: a loop of N calls runs the timer N times."""
    node = Ticker(0.02)
    for _ in range(3):
        rclpy.spin_once(node, timeout_sec=scaled(10))
    assert node.ticks == 3
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    executor.wake()
    executor.spin_once(timeout_sec=scaled(10))  # the wake-up is not the callback waited for
    assert node.ticks == 4


def test_a_node_held_by_an_executor_on_another_thread_is_served_at_once(
    rclpy_inproc: None,
) -> None:
    """Two executors spin on two threads: a message for the other's node is taken off the bus
    by either thread and reaches its own executor without waiting out a polling slice."""
    from std_msgs.msg import Float64

    talker, listener = rclpy.create_node("talker"), rclpy.create_node("listener")
    publisher = talker.create_publisher(Float64, "/stamp", 10)
    latencies_s: list[float] = []
    listener.create_subscription(
        Float64, "/stamp", lambda m: latencies_s.append(time.monotonic() - m.data), 100
    )
    executors = [SingleThreadedExecutor(), SingleThreadedExecutor()]
    executors[0].add_node(talker)
    executors[1].add_node(listener)
    threads = [threading.Thread(target=e.spin, daemon=True) for e in executors]
    for thread in threads:
        thread.start()
    for n in range(30):
        publisher.publish(Float64(data=time.monotonic()))
        wait_until(lambda n=n: len(latencies_s) > n, 10, what=f"message {n}", interval_s=0.001)
    for executor in executors:
        executor.shutdown()
    for thread in threads:
        thread.join(scaled(10))
    # A 50 ms polling slice gave a median near 25 ms; a wake-up takes well under a millisecond.
    assert statistics.median(latencies_s) < min(scaled(0.005), 0.015)


def test_sigterm_stops_the_context_and_spin_raises_external_shutdown(
    tutorial_interfaces: Path,
) -> None:
    from rclpy.signals import SignalHandlerOptions, get_current_signal_handlers_options

    before = signal.getsignal(signal.SIGTERM)
    with rclpy.init(args=["test"], bus="inproc"):
        assert get_current_signal_handlers_options() == SignalHandlerOptions.ALL
        # rclpy's handler, or the kill below would end the test process
        assert signal.getsignal(signal.SIGTERM) not in (before, signal.SIG_DFL)
        node = rclpy.create_node("terminated")
        # from outside while spin waits, as `kill` or a launch ending does
        threading.Timer(0.05, os.kill, (os.getpid(), signal.SIGTERM)).start()
        with pytest.raises(ExternalShutdownException):
            rclpy.spin(node)
        assert not rclpy.ok()
    assert signal.getsignal(signal.SIGTERM) is before  # put back at shutdown
    with rclpy.init(
        args=["test"], bus="inproc", signal_handler_options=SignalHandlerOptions.SIGTERM
    ):
        assert get_current_signal_handlers_options() == SignalHandlerOptions.SIGTERM
        assert signal.getsignal(signal.SIGINT) is signal.default_int_handler  # left alone


@pytest.mark.parametrize(
    ("executor_class", "raises"),
    [(SingleThreadedExecutor, True), (MultiThreadedExecutor, False)],
)
def test_a_shutdown_from_another_thread_ends_spin_as_in_rclpy(
    tutorial_interfaces: Path, executor_class: type, raises: bool
) -> None:
    """rclpy's single-threaded executor raises ExternalShutdownException out of spin, its
    multi-threaded one returns; either at once, not after a wait."""
    context = Context()
    rclpy.init(args=["test"], context=context, bus="inproc")
    node = rclpy.create_node("stopped", context=context)
    spinning = threading.Event()
    once = node.create_timer(0.01, lambda: (spinning.set(), once.cancel()))
    executor = executor_class(context=context)
    executor.add_node(node)
    outcome: list[BaseException | None] = []

    def spin() -> None:
        try:
            executor.spin()
        except ExternalShutdownException as exc:
            outcome.append(exc)
        else:
            outcome.append(None)

    thread = threading.Thread(target=spin, daemon=True)
    thread.start()
    assert spinning.wait(scaled(10))  # the spin runs; then it waits, with nothing to run
    context.interrupt()  # what the signal handler does
    thread.join(scaled(10))
    assert len(outcome) == 1 and isinstance(outcome[0], ExternalShutdownException) == raises
    executor.shutdown()
    context.try_shutdown()


def test_a_coroutine_callback_s_exception_leaves_spin(rclpy_inproc: None) -> None:
    node = rclpy.create_node("failing")
    later: Future = Future()

    async def fails_after_awaiting() -> None:
        await later
        raise ValueError("after the await")

    timer = node.create_timer(0.01, fails_after_awaiting)
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    executor.spin_once(timeout_sec=scaled(10))  # the timer's coroutine waits for `later`
    timer.cancel()
    later.set_result(None)
    with pytest.raises(ValueError, match="after the await"):
        executor.spin_once(timeout_sec=scaled(10))

    async def fails_at_once() -> None:
        raise KeyError("task")

    executor.create_task(fails_at_once)
    with pytest.raises(KeyError, match="task"):
        executor.spin_once(timeout_sec=scaled(10))


def test_an_rclpy_future_awaited_in_asyncio(rclpy_inproc: None) -> None:
    """An asyncio coroutine awaits an rclpy future completed on another thread (a service
    answer while the executor spins there)."""
    from std_srvs.srv import Trigger

    node = rclpy.create_node("asyncio_user")
    node.create_service(Trigger, "/ask", lambda req, res: Trigger.Response(message="answered"))
    client = node.create_client(Trigger, "/ask")
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    spinner = threading.Thread(target=executor.spin, daemon=True)
    spinner.start()

    async def ask() -> str:
        assert client.wait_for_service(timeout_sec=scaled(10))
        response = await client.call_async(Trigger.Request())
        return str(response.message)

    # asyncio.run on a thread of its own, as the user's program would own its thread: this
    # worker's main thread may hold the running loop of the browser tests' playwright
    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        answer = pool.submit(asyncio.run, asyncio.wait_for(ask(), scaled(10))).result()
    assert answer == "answered"
    executor.shutdown()
    spinner.join(scaled(10))


def test_spin_once_returns_when_a_call_async_response_comes(rclpy_inproc: None) -> None:
    """examples_rclpy_minimal_client's client_async: ``while not future.done():
    rclpy.spin_once(node)`` ends once the response is in (no done callbacks at all)."""
    from std_srvs.srv import Trigger

    server = rclpy.create_node("server")
    server.create_service(Trigger, "/ready", lambda req, res: Trigger.Response(success=True))
    executor = SingleThreadedExecutor()
    executor.add_node(server)
    spinner = threading.Thread(target=executor.spin, daemon=True)
    spinner.start()
    node = rclpy.create_node("client_async")
    client = node.create_client(Trigger, "/ready")
    assert client.wait_for_service(timeout_sec=scaled(10))
    future = client.call_async(Trigger.Request())
    started = time.monotonic()
    while not future.done():
        rclpy.spin_once(node, timeout_sec=scaled(20))
    # it returned with the response, not at the end of its wait
    assert time.monotonic() - started < scaled(10)
    assert future.result().success
    executor.shutdown()
    spinner.join(scaled(10))
