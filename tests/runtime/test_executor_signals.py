"""The executor's wait ends: after a signal handler that outlasts it, and on a post from another
thread.

On CPython 3.11 and 3.12, ``queue.SimpleQueue.get(timeout=...)`` blocks forever when a signal
handler runs past the deadline (its loop recomputes a negative timeout, which means "no
timeout"). The executor waited there, so a Ctrl-C or SIGTERM landing near the end of a wait left
``robomodel log`` (and any spinning command) hung, ignoring every later signal.
"""

from __future__ import annotations

import subprocess
import sys
import textwrap
import threading

from robomodel.runtime.executor import Executor
from tests.timing import scaled

_HANDLER_OUTLASTS_THE_WAIT = textwrap.dedent(
    """
    import signal, time
    from robomodel.runtime.executor import Executor

    executor = Executor()
    seen = []
    signal.signal(signal.SIGALRM, lambda *_: (time.sleep(0.1), seen.append(True)))
    signal.setitimer(signal.ITIMER_REAL, 0.01)  # during the wait, the handler ends after it
    executor.spin_once(0.05)
    print("returned", bool(seen))
    """
)


def test_a_wait_ends_after_a_signal_handler_that_outlasts_it() -> None:
    try:
        done = subprocess.run(
            [sys.executable, "-c", _HANDLER_OUTLASTS_THE_WAIT],
            capture_output=True,
            text=True,
            timeout=scaled(30),
        )
    except subprocess.TimeoutExpired:
        raise AssertionError("spin_once never returned after the signal") from None
    assert done.returncode == 0, done.stderr
    assert done.stdout == "returned True\n"


def test_a_post_from_another_thread_wakes_a_long_wait() -> None:
    executor = Executor()
    ran: list[str] = []
    counts: list[int] = []
    spinner = threading.Thread(target=lambda: counts.append(executor.spin_once(scaled(600))))
    spinner.start()
    executor.post(lambda: ran.append("posted"))
    spinner.join(scaled(60))
    assert not spinner.is_alive(), "the post did not wake the waiting spin_once"
    assert ran == ["posted"] and counts == [1]


def test_posts_from_threads_all_run_in_their_order() -> None:
    executor = Executor()
    ran: list[tuple[int, int]] = []
    total = 4 * 500

    def produce(thread: int) -> None:
        for index in range(500):
            executor.post(lambda t=thread, i=index: ran.append((t, i)))

    producers = [threading.Thread(target=produce, args=(t,)) for t in range(4)]
    for producer in producers:
        producer.start()
    executor.spin(duration_s=scaled(60), until=lambda: len(ran) == total)
    for producer in producers:
        producer.join()
    assert len(ran) == total
    for thread in range(4):
        assert [i for t, i in ran if t == thread] == list(range(500))
