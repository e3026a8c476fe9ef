"""Waiting for a bridge process's start line, failing at once (with its log) if it ends."""

from __future__ import annotations

import subprocess
from pathlib import Path
from typing import Any

from tests.timing import wait_until


def wait_started(proc: subprocess.Popen[Any], log: Path, text: str) -> None:
    """Until ``log`` shows ``text``; an AssertionError with the log if ``proc`` ends first (a
    port taken meanwhile, a bad argument)."""

    def started() -> bool:
        if text in log.read_text():
            return True
        if proc.poll() is not None:
            raise AssertionError(f"the bridge ended ({proc.returncode}): {log.read_text()}")
        return False

    wait_until(started, 60, what=lambda: f"the bridge's start line; its log: {log.read_text()}")
