"""Processes under test, measured: the peak resident memory of a command (``os.wait4``'s
``ru_maxrss``) or of a running process (``VmHWM``), its thread count, and its output.

Hostile-input tests use these to show that a bound holds in the process that meets the input,
not only in the test's own process."""

from __future__ import annotations

import os
import subprocess
import tempfile
import threading
from dataclasses import dataclass
from pathlib import Path

from tests.conftest import ROBOMODEL
from tests.timing import scaled

MIB = 1 << 20


@dataclass(frozen=True)
class Measured:
    """A finished command: exit code, stdout, stderr and peak RSS [bytes]."""

    code: int
    out: str
    err: str
    peak_rss_bytes: int


def run_measured(*argv: str, env: dict[str, str] | None = None, timeout_s: float = 120) -> Measured:
    """Run ``robomodel *argv`` to its end; killed (and the test failed) after ``timeout_s``
    (scaled with the machine: :func:`tests.timing.scaled`)."""
    timeout_s = scaled(timeout_s)
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        proc = subprocess.Popen([*ROBOMODEL, *argv], stdout=out, stderr=err, env=env, text=True)
        timer = threading.Timer(timeout_s, proc.kill)
        timer.start()
        try:
            _, status, usage = os.wait4(proc.pid, 0)
        finally:
            timer.cancel()
        proc.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        assert proc.returncode != -9, f"robomodel {' '.join(argv)}: not done in {timeout_s} s"
        return Measured(proc.returncode, out.read(), err.read(), usage.ru_maxrss * 1024)


def _status(pid: int, field: str) -> int:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith(field + ":"):
            return int(line.split()[1])
    raise AssertionError(f"/proc/{pid}/status has no {field}")


def peak_rss_bytes(pid: int) -> int:
    """The peak resident memory of a running process so far (``VmHWM``)."""
    return _status(pid, "VmHWM") * 1024


def thread_count(pid: int) -> int:
    return _status(pid, "Threads")
