"""Ctrl-C that arrives while a Zenoh callback runs on the main thread still ends the command."""

from __future__ import annotations

import pytest

from robomodel.runtime.transport._zenoh_common import passing_interrupts


def _interrupted(_sample: object) -> None:
    raise KeyboardInterrupt


def test_a_keyboard_interrupt_in_a_callback_is_raised_again_on_the_main_thread() -> None:
    wrapped = passing_interrupts(_interrupted)
    with pytest.raises(KeyboardInterrupt):
        wrapped(None)  # returns normally to Zenoh; the signal is pending for the main thread
        for _ in range(1_000_000):  # the next bytecodes of the main thread raise it
            pass


def test_other_callbacks_run_unchanged() -> None:
    seen: list[object] = []
    passing_interrupts(seen.append)("sample")
    assert seen == ["sample"]
