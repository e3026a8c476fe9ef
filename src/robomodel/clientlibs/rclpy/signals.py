"""``rclpy.signals``: the signal handlers ``rclpy.init`` installs.

As rclpy's (Jazzy's signal_handler.cpp): on SIGINT or SIGTERM every context initialised with
handlers stops being ``ok()``, then the handler that was there before runs if it is a Python
function: for SIGINT Python's own, raising ``KeyboardInterrupt`` in the main thread; for SIGTERM
usually none (the default action, ending the process, is not taken), so a single-threaded
executor's spin raises ``ExternalShutdownException`` and a multi-threaded one's returns.
``rclpy.init`` installs both for the default context (``SignalHandlerOptions.ALL``; ``SIGINT``
or ``SIGTERM`` alone as asked) and ``shutdown`` of the last such context restores the previous
ones. Python lets only the main thread install handlers: from another thread none are
installed, as ``SignalHandlerOptions.NO``.
"""

from __future__ import annotations

import enum
import signal
import threading
import weakref
from types import FrameType
from typing import Any, Protocol

__all__ = [
    "SignalHandlerOptions",
    "get_current_signal_handlers_options",
    "install_signal_handlers",
    "uninstall_signal_handlers",
]


class SignalHandlerOptions(enum.IntEnum):
    NO = 0
    SIGINT = 1
    SIGTERM = 2
    ALL = 3


class _Interruptible(Protocol):
    def interrupt(self) -> None: ...


_previous: dict[int, Any] = {}  # signal number -> the handler installed before rclpy's
_options = SignalHandlerOptions.NO
_contexts: weakref.WeakSet[Any] = weakref.WeakSet()  # what SIGINT shuts down
_lock = threading.Lock()


def _on_signal(signum: int, frame: FrameType | None) -> None:
    for context in list(_contexts):
        context.interrupt()
    previous = _previous.get(signum)
    if callable(previous):  # SIG_DFL and SIG_IGN are not: rclpy does not chain to them
        previous(signum, frame)  # for SIGINT Python's default_int_handler: KeyboardInterrupt


_HANDLED: dict[SignalHandlerOptions, tuple[signal.Signals, ...]] = {
    SignalHandlerOptions.SIGINT: (signal.SIGINT,),
    SignalHandlerOptions.SIGTERM: (signal.SIGTERM,),
    SignalHandlerOptions.ALL: (signal.SIGINT, signal.SIGTERM),
}


def install_signal_handlers(options: SignalHandlerOptions = SignalHandlerOptions.ALL) -> None:
    """Install rclpy's handler for SIGINT and SIGTERM (``ALL``), or one of them; nothing with
    ``NO`` or off the main thread."""
    global _options
    options = SignalHandlerOptions(options)
    if options == SignalHandlerOptions.NO:
        return
    if threading.current_thread() is not threading.main_thread():
        return
    with _lock:
        for signum in _HANDLED[options]:
            if signum not in _previous:
                _previous[signum] = signal.signal(signum, _on_signal)
        _options = SignalHandlerOptions(
            SignalHandlerOptions.SIGINT * (signal.SIGINT in _previous)
            + SignalHandlerOptions.SIGTERM * (signal.SIGTERM in _previous)
        )


def get_current_signal_handlers_options() -> SignalHandlerOptions:
    return _options if _previous else SignalHandlerOptions.NO


def uninstall_signal_handlers() -> None:
    """Put back the handlers that were there before rclpy's."""
    global _options
    if threading.current_thread() is not threading.main_thread():
        return
    with _lock:
        for signum, previous in list(_previous.items()):
            if signal.getsignal(signum) is _on_signal:
                signal.signal(signum, previous if previous is not None else signal.SIG_DFL)
            del _previous[signum]
        _options = SignalHandlerOptions.NO


def _watch(context: _Interruptible) -> None:
    """SIGINT and SIGTERM interrupt ``context`` from now on."""
    _contexts.add(context)


def _forget(context: _Interruptible) -> None:
    """``context`` shut down; the handlers go when no watched context is left."""
    _contexts.discard(context)
    if not _contexts and _previous:
        uninstall_signal_handlers()
