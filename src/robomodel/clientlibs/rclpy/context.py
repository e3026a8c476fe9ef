"""``rclpy.context.Context``: what ``rclpy.init`` initialises. Behind it, one robomodel
:class:`~robomodel.runtime.context.Context` on the Zenoh bus (rmw_zenoh's wire, the router
robomodel starts when none answers), which every node of the context shares."""

from __future__ import annotations

import os
import sys
import threading
import weakref
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, Protocol

from robomodel.clientlibs.rclpy._arguments import RosArguments, parse_ros_arguments
from robomodel.clientlibs.rclpy.exceptions import NotInitializedException

if TYPE_CHECKING:
    from robomodel.runtime.context import Context as RobomodelContext

__all__ = ["Context"]

_BUS_VARIABLE = "ROBOMODEL_RCLPY_BUS"  # robomodel's: "inproc" keeps the nodes in this process


def _choose_rosidl_flavour() -> None:
    """rclpy's message classes are rosidl's. Importing rclpy chooses that flavour already (the
    flavour rule of :mod:`robomodel.clientlibs.messages`); an explicit chooser, where there is
    one, is told too. ``ROBOMODEL_MESSAGE_FLAVOUR`` is left alone: child processes (a rospy
    node a script starts) choose their own."""
    try:
        from robomodel.clientlibs import messages  # type: ignore[attr-defined, unused-ignore]
    except ImportError:
        return
    choose = getattr(messages, "set_flavour", None)
    if callable(choose):
        choose("rosidl")


class Dispatcher(Protocol):
    """The executor spinning a context, as nodes hand it their callbacks
    (:class:`~robomodel.clientlibs.rclpy.executors.Executor`)."""

    hands_over: bool

    def dispatch(
        self, group: Any, run: Callable[[], None], node: Any = None, entity: Any = None
    ) -> None: ...

    def fail(self, exc: Exception) -> None: ...

    def owns(self, node: Any) -> bool: ...


class _Node(Protocol):
    def destroy_node(self) -> None: ...


class Context:
    """An rclpy context: ``init`` opens its robomodel context, ``shutdown`` closes it."""

    def __init__(self) -> None:
        self._lock = threading.RLock()
        self._robomodel: RobomodelContext | None = None
        self._shutdown = threading.Event()
        self._shutdown.set()
        self._callbacks: list[Callable[[], None]] = []
        self._nodes: weakref.WeakSet[_Node] = weakref.WeakSet()
        self._domain_id: int | None = None
        self.arguments = RosArguments()
        self._dispatcher: Dispatcher | None = None  # the executor that spun last, any thread
        self._spinning = threading.local()  # .executor: the one spinning on this thread

    @property
    def dispatcher(self) -> Dispatcher | None:
        """The executor spinning on this thread; on a thread that spins none (a pool thread of
        a multi-threaded executor, a thread of the user's), the one that spun last."""
        own: Dispatcher | None = getattr(self._spinning, "executor", None)
        return own if own is not None else self._dispatcher

    @dispatcher.setter
    def dispatcher(self, executor: Dispatcher | None) -> None:
        self._spinning.executor = executor
        self._dispatcher = executor

    # -- lifetime -----------------------------------------------------------------------------
    def init(
        self,
        args: Sequence[str] | None = None,
        *,
        initialize_logging: bool = True,
        domain_id: int | None = None,
        bus: str | None = None,
    ) -> None:
        """Parse ``args`` (``sys.argv`` by default; its ``--ros-args``) and join the bus.

        Args:
            bus: robomodel's: ``zenoh`` (the default; ``ROBOMODEL_RCLPY_BUS`` chooses too) or
                ``inproc`` (this process only, for tests).
        """
        with self._lock:
            if self._robomodel is not None:
                raise RuntimeError("Context.init() must only be called once")
            from robomodel.clientlibs.rclpy import logging as rclpy_logging
            from robomodel.runtime.context import Context as RobomodelContext

            self.arguments = parse_ros_arguments(list(sys.argv if args is None else args))
            for logger, level in self.arguments.log_levels:
                if logger is None:
                    rclpy_logging.set_default_level(level)
                else:
                    rclpy_logging.set_logger_level(logger, level)
            _choose_rosidl_flavour()
            chosen = bus or os.environ.get(_BUS_VARIABLE) or "zenoh"
            if chosen not in ("zenoh", "inproc"):
                raise ValueError(f"rclpy bus must be 'zenoh' or 'inproc', got '{chosen}'")
            self._robomodel = RobomodelContext(chosen, domain_id=domain_id)
            self._domain_id = domain_id
            self._dispatcher = None
            self._shutdown.clear()

    def ok(self) -> bool:
        return not self._shutdown.is_set()

    def shutdown(self) -> None:
        """Destroy the nodes and leave the bus; RuntimeError if not initialised."""
        with self._lock:
            if self._robomodel is None:
                raise RuntimeError("Context must be initialized before it can be shutdown")
            robomodel, self._robomodel = self._robomodel, None
            self._dispatcher = None
            self._shutdown.set()
            robomodel.executor.wake()  # waiting executors see it at once
            callbacks, self._callbacks = self._callbacks, []
        from robomodel.clientlibs.rclpy import signals

        signals._forget(self)
        for callback in callbacks:
            callback()
        for node in list(self._nodes):
            node.destroy_node()
        robomodel.shutdown()

    def interrupt(self) -> None:
        """Ctrl-C (rclpy's SIGINT handler): no longer ``ok()``, and the spinning executor wakes
        and returns; the nodes and the bus go at :meth:`shutdown` (``try_shutdown``, the end
        of ``with rclpy.init()``), which is safe to call then."""
        self._shutdown.set()
        self.wake()

    def try_shutdown(self) -> None:
        """Shut down if initialised; nothing otherwise."""
        with self._lock:
            if self._robomodel is None:
                return
        self.shutdown()

    def on_shutdown(self, callback: Callable[[], None]) -> None:
        """Call ``callback()`` when the context shuts down (at once if it is)."""
        with self._lock:
            if self._robomodel is not None:
                self._callbacks.append(callback)
                return
        callback()

    def _post(self, callback: Callable[[], None]) -> None:
        """Queue ``callback`` for whoever spins (what a :class:`~.task.Future` made with
        ``executor=context`` runs its done callbacks with); nothing once shut down, when no
        executor will run anything again."""
        robomodel = self._robomodel
        if robomodel is not None:
            robomodel.executor.post(callback)

    def fail(self, exc: Exception) -> None:
        """A task made with ``executor=context`` (a coroutine callback) raised ``exc``: the
        spin call of the executor running it raises it."""
        dispatcher = self.dispatcher
        if dispatcher is None:
            raise exc
        dispatcher.fail(exc)

    def wake(self) -> None:
        """Make every executor waiting for this context's work look again."""
        robomodel = self._robomodel
        if robomodel is not None:
            robomodel.executor.wake()

    def wait_shutdown(self, timeout_s: float) -> bool:
        """Wait up to ``timeout_s`` for shutdown; True once shut down."""
        return self._shutdown.wait(timeout_s)

    def get_domain_id(self) -> int:
        transport: Any = self.robomodel.transport
        return int(getattr(transport, "domain_id", self._domain_id or 0))

    def track_node(self, node: _Node) -> None:
        self._nodes.add(node)

    def untrack_node(self, node: _Node) -> None:
        self._nodes.discard(node)

    @property
    def robomodel(self) -> RobomodelContext:
        """The robomodel context behind this one; NotInitializedException before ``init``."""
        robomodel = self._robomodel
        if robomodel is None:
            raise NotInitializedException()
        return robomodel

    def __enter__(self) -> Context:
        return self

    def __exit__(self, *exc: object) -> None:
        self.try_shutdown()
