"""rclpy, the ROS 2 Python client library, on robomodel's runtime.

``import rclpy`` (through robomodel's import finder, when no real ROS 2 install is on the path)
gives this package: nodes are robomodel runtime nodes on the Zenoh bus in rmw_zenoh's wire
format, so real ROS 2 nodes and tools see them. What rclpy offers and robomodel does not raises
NotImplementedError naming the call (docs/reference/rclpy.md lists both).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from robomodel.clientlibs.rclpy.context import Context
from robomodel.clientlibs.rclpy.utilities import (
    get_default_context,
    get_rmw_implementation_identifier,
    ok,
    remove_ros_args,
    shutdown,
    try_shutdown,
)

if TYPE_CHECKING:
    from robomodel.clientlibs.rclpy.executors import Executor
    from robomodel.clientlibs.rclpy.node import Node
    from robomodel.clientlibs.rclpy.task import Future

__all__ = [
    "InitContextManager",
    "create_node",
    "get_default_context",
    "get_global_executor",
    "get_rmw_implementation_identifier",
    "init",
    "ok",
    "remove_ros_args",
    "shutdown",
    "spin",
    "spin_once",
    "spin_until_future_complete",
    "try_shutdown",
]

_global_executor: list[Executor] = []


class InitContextManager:
    """What ``init`` returns: ``with rclpy.init():`` shuts the context down on leaving."""

    def __init__(self, context: Context) -> None:
        self.context = context

    def __enter__(self) -> InitContextManager:
        return self

    def __exit__(self, *exc: object) -> None:
        self.context.try_shutdown()


def init(
    *,
    args: Sequence[str] | None = None,
    context: Context | None = None,
    domain_id: int | None = None,
    signal_handler_options: Any = None,
    bus: str | None = None,
) -> InitContextManager:
    """Initialise ``context`` (the default one): parse ``args`` (``sys.argv``) and join the bus.

    ``bus`` is robomodel's: ``zenoh`` (default) or ``inproc`` (one process, for tests).
    ``signal_handler_options`` as rclpy's (None: ``ALL`` for the default context, else ``NO``):
    Ctrl-C then stops the context (``ok()`` is False) and raises KeyboardInterrupt, SIGTERM
    stops it and ``spin`` raises ``ExternalShutdownException``
    (:mod:`~robomodel.clientlibs.rclpy.signals`).
    """
    from robomodel.clientlibs.rclpy import signals

    chosen = context or get_default_context()
    if signal_handler_options is None:
        signal_handler_options = (
            signals.SignalHandlerOptions.ALL
            if chosen is get_default_context()
            else signals.SignalHandlerOptions.NO
        )
    options = signals.SignalHandlerOptions(signal_handler_options)
    chosen.init(args, domain_id=domain_id, bus=bus)
    if options != signals.SignalHandlerOptions.NO:
        signals.install_signal_handlers(options)
        signals._watch(chosen)
    return InitContextManager(chosen)


def get_global_executor() -> Executor:
    """The executor ``rclpy.spin`` uses (single-threaded, on the default context)."""
    from robomodel.clientlibs.rclpy.executors import SingleThreadedExecutor

    if not _global_executor:
        _global_executor.append(SingleThreadedExecutor())
    return _global_executor[0]


def create_node(
    node_name: str,
    *,
    context: Context | None = None,
    cli_args: Sequence[str] | None = None,
    namespace: str | None = None,
    use_global_arguments: bool = True,
    enable_rosout: bool = True,
    start_parameter_services: bool = True,
    parameter_overrides: Any = None,
    allow_undeclared_parameters: bool = False,
    automatically_declare_parameters_from_overrides: bool = False,
    enable_logger_service: bool = False,
) -> Node:
    """A :class:`~robomodel.clientlibs.rclpy.node.Node`."""
    from robomodel.clientlibs.rclpy.node import Node

    return Node(
        node_name,
        context=context,
        cli_args=cli_args,
        namespace=namespace,
        use_global_arguments=use_global_arguments,
        enable_rosout=enable_rosout,
        start_parameter_services=start_parameter_services,
        parameter_overrides=parameter_overrides,
        allow_undeclared_parameters=allow_undeclared_parameters,
        automatically_declare_parameters_from_overrides=automatically_declare_parameters_from_overrides,
        enable_logger_service=enable_logger_service,
    )


def _executor_for(node: Node, executor: Executor | None) -> Executor:
    if executor is not None:
        return executor
    if node.context is get_default_context():
        return get_global_executor()
    from robomodel.clientlibs.rclpy.executors import SingleThreadedExecutor

    return SingleThreadedExecutor(context=node.context)


def spin(node: Node, executor: Executor | None = None) -> None:
    """Run ``node``'s callbacks until the context shuts down."""
    chosen = _executor_for(node, executor)
    try:
        chosen.add_node(node)
        chosen.spin()
    finally:
        chosen.remove_node(node)


def spin_once(
    node: Node, *, executor: Executor | None = None, timeout_sec: float | None = None
) -> None:
    """Run one callback of ``node`` (waiting up to ``timeout_sec`` for one)."""
    chosen = _executor_for(node, executor)
    try:
        chosen.add_node(node)
        chosen.spin_once(timeout_sec=timeout_sec)
    finally:
        chosen.remove_node(node)


def spin_until_future_complete(
    node: Node, future: Future, executor: Executor | None = None, timeout_sec: float | None = None
) -> None:
    """Run ``node``'s callbacks until ``future`` is done (or ``timeout_sec`` passed)."""
    chosen = _executor_for(node, executor)
    try:
        chosen.add_node(node)
        chosen.spin_until_future_complete(future, timeout_sec)
    finally:
        chosen.remove_node(node)
