"""Helpers shared by the Zenoh transport's modules."""

from __future__ import annotations

import ctypes
import functools
import logging
import threading
import time
from typing import TYPE_CHECKING, Any, Protocol

from robomodel.errors import MissingDependencyError

if TYPE_CHECKING:
    from collections.abc import Callable

    from robomodel.runtime.executor import Executor
    from robomodel.runtime.msg import Message
    from robomodel.runtime.msg.schema import Service
    from robomodel.runtime.transport.base import Endpoint
    from robomodel.runtime.transport.rmw_zenoh import EntityKind, EntityToken

__all__ = [
    "CLOSE_TIMEOUT_S",
    "ZenohSessionOwner",
    "close_session",
    "direct",
    "import_zenoh",
    "log",
    "release_freed_memory",
    "undeclare_all",
]

log = logging.getLogger("robomodel.runtime")


class ZenohSessionOwner(Protocol):
    """What the transport's publishers, subscriptions and services use of the
    :class:`~robomodel.runtime.transport.zenoh_bus.ZenohTransport` that makes them: its Zenoh
    session, executor, key and token naming and its once-only warnings."""

    @property
    def session(self) -> Any: ...

    @property
    def executor(self) -> Executor: ...

    def data_key(self, name: str, kind: type[Message] | type[Service]) -> str: ...

    def entity_token(
        self, endpoint: Endpoint, kind: EntityKind, type_: type[Message] | type[Service]
    ) -> EntityToken: ...

    def warn_once(self, key: tuple[str, ...], fmt: str, *args: object) -> None: ...


def import_zenoh() -> Any:
    try:
        import zenoh
        import zenoh.ext
    except ImportError:
        raise MissingDependencyError("eclipse-zenoh", "bus", "the zenoh bus") from None
    return zenoh


def undeclare_all(*handles: Any) -> None:
    """Undeclare Zenoh entities, in order; one already gone (session closed) is skipped."""
    for handle in handles:
        if handle is None:
            continue
        try:
            handle.undeclare()
        except Exception:
            log.debug("undeclare failed", exc_info=True)


@functools.cache
def _malloc_trim() -> Any:
    try:
        return ctypes.CDLL("libc.so.6").malloc_trim
    except (OSError, AttributeError):  # not glibc: nothing to do
        return None


def release_freed_memory() -> None:
    """Give the memory freed inside this process back to the system (glibc's ``malloc_trim``).

    Zenoh's routing tables live in the C heap: after 12,000 liveliness tokens of a peer came
    and went, a router process kept 51 MiB of the 23 it started with (measured), since glibc
    keeps freed pages for later; trimming brought it back to 26 MiB. A no-op off glibc.
    """
    trim = _malloc_trim()
    if trim is not None:
        trim(0)


def direct(callback: Any) -> Any:
    """``callback`` as a Zenoh handler run on Zenoh's own receiving thread.

    zenoh-python otherwise starts a Python thread per subscriber or queryable and hands each
    sample over to it: 120 threads and ~0.4 s for 20 nodes' parameter services, and a thread
    switch on every message. robomodel's callbacks only queue the sample for the executor.
    """
    zenoh = import_zenoh()
    # drop passed explicitly: zenoh-python 1.5 requires it despite its stub's default
    return zenoh.handlers.Callback(passing_interrupts(callback), None, indirect=False)


def passing_interrupts(callback: Any) -> Any:
    """``callback``, with Ctrl-C and SIGTERM handed back to the main thread.

    Zenoh delivers a local sample on the thread that put it, so a callback can run on the main
    thread (a launch's simulator publishing /clock); a KeyboardInterrupt raised there would be
    printed as a "callback error" and swallowed by zenoh-python, and Ctrl-C would not end the
    command. A signal that arrives in the callback is raised again a moment later: the command
    line's handlers (robomodel.cli.main) defer one that lands on this wrapper's own frame
    (:func:`defer_signal`), and one raised further in is caught here and deferred the same way.
    """

    def run(sample: Any) -> None:
        try:
            if _get_ident() not in _kept_thread_states:
                keep_thread_state()
            callback(sample)
        except KeyboardInterrupt as exc:
            defer_signal(_signal_of(exc))

    return run


_get_ident = threading.get_ident
_kept_thread_states: set[int] = set()


def keep_thread_state() -> None:
    """Keep the Python thread state of the (Zenoh) thread this runs on from one callback to
    the next.

    zenoh-python enters Python from its own threads through ``PyGILState_Ensure`` and leaves
    through ``PyGILState_Release``, and a thread that Python did not start has its thread
    state made by the first and destroyed by the second: every sample paid for a new thread
    state and its frame stack (CPython maps and unmaps a 16 KiB chunk for it), about 20 us of
    each message's way at 1 kHz. One more ``PyGILState_Ensure``,
    never released, keeps the thread state's count above zero, so the release after each
    callback only lets the GIL go; the state stays with its thread as a Python thread's
    does. On a thread that Python started, or the main thread, it only counts one more.
    Once per thread; CPython only (elsewhere nothing is done).
    """
    ident = _get_ident()
    if ident in _kept_thread_states or len(_kept_thread_states) > _MAX_KEPT:
        return
    _kept_thread_states.add(ident)
    ensure = getattr(getattr(ctypes, "pythonapi", None), "PyGILState_Ensure", None)
    if ensure is not None:
        ensure()


_MAX_KEPT = 4096  # thread identifiers remembered (a thread's is reused after it ends)


CALLBACK_CODE = passing_interrupts(print).__code__
"""The code of every Zenoh callback's wrapper: a signal handler that finds it running defers."""
_deferred: list[int] = []
_delivering = [False]  # a helper thread is on its way to raise the deferred signals


def _signal_of(exc: BaseException) -> int:
    import signal

    terminated = type(exc).__name__ == "Terminated"  # robomodel.cli.main's SIGTERM
    return int(signal.SIGTERM if terminated else signal.SIGINT)


def defer_signal(signum: int) -> None:
    """Raise ``signum`` in the main thread again a moment later, from a helper thread: raised
    at once it would land in the wrapper's frame again.

    The helper is started here, not when the callback returns: a signal can land on the
    wrapper's frame after its last look (on its way out), and was then never raised again
    (seen under load: Ctrl-C lost). If the signal lands on a wrapper again, it is deferred
    again. Each deferred signal is raised once (popped), whichever helper gets it.
    """
    if signum not in _deferred:
        _deferred.append(signum)
    if not _delivering[0]:
        _delivering[0] = True
        threading.Thread(target=_deliver_later, name="robomodel-signal", daemon=True).start()


def _deliver_later() -> None:
    import _thread
    import signal

    while True:
        time.sleep(0.01)
        while _deferred:
            try:
                signum = _deferred.pop(0)
            except IndexError:  # another helper took it
                break
            _thread.interrupt_main(signal.Signals(signum))
        _delivering[0] = False
        if not _deferred:  # one deferred after the pops and before the flag fell: go again
            return
        _delivering[0] = True


CLOSE_TIMEOUT_S = 5.0
abandoned_sessions = 0  # sessions whose close() did not return (robomodel.cli.main exits hard)


def close_session(
    session: Any, timeout_s: float = CLOSE_TIMEOUT_S, before: Callable[[], None] | None = None
) -> bool:
    """``before()`` (the session's undeclarations) then ``session.close()``, waited for at most
    ``timeout_s`` together; False if they did not return.

    Zenoh's runtime has been seen to panic in a routing task while peers go away (a
    ``PoisonError`` in its demultiplexer), and ``close()`` then never returns: the process
    that is ending would hang on Ctrl-C. An undeclaration waits on the same runtime, so it runs
    on the same daemon thread, under the same bound. A session left behind is counted, so that
    the command line can exit without waiting for it.
    """
    global abandoned_sessions
    done = threading.Event()

    def run() -> None:
        try:
            if before is not None:
                before()
            session.close()
        except Exception:
            log.debug("closing the Zenoh session failed", exc_info=True)
        finally:
            done.set()

    threading.Thread(target=run, name="robomodel-zenoh-close", daemon=True).start()
    if done.wait(timeout_s):
        return True
    abandoned_sessions += 1
    log.warning("the Zenoh session did not close within %g s; leaving it", timeout_s)
    return False
