"""Ctrl-C that arrives while a Zenoh callback runs on the main thread still ends the command.

Zenoh delivers a local sample on the thread that put it; zenoh-python swallows what a callback
raises (it prints "callback error"), so a KeyboardInterrupt raised in one would be lost.
"""

from __future__ import annotations

import signal
import sys

import pytest

from robomodel.cli import main as cli_main
from robomodel.runtime.transport import _zenoh_common
from robomodel.runtime.transport._zenoh_common import CALLBACK_CODE, passing_interrupts


def _interrupted(_sample: object) -> None:
    raise KeyboardInterrupt


def _spin_until_raised() -> None:
    for _ in range(2_000):  # the main thread's next bytecodes raise it, once re-delivered
        for _ in range(1_000):
            pass
        import time

        time.sleep(0.001)


def test_a_keyboard_interrupt_raised_in_a_callback_is_raised_again_after_it() -> None:
    wrapped = passing_interrupts(_interrupted)
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)  # Python's, at start
    try:
        with pytest.raises(KeyboardInterrupt):
            wrapped(None)  # returns normally to Zenoh; the signal comes back a moment later
            _spin_until_raised()
    finally:
        signal.signal(signal.SIGINT, previous)


def test_a_signal_landing_on_the_wrapper_frame_is_deferred_not_raised() -> None:
    """The command line's handler, called with the wrapper's frame (where the interpreter
    checks for signals on entry), defers instead of raising into zenoh-python; the signal is
    raised again a moment later, with no further call of the wrapper (it may have been on its
    way out: under load a Ctrl-C landing there was lost)."""
    frame = type("Frame", (), {"f_code": CALLBACK_CODE})()
    previous = signal.signal(signal.SIGINT, cli_main._raise_interrupt)
    try:
        with pytest.raises(KeyboardInterrupt):
            cli_main._raise_interrupt(signal.SIGINT, frame)  # no exception here: deferred
            _spin_until_raised()
        assert not _zenoh_common._deferred
    finally:
        signal.signal(signal.SIGINT, previous)
        _zenoh_common._deferred.clear()
    with pytest.raises(KeyboardInterrupt):
        cli_main._raise_interrupt(signal.SIGINT, sys._getframe())  # elsewhere: raised at once


def test_a_signal_deferred_on_a_wrapper_frame_again_is_raised_later() -> None:
    """Redelivered while a wrapper runs again, the signal is deferred again, then raised."""
    frame = type("Frame", (), {"f_code": CALLBACK_CODE})()
    previous = signal.signal(signal.SIGINT, cli_main._raise_interrupt)
    landed: list[bool] = []

    def handler(signum: int, current: object) -> None:
        landed.append(True)
        # the first redelivery finds a wrapper running again; the next one raises
        cli_main._raise_interrupt(signum, frame if len(landed) == 1 else current)

    try:
        signal.signal(signal.SIGINT, handler)
        with pytest.raises(KeyboardInterrupt):
            cli_main._raise_interrupt(signal.SIGINT, frame)
            _spin_until_raised()
        assert len(landed) == 2
    finally:
        signal.signal(signal.SIGINT, previous)
        _zenoh_common._deferred.clear()


def test_other_callbacks_run_unchanged() -> None:
    seen: list[object] = []
    passing_interrupts(seen.append)("sample")
    assert seen == ["sample"]
