"""A bound on a close that may never return: ``ends_process_after``.

A Zenoh runtime that panicked while peers went away can block an undeclaration or a session
close for good. A long-running verb (``launch``, ``view``) closes its bus inside this bound so
that Ctrl-C always ends it: past the bound it prints one line and every thread's stack to
stderr (where it waited, for a bug report) and ends the process at once.
"""

from __future__ import annotations

import contextlib
import faulthandler
import os
import sys
import threading
from collections.abc import Iterator

__all__ = ["ends_process_after"]


@contextlib.contextmanager
def ends_process_after(bound_s: float, line: str, exit_code: int) -> Iterator[None]:
    """Run the ``with`` body; if it has not finished within ``bound_s``, print ``line`` and the
    threads' stacks to stderr and end the process with ``exit_code`` (``os._exit``: the hung
    thread cannot be unwound, and the caller starts nothing that could be left behind)."""
    watchdog = threading.Timer(bound_s, _end_process, args=(line, exit_code))
    watchdog.daemon = True
    watchdog.start()
    try:
        yield
    finally:
        watchdog.cancel()


def _end_process(line: str, exit_code: int) -> None:
    print(f"{line}. Its threads:", file=sys.stderr, flush=True)
    faulthandler.dump_traceback(file=sys.stderr, all_threads=True)
    sys.stderr.flush()
    os._exit(exit_code)
