"""The node of this process and its lifetime: ``is_shutdown``, ``on_shutdown``,
``signal_shutdown``, names, and rospy's logging (``loginfo`` and its ``_throttle``, ``_once``
and ``_throttle_identical`` forms) to the console and ``/rosout``.

rospy has one node per process; :class:`NodeState` holds it (robomodel's context on the ROS 1
bus, its node and a thread that runs the node's callbacks), created by ``init_node``.
"""

from __future__ import annotations

import functools
import hashlib
import inspect
import logging
import sys
import threading
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from robomodel.clientlibs.rospy.exceptions import ROSInitException
from robomodel.clientlibs.rospy.names import resolve

if TYPE_CHECKING:
    from robomodel.runtime.context import Context
    from robomodel.runtime.node import Node

__all__ = [
    "DEBUG",
    "ERROR",
    "FATAL",
    "INFO",
    "WARN",
    "NodeState",
    "get_caller_id",
    "get_name",
    "get_namespace",
    "is_shutdown",
    "on_shutdown",
    "resolve_name",
    "robomodel_node",
    "signal_shutdown",
]

# rosgraph_msgs/Log's levels, which rospy exports
DEBUG, INFO, WARN, ERROR, FATAL = 1, 2, 4, 8, 16
_PYTHON_LEVEL = {DEBUG: logging.DEBUG, INFO: logging.INFO, WARN: logging.WARNING,
                 ERROR: logging.ERROR, FATAL: logging.CRITICAL}  # fmt: skip
_NAMES = {DEBUG: "DEBUG", INFO: "INFO", WARN: "WARN", ERROR: "ERROR", FATAL: "FATAL"}


@dataclass(eq=False)
class NodeState:
    """This process's rospy node: its names, its robomodel node, and its lifetime."""

    caller_id: str
    remappings: Mapping[str, str]
    context: Context
    node: Node
    log_level: int = INFO
    arguments: tuple[Any, ...] = ()  # init_node's, to tell a second call with others
    spinner: threading.Thread | None = None
    hooks: list[Callable[[], Any]] = field(default_factory=list)

    def resolve(self, name: str) -> str:
        return resolve(name, self.caller_id, self.remappings)


class _Lifetime:
    """The shutdown flag, the event sleeps wait on, and the teardown done once."""

    def __init__(self) -> None:
        self.state: NodeState | None = None
        self.flag = threading.Event()
        self.reason = ""
        self.lock = threading.Lock()
        self.done = threading.Event()
        self.started = False


_LIFE = _Lifetime()


def state() -> NodeState:
    """The node, or ROSInitException before ``init_node``."""
    found = _LIFE.state
    if found is None:
        raise ROSInitException("the node is not initialized: call rospy.init_node(name) first")
    return found


def current() -> NodeState | None:
    return _LIFE.state


def set_state(node_state: NodeState) -> None:
    _LIFE.state = node_state


def shutdown_event() -> threading.Event:
    return _LIFE.flag


def robomodel_node() -> Node:
    """The robomodel :class:`~robomodel.runtime.node.Node` behind this process's rospy node,
    once ``init_node`` ran (robomodel's addition to rospy's API: robomodel's own libraries,
    ``tf`` for one, work on it)."""
    return state().node


def is_shutdown() -> bool:
    """Whether the node is shutting down (or shut down)."""
    return _LIFE.flag.is_set()


def is_shutdown_requested() -> bool:
    return _LIFE.flag.is_set()


def on_shutdown(hook: Callable[[], Any]) -> None:
    """Call ``hook()`` when the node shuts down, before its topics and services go."""
    if not callable(hook):
        raise TypeError(f"on_shutdown needs a callable, got {hook!r}")
    node_state = _LIFE.state
    if _LIFE.flag.is_set():
        hook()  # as rospy: a hook added after shutdown runs at once
        return
    if node_state is None:
        _PENDING_HOOKS.append(hook)
    else:
        node_state.hooks.append(hook)


_PENDING_HOOKS: list[Callable[[], Any]] = []
_AFTER_TEARDOWN: list[Callable[[], None]] = []


def after_teardown(close: Callable[[], None]) -> None:
    """Call ``close()`` once the node's topics and services are gone (the callback threads
    stop then)."""
    _AFTER_TEARDOWN.append(close)


_DEFERRED: list[Callable[[NodeState], None]] = []


def defer(bind: Callable[[NodeState], None]) -> None:
    """Run ``bind(state)`` when ``init_node`` has made the node (a Publisher made before)."""
    _DEFERRED.append(bind)


def bind_deferred(node_state: NodeState) -> None:
    binds, _DEFERRED[:] = list(_DEFERRED), []
    for bind in binds:
        bind(node_state)


def pending_hooks() -> list[Callable[[], Any]]:
    hooks, _PENDING_HOOKS[:] = list(_PENDING_HOOKS), []
    return hooks


def signal_shutdown(reason: str) -> None:
    """Shut the node down: sleeps and ``spin()`` end, ``on_shutdown`` hooks run, then its
    publishers, subscribers and services leave the master."""
    with _LIFE.lock:
        first = not _LIFE.started
        _LIFE.started = True
        if first:
            _LIFE.reason = reason
            _LIFE.flag.set()
    if first:
        _teardown()
    elif not _in_teardown():  # a hook that signals shutdown again must not wait for itself
        _LIFE.done.wait(10.0)


_tearing = threading.local()


def _in_teardown() -> bool:
    return bool(getattr(_tearing, "on", False))


def _teardown() -> None:
    _tearing.on = True
    try:
        node_state = _LIFE.state
        hooks = (node_state.hooks if node_state is not None else []) + pending_hooks()
        for hook in hooks:
            try:
                hook()
            except Exception as exc:  # one hook's failure must not keep the others from running
                _emit(ERROR, f"on_shutdown hook {hook!r} failed: {exc}", None)
        if node_state is not None:
            node_state.context.shutdown()
        for close in _AFTER_TEARDOWN:
            close()
    finally:
        _tearing.on = False
        _LIFE.done.set()


def wait_for_teardown(timeout_s: float = 10.0) -> None:
    if _LIFE.started:
        _LIFE.done.wait(timeout_s)


def shutdown_reason() -> str:
    return _LIFE.reason


# -- names --------------------------------------------------------------------------------------
@functools.cache
def _unnamed() -> tuple[str, Mapping[str, str]]:
    """The caller id and remappings before ``init_node``: rospy reads ``sys.argv``'s at import
    and names the process ``<namespace>unnamed``."""
    from robomodel.clientlibs.rospy.names import (
        namespace_from,
        parse_command_line,
        resolve_remappings,
    )

    command_line = parse_command_line(sys.argv)
    caller_id = namespace_from(command_line.special) + "unnamed"
    return caller_id, resolve_remappings(command_line.remappings, caller_id)


def get_name() -> str:
    """The node's name with its namespace (``/ns/talker``); ``/unnamed`` before init_node."""
    node_state = _LIFE.state
    return node_state.caller_id if node_state is not None else _unnamed()[0]


get_caller_id = get_name


def get_namespace() -> str:
    """The node's namespace, with a trailing ``/``."""
    from robomodel.clientlibs.rospy.names import namespace_of

    return namespace_of(get_name())


def resolve_name(name: str, caller_id: str | None = None) -> str:
    """``name`` resolved as this node (or ``caller_id``) resolves it, remappings applied."""
    node_state = _LIFE.state
    remappings = node_state.remappings if node_state is not None else _unnamed()[1]
    return resolve(name, caller_id or get_name(), remappings)


# -- logging ------------------------------------------------------------------------------------
def _emit(level: int, text: str, frame: Any) -> None:
    node_state = _LIFE.state
    threshold = node_state.log_level if node_state is not None else INFO
    if level < threshold:
        return
    stamp = _now_s(node_state)
    stream = sys.stdout if level <= INFO else sys.stderr
    try:
        stream.write(f"[{_NAMES[level]}] [{stamp:.6f}]: {text}\n")
        stream.flush()
    except (OSError, ValueError):  # a closed console must not stop the node
        pass
    if node_state is None or (_LIFE.flag.is_set() and _LIFE.done.is_set()):
        return
    rosout = node_state.node.rosout
    if rosout is None:
        return
    where = inspect.getframeinfo(frame, context=0) if frame is not None else None
    rosout.publish(
        _PYTHON_LEVEL[level],
        text,
        file=where.filename if where else "",
        function=where.function if where else "",
        line=where.lineno if where else 0,
    )


def _now_s(node_state: NodeState | None) -> float:
    if node_state is None:
        return time.time()
    return node_state.node.get_clock().now_s()


def _text(msg: Any, args: tuple[Any, ...]) -> str:
    text = str(msg)
    return text % args if args else text


_once_sites: set[tuple[str, int, int]] = set()
_throttle_last: dict[tuple[str, int, int], float] = {}
_identical_last: dict[tuple[str, int, int], str] = {}


def _site(frame: Any) -> tuple[str, int, int]:
    """The call site, as rospy keys its throttles: file, line and bytecode offset."""
    return (frame.f_code.co_filename, frame.f_lineno, frame.f_lasti)


def _throttle_passes(site: tuple[str, int, int], period_s: float) -> bool:
    now = _now_s(_LIFE.state)
    last = _throttle_last.get(site)
    if last is None or now - last > period_s or last > now:  # time went back: log again
        _throttle_last[site] = now
        return True
    return False


def _log(
    level: int,
    msg: Any,
    args: tuple[Any, ...],
    kwargs: Mapping[str, Any],
    *,
    throttle_s: float | None = None,
    once: bool = False,
    identical: bool = False,
) -> None:
    unknown = set(kwargs) - {"logger_name"}
    if unknown:
        raise TypeError(f"unexpected keyword arguments {sorted(unknown)} (rospy takes logger_name)")
    frame = inspect.currentframe()
    caller = frame.f_back.f_back if frame is not None and frame.f_back is not None else None
    if caller is not None and (once or identical or throttle_s is not None):
        site = _site(caller)
        if once:
            if site in _once_sites:
                return
            _once_sites.add(site)
        elif identical:
            digest = hashlib.md5(str(msg).encode(), usedforsecurity=False).hexdigest()
            elapsed = throttle_s is not None and _throttle_passes(site, throttle_s)
            if _identical_last.get(site) == digest and not elapsed:
                return
            _identical_last[site] = digest
        elif throttle_s is not None and not _throttle_passes(site, throttle_s):
            return
    _emit(level, _text(msg, args), caller)


def _make_loggers(level: int) -> tuple[Callable[..., None], ...]:
    def plain(msg: Any, *args: Any, **kwargs: Any) -> None:
        _log(level, msg, args, kwargs)

    def throttle(period: float, msg: Any, *args: Any, **kwargs: Any) -> None:
        _log(level, msg, args, kwargs, throttle_s=float(period))

    def once(msg: Any, *args: Any, **kwargs: Any) -> None:
        _log(level, msg, args, kwargs, once=True)

    def identical(period: float, msg: Any, *args: Any, **kwargs: Any) -> None:
        _log(level, msg, args, kwargs, throttle_s=float(period), identical=True)

    return plain, throttle, once, identical


logdebug, logdebug_throttle, logdebug_once, logdebug_throttle_identical = _make_loggers(DEBUG)
loginfo, loginfo_throttle, loginfo_once, loginfo_throttle_identical = _make_loggers(INFO)
logwarn, logwarn_throttle, logwarn_once, logwarn_throttle_identical = _make_loggers(WARN)
logerr, logerr_throttle, logerr_once, logerr_throttle_identical = _make_loggers(ERROR)
logfatal, logfatal_throttle, logfatal_once, logfatal_throttle_identical = _make_loggers(FATAL)
logout = loginfo
logerror = logerr
