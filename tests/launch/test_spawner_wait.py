"""Both dialects' spawners wait for their controller manager through one poll loop."""

from __future__ import annotations

import threading
import time
from types import SimpleNamespace
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.launch.nodes.controllers import wait_for_manager


class _Runtime:
    """Answers ``list_controllers`` from the ``answer_after``-th call on; refuses before."""

    def __init__(self, answer_after: int | None) -> None:
        self.answer_after = answer_after
        self.calls: list[tuple[str, float]] = []

    def call_service(self, name: str, srv_type: Any, request: Any, timeout_s: float) -> Any:
        self.calls.append((name, timeout_s))
        if self.answer_after is None or len(self.calls) < self.answer_after:
            raise RobomodelError(f"service '{name}' not found")
        return srv_type.Response()


def _wait(runtime: _Runtime, timeout_s: float, stopping: threading.Event | None = None, **kw: Any):  # type: ignore[no-untyped-def]
    ctx = SimpleNamespace(runtime=runtime)
    node = SimpleNamespace(stopping=stopping or threading.Event())
    return wait_for_manager(ctx, node, "/ns/controller_manager", timeout_s, **kw)  # type: ignore[arg-type]


def test_ready_once_list_controllers_answers() -> None:
    runtime = _Runtime(answer_after=3)
    assert _wait(runtime, 5.0, call_timeout_s=2.0) is True
    assert runtime.calls == [("/ns/controller_manager/list_controllers", 2.0)] * 3


def test_times_out_without_a_manager() -> None:
    start = time.monotonic()
    assert _wait(_Runtime(answer_after=None), 0.3) is False
    assert 0.3 <= time.monotonic() - start < 3.0


def test_zero_timeout_waits_until_stopped_when_asked_to() -> None:
    stopping = threading.Event()
    threading.Timer(0.5, stopping.set).start()
    runtime = _Runtime(answer_after=None)
    assert _wait(runtime, 0.0, stopping, zero_waits_forever=True) is None  # stopped, not timed out
    assert len(runtime.calls) >= 2
    assert _wait(_Runtime(answer_after=None), 0.0) is False  # ROS 1: 0 s is no wait
