"""A bus spun by a thread of its own, as a launch's loop spins its bus, for the tests of a
bridge made in this process."""

from __future__ import annotations

import contextlib
import threading
from collections.abc import Iterator

from robomodel.runtime import Context
from tests.timing import scaled


@contextlib.contextmanager
def spun(context: Context) -> Iterator[Context]:
    """``context``, spun by a thread until the block ends; then the thread ends and the
    context is shut down."""
    stop = threading.Event()
    spinner = threading.Thread(target=lambda: context.spin(until=stop.is_set), daemon=True)
    spinner.start()
    try:
        yield context
    finally:
        stop.set()
        context.executor.post(lambda: None)  # wakes the spin to see the event
        spinner.join(timeout=scaled(5))
        context.shutdown()
