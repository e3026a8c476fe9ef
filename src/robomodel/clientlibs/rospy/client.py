"""``init_node``, ``spin``, ``myargv``, the parameter server and the graph, as rospy offers
them, on a robomodel node of the ROS 1 master at ``ROS_MASTER_URI``."""

from __future__ import annotations

import atexit
import contextlib
import os
import signal
import sys
import threading
import time
from collections.abc import Sequence
from typing import Any

from robomodel.clientlibs.rospy import core
from robomodel.clientlibs.rospy.exceptions import ROSException, ROSInitException
from robomodel.clientlibs.rospy.names import (
    namespace_from,
    parse_command_line,
    resolve_remappings,
    strip_remappings,
)

__all__ = [
    "delete_param",
    "get_node_uri",
    "get_param",
    "get_param_cached",
    "get_param_names",
    "get_published_topics",
    "has_param",
    "init_node",
    "myargv",
    "search_param",
    "set_param",
    "spin",
]

_MASTER_POLL_S = 0.5
_UNSET = object()
_init_lock = threading.Lock()


def myargv(argv: Sequence[str] | None = None) -> list[str]:
    """``argv`` (default ``sys.argv``) without the ROS arguments (``a:=b``)."""
    return strip_remappings(sys.argv if argv is None else argv)


def init_node(
    name: str,
    argv: Sequence[str] | None = None,
    anonymous: bool = False,
    log_level: int | None = None,
    disable_rostime: bool = False,
    disable_rosout: bool = False,
    disable_signals: bool = False,
    xmlrpc_port: int = 0,
    tcpros_port: int = 0,
) -> None:
    """Make this process the ROS 1 node ``name``: it registers with the master at
    ``ROS_MASTER_URI`` (or ``__master:=``), waiting for one to answer as rospy does, and its
    callbacks run on a thread of their own. ``argv`` (default ``sys.argv``) gives remappings,
    ``__name:=``, ``__ns:=`` and private parameters ``_name:=value``."""
    if xmlrpc_port or tcpros_port:
        raise NotImplementedError(
            "rospy init_node(xmlrpc_port=..., tcpros_port=...): robomodel's nodes take free ports"
        )
    arguments = (name, anonymous, log_level, disable_rostime, disable_rosout, disable_signals)
    with _init_lock:
        existing = core.current()
        if existing is not None:
            if existing.arguments != arguments:
                raise ROSException(
                    "rospy.init_node() has already been called with different arguments: "
                    f"{existing.arguments[0]!r} before, {name!r} now"
                )
            return
        if core.is_shutdown():
            raise ROSInitException("init_node() after the node shut down: a process has one node")
        _init(name, sys.argv if argv is None else argv, arguments, disable_signals, disable_rosout)
    level = core.INFO if log_level is None else int(log_level)
    core.state().log_level = level


def _node_name(name: str, special: dict[str, str], anonymous: bool) -> str:
    if not name:
        raise ValueError("name must not be empty")
    if "/" in name:
        raise ValueError(f"namespaces are not allowed in node names: {name!r}")
    if "__name" in special:
        return special["__name"]  # as rospy: __name:= wins, and the name is no more anonymous
    if anonymous:
        return f"{name}_{os.getpid()}_{int(time.time() * 1000)}"
    return name


def _init(
    name: str,
    argv: Sequence[str],
    arguments: tuple[Any, ...],
    disable_signals: bool,
    disable_rosout: bool,
) -> None:
    from robomodel.runtime.context import Context
    from robomodel.runtime.transport.ros1.names import master_uri
    from robomodel.runtime.transport.ros1.xmlrpc_io import Ros1WireError

    command_line = parse_command_line(argv)
    special = dict(command_line.special)
    base = _node_name(name, special, arguments[1])
    namespace = namespace_from(special)
    caller_id = namespace + base
    remappings = resolve_remappings(command_line.remappings, caller_id)
    master = master_uri(special.get("__master"))
    if not disable_signals and threading.current_thread() is threading.main_thread():
        _install_signal_handlers()
    warned = False
    while True:
        try:
            context = Context("ros1", master=master)
            break
        except Ros1WireError:  # no master answers yet: rospy waits for one
            if core.is_shutdown():
                raise ROSInitException(
                    f"shut down while waiting for the master at {master}"
                ) from None
            if not warned:
                core.logwarn(
                    f"Unable to register with master node [{master}]: master may not be"
                    " running yet. Will keep trying."
                )
                warned = True
            time.sleep(_MASTER_POLL_S)
    node = context.create_node(base, namespace.rstrip("/") or "/", enable_rosout=not disable_rosout)
    node_state = core.NodeState(caller_id, remappings, context, node, arguments=arguments)
    node_state.hooks.extend(core.pending_hooks())
    core.set_state(node_state)
    core.bind_deferred(node_state)
    for key, value in command_line.params.items():
        set_param("~" + key, value)
    if _sim_time(node_state):
        node.set_parameters({"use_sim_time": True})
    spinner = threading.Thread(target=context.spin, name="rospy-callbacks", daemon=True)
    node_state.spinner = spinner
    spinner.start()
    atexit.register(_at_exit)


def _at_exit() -> None:
    core.signal_shutdown("atexit")
    core.wait_for_teardown()


def _install_signal_handlers() -> None:
    """SIGINT and SIGTERM shut the node down, as rospy's handlers do. The handler only writes
    the signal's number to a pipe: a thread reads it and shuts down. Setting the shutdown event
    in the handler itself would deadlock when the signal lands while the main thread holds that
    event's lock (returning from a sleep's wait)."""
    read_end, write_end = os.pipe()
    os.set_blocking(write_end, False)

    def watch() -> None:
        number = os.read(read_end, 1)
        if number:
            core.signal_shutdown(f"signal-{number[0]}")

    threading.Thread(target=watch, name="rospy-signals", daemon=True).start()
    for number in (signal.SIGINT, signal.SIGTERM):
        previous = signal.getsignal(number)

        def handler(signum: int, frame: Any, previous: Any = previous) -> None:
            with contextlib.suppress(BlockingIOError):  # a full pipe: shutdown is under way
                os.write(write_end, bytes([signum]))
            if callable(previous):
                # as rospy: Ctrl-C's KeyboardInterrupt is dropped, and the node's sleeps and
                # spin end through the shutdown instead
                with contextlib.suppress(KeyboardInterrupt):
                    previous(signum, frame)

        signal.signal(number, handler)


def spin() -> None:
    """Block until the node shuts down (Ctrl-C, ``signal_shutdown``); callbacks run meanwhile."""
    core.state()
    stop = core.shutdown_event()
    try:
        while not stop.is_set():
            stop.wait(0.5)
    except KeyboardInterrupt:
        core.signal_shutdown("keyboard interrupt")
    core.wait_for_teardown()


# -- parameters -----------------------------------------------------------------------------------
def _master(node_state: core.NodeState, method: str, *args: Any) -> Any:
    from robomodel.runtime.transport.ros1.xmlrpc_io import Ros1WireError, call

    master = node_state.context.transport.master_uri  # type: ignore[attr-defined]
    try:
        return call(master, method, node_state.caller_id, *args, timeout_s=10.0)
    except Ros1WireError as exc:
        raise ROSException(f"{method}: {exc}") from None


def _sim_time(node_state: core.NodeState) -> bool:
    """Whether ``/use_sim_time`` is true (one call: the master answers an error when unset)."""
    try:
        return _master(node_state, "getParam", "/use_sim_time") is True
    except ROSException:
        return False


def get_param(param_name: str, default: Any = _UNSET) -> Any:
    """The value of ``param_name`` (``~private``, relative or global); ``default`` if it is
    not set, KeyError if no default is given."""
    node_state = core.state()
    name = node_state.resolve(param_name)
    if _master(node_state, "hasParam", name):
        return _master(node_state, "getParam", name)
    if default is _UNSET:
        raise KeyError(name)
    return default


def get_param_cached(param_name: str, default: Any = _UNSET) -> Any:
    """:func:`get_param` (every read asks the master)."""
    return get_param(param_name, default)


def set_param(param_name: str, param_value: Any) -> None:
    """Set ``param_name`` on the master's parameter server."""
    node_state = core.state()
    _master(node_state, "setParam", node_state.resolve(param_name), param_value)


def has_param(param_name: str) -> bool:
    node_state = core.state()
    return bool(_master(node_state, "hasParam", node_state.resolve(param_name)))


def delete_param(param_name: str) -> None:
    """Delete ``param_name``; KeyError if it is not set."""
    node_state = core.state()
    name = node_state.resolve(param_name)
    if not _master(node_state, "hasParam", name):
        raise KeyError(name)
    _master(node_state, "deleteParam", name)


def search_param(param_name: str) -> str | None:
    """The closest parameter ``param_name`` up the node's namespaces, or None."""
    from robomodel.runtime.transport.ros1.xmlrpc_io import Ros1WireError, call_raw

    node_state = core.state()
    master = node_state.context.transport.master_uri  # type: ignore[attr-defined]
    try:
        answer = call_raw(master, "searchParam", node_state.caller_id, param_name, timeout_s=10.0)
    except Ros1WireError as exc:
        raise ROSException(f"searchParam: {exc}") from None
    if isinstance(answer, list) and len(answer) == 3 and answer[0] == -1:
        return None  # as rospy: the master found none (code -1)
    if not (isinstance(answer, list) and len(answer) == 3 and answer[0] == 1):
        raise ROSException(f"searchParam: the master answered {answer!r:.80}")
    return str(answer[2]) if answer[2] else None


def get_param_names() -> list[str]:
    return [str(name) for name in _master(core.state(), "getParamNames")]


# -- graph ------------------------------------------------------------------------------------------
def get_published_topics(namespace: str = "/") -> list[list[str]]:
    """``[topic, type]`` of every published topic in ``namespace``."""
    node_state = core.state()
    return [[str(t), str(k)] for t, k in _master(node_state, "getPublishedTopics", namespace)]


def get_node_uri() -> str:
    """The node's slave API URI, as the master has it."""
    node_state = core.state()
    return str(_master(node_state, "lookupNode", node_state.caller_id))
