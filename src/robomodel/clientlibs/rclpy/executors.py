"""``rclpy.executors``: executors run the callbacks of nodes' subscriptions, timers, services,
clients and actions.

Every node of an rclpy context lives in the context's one robomodel context, whose executor
receives the bus's deliveries (:mod:`robomodel.runtime.executor`); an rclpy executor spins it.
:class:`SingleThreadedExecutor` runs each callback on the spinning thread.
:class:`MultiThreadedExecutor` hands them to a thread pool, a mutually exclusive callback group's
one at a time and in order, a reentrant group's in parallel. An executor runs only the
callbacks of the nodes added to it, as rclpy's: a delivery to another node that reaches the
spinning executor is parked on that node (a subscription keeps its QoS depth, a timer one tick)
until an executor holding the node spins. Each executor waits on a bell of its own, rung by
every post to the context's executor and by work parked on its nodes, so executors spinning
on several threads each hear of their work at once; a wake-up alone is no callback, so
``spin_once`` goes on waiting for one, as rclpy's. An executor of the user's that overrides
``spin_once`` takes its callbacks from :meth:`Executor.wait_for_ready_callbacks`.
"""

from __future__ import annotations

import collections
import os
import threading
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from typing import TYPE_CHECKING, Any, Protocol

from robomodel.clientlibs.rclpy.task import Future, Task
from robomodel.clientlibs.rclpy.utilities import get_default_context

if TYPE_CHECKING:
    from robomodel.clientlibs.rclpy.callback_groups import CallbackGroup
    from robomodel.clientlibs.rclpy.context import Context

__all__ = [
    "ConditionReachedException",
    "Executor",
    "ExternalShutdownException",
    "MultiThreadedExecutor",
    "ShutdownException",
    "SingleThreadedExecutor",
    "TimeoutException",
]

_SLICE_S = 0.05  # how often a wait for ever looks at shutdown and at its future


class Node(Protocol):
    """What an executor uses of an rclpy node (:class:`~robomodel.clientlibs.rclpy.node.Node`;
    the node module imports this one, which stays free of it)."""

    executor: Any
    _parked: collections.deque[Callable[[], None]]


class ExternalShutdownException(Exception):
    """The context was shut down from outside (a signal, another thread)."""


class ShutdownException(Exception):
    """The executor was shut down."""


class TimeoutException(Exception):
    """Nothing became ready in time."""


class ConditionReachedException(Exception):
    """The future waited for is done."""


class Executor:
    """The base of the executors (the interface is documented here)."""

    hands_over = False  # whether callbacks run on other threads than the spinning one
    raises_external_shutdown = True  # spin raises ExternalShutdownException (rclpy's single)

    def __init__(self, *, context: Context | None = None) -> None:
        self._context = context or get_default_context()
        self._nodes: list[Node] = []
        self._node_ids: frozenset[int] = frozenset()  # id() of each node added, for owns()
        self._held: tuple[Node, ...] = ()  # the nodes, read without the lock when spinning
        self._nodes_lock = threading.Lock()
        self._is_shutdown = False
        self._failure: BaseException | None = None
        # The bell this executor's spinning thread waits on, held while silent: rung by every
        # post to the context's executor while it waits, and by work parked on its own nodes
        # by another executor's thread (which takes that work off the shared queue).
        self._bell = threading.Lock()
        self._bell.acquire()
        self._ring = self.wake
        # An executor of the user's that overrides spin_once takes its callbacks through
        # wait_for_ready_callbacks: they are kept here, (run, entity, node), until it does.
        self._pulls = type(self).spin_once is not Executor.spin_once
        self._ready: collections.deque[tuple[Callable[[], None], Any, Any]] = collections.deque()
        if self._pulls:
            self.hands_over = True

    @property
    def context(self) -> Context:
        return self._context

    def _post(self, callback: Callable[[], None]) -> None:
        """Queue ``callback`` on the context's executor (run by whoever spins)."""
        self._context.robomodel.executor.post(callback)

    def wake(self) -> None:
        """Make the spinning thread look again (work was parked on a node of this one)."""
        bell = self._bell
        if bell.locked():
            try:  # noqa: SIM105 (as the context's executor rings: cheap)
                bell.release()
            except RuntimeError:  # rung by another thread in between
                pass

    def create_task(self, callback: Callable[..., Any], *args: Any, **kwargs: Any) -> Task:
        """Run ``callback(*args)`` (a function or a coroutine) at the next spin."""
        task = Task(callback, args, kwargs, executor=self)
        task._fails_spin = True
        self._post(task)
        return task

    def add_node(self, node: Node) -> bool:
        with self._nodes_lock:
            if node in self._nodes:
                return False
            self._nodes.append(node)
            self._node_ids = frozenset(map(id, self._nodes))
            self._held = tuple(self._nodes)
        node.executor = self
        if self._context.ok():
            self.wake()  # what was parked on the node runs at the next spin
        return True

    def remove_node(self, node: Node) -> None:
        with self._nodes_lock:
            if node in self._nodes:
                self._nodes.remove(node)
                self._node_ids = frozenset(map(id, self._nodes))
                self._held = tuple(self._nodes)

    def owns(self, node: Any) -> bool:
        """Whether ``node`` was added to this executor (its callbacks are this executor's)."""
        return id(node) in self._node_ids

    def get_nodes(self) -> list[Node]:
        with self._nodes_lock:
            return list(self._nodes)

    def shutdown(self, timeout_sec: float | None = None) -> bool:
        """Stop spinning (the spin in progress returns); True when stopped."""
        self._is_shutdown = True
        if self._context.dispatcher is self:
            self._context.dispatcher = None
        self.wake()  # its own bell: a spin waiting on it returns at once
        return True

    def _run_parked(self) -> int:
        """Run the deliveries parked on this executor's nodes while another spun."""
        done = 0
        for node in self._held:
            parked = node._parked
            while parked:
                try:
                    deliver = parked.popleft()
                except IndexError:
                    break
                try:
                    deliver()
                except Exception as exc:  # a parked service's callback: out of spin
                    self.fail(exc)
                done += 1
        return done

    def _spin_robomodel(self, timeout_s: float) -> int:
        """Run what is parked on this executor's nodes and what the context's executor holds;
        if nothing, wait up to ``timeout_s`` for either on this executor's own bell (so that
        two executors spinning on two threads each hear of their own work at once)."""
        context = self._context
        spinning = context._spinning
        outer = getattr(spinning, "executor", None)  # an executor spun in a callback nests
        context.dispatcher = self
        shared = context.robomodel.executor
        try:
            done = self._run_parked() + shared.spin_once(0.0)
            if not done and timeout_s > 0:
                wait = shared.wait_s(timeout_s)
                bell = self._bell
                bell.acquire(blocking=False)  # silence, then look: a later ring is heard
                shared.add_ring(self._ring)
                try:
                    done = self._run_parked() + shared.spin_once(0.0)
                    if not done and wait > 0 and context.ok() and not self._is_shutdown:
                        bell.acquire(timeout=wait)
                        done = self._run_parked() + shared.spin_once(0.0)
                finally:
                    shared.remove_ring(self._ring)
        finally:
            spinning.executor = outer
        failure, self._failure = self._failure, None
        if failure is not None:  # as rclpy: a callback's exception comes out of spin
            raise failure
        return done

    def spin(self) -> None:
        """Run callbacks until the context or this executor shuts down."""
        while self._context.ok() and not self._is_shutdown:
            self.spin_once()  # as rclpy: an executor of the user's may override it

    def _external_shutdown(self) -> None:
        """The wait ended because the context was shut down from outside (a signal, another
        thread): rclpy's single-threaded executor raises that out of spin, its multi-threaded
        one returns."""
        if self.raises_external_shutdown and not self._is_shutdown:
            raise ExternalShutdownException()

    def spin_once(self, timeout_sec: float | None = None) -> None:
        """Run what is ready; if nothing is, wait up to ``timeout_sec`` (None: for ever) for
        a callback and run it (a wake-up alone does not end the wait, as in rclpy)."""
        if not self._context.ok():
            self._external_shutdown()
            return
        if timeout_sec is not None and timeout_sec <= 0:
            self._spin_robomodel(0.0)
            return
        deadline = None if timeout_sec is None else time.monotonic() + timeout_sec
        while not self._is_shutdown:
            if not self._context.ok():
                self._external_shutdown()
                return
            remaining = _SLICE_S if deadline is None else deadline - time.monotonic()
            if remaining <= 0:
                return
            if self._spin_robomodel(min(remaining, _SLICE_S)):
                return

    def spin_until_future_complete(self, future: Future, timeout_sec: float | None = None) -> None:
        """Spin until ``future`` is done, or ``timeout_sec`` passed (None: for ever)."""
        if future._post is None:
            future._set_executor(self)  # its completion now wakes this spin
        deadline = (
            None if timeout_sec is None or timeout_sec < 0 else time.monotonic() + timeout_sec
        )
        while not self._is_shutdown and not future.done():
            if not self._context.ok():
                self._external_shutdown()
                return
            remaining = _SLICE_S if deadline is None else deadline - time.monotonic()
            if remaining <= 0:
                return
            self._spin_robomodel(min(remaining, _SLICE_S))

    def spin_once_until_future_complete(
        self, future: Future, timeout_sec: float | None = None
    ) -> None:
        if future._post is None:
            future._set_executor(self)
        if not future.done():
            self.spin_once(timeout_sec)

    # -- callbacks (called on the spinning thread) ----------------------------------------
    def dispatch(
        self, group: CallbackGroup, run: Callable[[], None], node: Any = None, entity: Any = None
    ) -> None:
        """Run ``run`` (a callback of ``group``, of ``entity`` of ``node``) now; a multi-threaded
        executor hands it over, an executor of the user's (overriding ``spin_once``) keeps it
        for :meth:`wait_for_ready_callbacks`. An exception leaves the spin call, with its
        traceback, as in rclpy."""
        if self._pulls:
            self._ready.append((run, entity, node))
            self.wake()
            return
        try:
            run()
        except Exception as exc:
            self._failure = exc

    def wait_for_ready_callbacks(
        self, timeout_sec: float | None = None, nodes: Any = None, condition: Any = None
    ) -> tuple[Task, Any, Any]:
        """The next callback ready, as ``(handler, entity, node)``: ``handler()`` runs it (a
        :class:`Task`). For an executor of the user's whose ``spin_once`` hands callbacks to
        threads of its own, as rclpy's custom executors do.

        Raises:
            ShutdownException: this executor was shut down.
            ExternalShutdownException: the context was.
            TimeoutException: nothing was ready within ``timeout_sec`` (None: wait for ever).
        """
        if not self._pulls:
            raise RuntimeError(
                "wait_for_ready_callbacks is for executors that override spin_once: "
                f"{type(self).__name__} runs its callbacks itself"
            )
        deadline = None if timeout_sec is None else time.monotonic() + timeout_sec
        while True:
            if self._ready:
                run, entity, node = self._ready.popleft()
                return Task(run, executor=self), entity, node
            if self._is_shutdown:
                raise ShutdownException()
            if not self._context.ok():
                raise ExternalShutdownException()
            remaining = _SLICE_S if deadline is None else deadline - time.monotonic()
            if remaining <= 0:
                raise TimeoutException()
            self._spin_robomodel(min(remaining, _SLICE_S))

    def fail(self, exc: Exception) -> None:
        """A callback raised ``exc``: the spin call raises it."""
        self._failure = exc
        self.wake()

    def __enter__(self) -> Executor:
        return self

    def __exit__(self, *exc: object) -> None:
        self.shutdown()


class SingleThreadedExecutor(Executor):
    """Runs every callback on the thread that spins, one at a time."""


class MultiThreadedExecutor(Executor):
    """Runs callbacks on ``num_threads`` threads (the CPU count by default), honouring callback
    groups."""

    hands_over = True
    raises_external_shutdown = False  # as rclpy's: spin returns when the context shuts down

    def __init__(self, num_threads: int | None = None, *, context: Context | None = None) -> None:
        super().__init__(context=context)
        if num_threads is None:
            num_threads = os.cpu_count() or 2
        if num_threads <= 0:
            raise ValueError("num_threads must be > 0")
        self._num_threads = num_threads
        self._pool = ThreadPoolExecutor(num_threads, thread_name_prefix="rclpy")
        self._lock = threading.Lock()
        self._waiting: dict[int, collections.deque[Callable[[], None]]] = {}
        self._busy: set[int] = set()

    @property
    def num_threads(self) -> int:
        return self._num_threads

    def dispatch(
        self, group: CallbackGroup, run: Callable[[], None], node: Any = None, entity: Any = None
    ) -> None:
        if group.reentrant:
            self._pool.submit(self._run, run)
            return
        key = id(group)
        with self._lock:
            if key in self._busy:
                self._waiting.setdefault(key, collections.deque()).append(run)
                return
            self._busy.add(key)
        self._pool.submit(self._drain, key, run)

    def _drain(self, key: int, run: Callable[[], None]) -> None:
        """Run the group's callbacks one after the other until none waits."""
        while True:
            self._run(run)
            with self._lock:
                queue = self._waiting.get(key)
                if not queue or self._is_shutdown:
                    self._busy.discard(key)
                    self._waiting.pop(key, None)
                    return
                run = queue.popleft()

    def shutdown(self, timeout_sec: float | None = None) -> bool:
        super().shutdown(timeout_sec)
        self._pool.shutdown(wait=timeout_sec is None or timeout_sec > 0, cancel_futures=True)
        return True

    def _run(self, run: Callable[[], None]) -> None:
        try:
            run()
        except Exception as exc:  # the spinning thread raises it, as rclpy's spin does
            self._failure = exc
            if self._context.ok():
                self.wake()
