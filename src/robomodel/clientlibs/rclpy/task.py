"""``rclpy.task``: :class:`Future` (a result that comes later) and :class:`Task` (a coroutine
run by an executor, resumed when a future it awaits is done).

A future made by robomodel's rclpy (``call_async``, ``send_goal_async``) is completed on any
thread and runs its done callbacks on the executor's thread, as rclpy schedules them; waking
the executor is part of completing it, so ``spin_until_future_complete`` returns at once.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Coroutine, Generator
from typing import Any

__all__ = ["Future", "Task"]

_PENDING, _DONE, _CANCELLED = "pending", "done", "cancelled"

# The future a coroutine stepped on this thread awaits (set by Future.__await__).
_awaiting = threading.local()


class Future:
    """The outcome of an asynchronous operation; ``await future`` in a coroutine callback."""

    def __init__(self, *, executor: Any = None) -> None:
        self._state = _PENDING
        self._result: Any = None
        self._exception: BaseException | None = None
        self._callbacks: list[Callable[[Future], None]] = []
        self._lock = threading.Lock()
        self._post: Callable[[Callable[[], None]], None] | None = None
        self._wake: Callable[[], None] | None = None
        if executor is not None:
            self._set_executor(executor)

    def _set_executor(self, executor: Any) -> None:
        self._post = executor._post  # an rclpy Executor's way onto its context's executor
        self._wake = executor.wake  # makes the executor (a context's: all) look again

    def __await__(self) -> Generator[None, None, Any]:
        # A bare yield, as rclpy's: asyncio's event loop accepts it too (an rclpy future
        # awaited in an asyncio coroutine). The Task running the coroutine learns which future
        # it waits for from _awaiting and goes on when that one is done.
        while not self.done():
            _awaiting.future = self
            yield
        return self.result()

    def cancel(self) -> None:
        """Cancel it, if not done yet (its done callbacks run)."""
        self._finish(_CANCELLED, None, None)

    def cancelled(self) -> bool:
        return self._state == _CANCELLED

    def done(self) -> bool:
        return self._state != _PENDING

    def result(self) -> Any:
        """The result (None until done); raises the exception it ended with."""
        if self._exception is not None:
            raise self._exception
        return self._result

    def exception(self) -> BaseException | None:
        return self._exception

    def set_result(self, result: Any) -> None:
        self._finish(_DONE, result, None)

    def set_exception(self, exception: BaseException) -> None:
        self._finish(_DONE, None, exception)

    def _finish(self, state: str, result: Any, exception: BaseException | None) -> None:
        with self._lock:
            if self._state != _PENDING:
                return
            self._result, self._exception, self._state = result, exception, state
            callbacks, self._callbacks = self._callbacks, []
        post, wake = self._post, self._wake
        for callback in callbacks:
            if post is None:
                callback(self)
            else:
                post(_bind(callback, self))
        if wake is not None:
            wake()  # a spin_until_future_complete waiting for work looks again

    def add_done_callback(self, callback: Callable[[Future], None]) -> None:
        """Call ``callback(future)`` when done (at once if it is)."""
        with self._lock:
            if self._state == _PENDING:
                self._callbacks.append(callback)
                return
        if self._post is None:
            callback(self)
        else:
            self._post(_bind(callback, self))

    def remove_done_callback(self, callback: Callable[[Future], None]) -> bool:
        with self._lock:
            if callback in self._callbacks:
                self._callbacks.remove(callback)
                return True
        return False


def _bind(callback: Callable[[Future], None], future: Future) -> Callable[[], None]:
    return lambda: callback(future)


class Task(Future):
    """Runs a coroutine (or a plain function) on an executor; done when it returns."""

    def __init__(
        self,
        handler: Callable[..., Any] | Coroutine[Any, Any, Any],
        args: tuple[Any, ...] = (),
        kwargs: dict[str, Any] | None = None,
        *,
        executor: Any = None,
    ) -> None:
        super().__init__(executor=executor)
        self._handler = handler
        self._args = args
        self._kwargs = kwargs or {}
        self._coroutine: Coroutine[Any, Any, Any] | None = None
        # A callback's or create_task's task: its exception leaves the executor's spin call,
        # as rclpy's executor raises a handler's exception (an action server's execute task
        # handles its own).
        self._fails_spin = False
        self._fail: Callable[[Exception], None] | None = getattr(executor, "fail", None)
        self._turn = threading.Lock()  # guards the two flags below
        self._running = False
        self._again = False  # asked to run while running: run once more when done

    def executing(self) -> bool:
        return self._running

    def __call__(self) -> None:
        """Run until the coroutine awaits something not done yet (or it ends). A call while
        another thread runs it is not lost: that thread runs it once more (a future it awaits
        may have completed in between)."""
        with self._turn:
            if self._running:
                self._again = True
                return
            self._running = True
        try:
            while True:
                if not self.done():
                    self._step()
                with self._turn:  # the check and the end are one step: no call slips between
                    if not self._again or self.done():
                        self._running = self._again = False
                        return
                    self._again = False
        except BaseException:
            with self._turn:
                self._running = False
            raise

    def _failed(self, exc: BaseException) -> None:
        self.set_exception(exc)
        if not isinstance(exc, Exception):  # KeyboardInterrupt, SystemExit: on, at once
            raise exc
        if self._fails_spin and self._fail is not None:
            self._fail(exc)

    def _step(self) -> None:
        if self._coroutine is None:
            if isinstance(self._handler, Coroutine):
                self._coroutine = self._handler
            else:
                try:
                    result = self._handler(*self._args, **self._kwargs)
                except BaseException as exc:
                    self._failed(exc)
                    return
                if not isinstance(result, Coroutine):
                    self.set_result(result)
                    return
                self._coroutine = result
        _awaiting.future = None
        try:
            self._coroutine.send(None)
        except StopIteration as stop:
            self.set_result(stop.value)
            return
        except BaseException as exc:
            self._failed(exc)
            return
        awaited, _awaiting.future = _awaiting.future, None
        post = self._post
        if isinstance(awaited, Future) and post is not None:
            awaited.add_done_callback(lambda _f: post(self))
        elif post is not None:
            post(self)  # a bare yield: go on at the executor's next turn
        else:
            raise RuntimeError("a Task awaiting a future needs an executor")
