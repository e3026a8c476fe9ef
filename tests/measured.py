"""Processes under test, measured: the peak resident memory of a command (``os.wait4``'s
``ru_maxrss``) or of a running process (``VmHWM``), its thread count, and its output.

Hostile-input tests use these to show that a bound holds in the process that meets the input,
not only in the test's own process."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
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


# Linux keeps a process's peak RSS across execve (the exec records the replaced image's peak),
# and a child that subprocess starts is vforked from the pytest worker: its ru_maxrss was never
# below the worker's own peak (422 MiB after a long run), whatever robomodel used. A small
# Python process in between starts the command and reports the command's wait4, so the image
# the command replaces is this one's (about 10 MiB), not the worker's.
_MEASURER = """
import os, sys
pid = os.posix_spawn(sys.argv[2], sys.argv[2:], os.environ)
_, status, usage = os.wait4(pid, 0)
with open(sys.argv[1], "w") as report:
    report.write(f"{os.waitstatus_to_exitcode(status)} {usage.ru_maxrss}")
"""


def run_measured(*argv: str, env: dict[str, str] | None = None, timeout_s: float = 120) -> Measured:
    """Run ``robomodel *argv`` to its end; killed (and the test failed) after ``timeout_s``
    (scaled with the machine: :func:`tests.timing.scaled`)."""
    timeout_s = scaled(timeout_s)
    with (
        tempfile.TemporaryFile("w+") as out,
        tempfile.TemporaryFile("w+") as err,
        tempfile.TemporaryDirectory() as folder,
    ):
        report = Path(folder) / "report"
        command = [sys.executable, "-I", "-S", "-c", _MEASURER, str(report), *ROBOMODEL, *argv]
        proc = subprocess.Popen(
            command, stdout=out, stderr=err, env=env, text=True, start_new_session=True
        )
        timer = threading.Timer(timeout_s, lambda: os.killpg(proc.pid, signal.SIGKILL))
        timer.start()
        try:
            proc.wait()
        finally:
            timer.cancel()
        out.seek(0)
        err.seek(0)
        assert report.exists(), f"robomodel {' '.join(argv)}: not done in {timeout_s} s"
        code, max_rss_kib = (int(field) for field in report.read_text().split())
        return Measured(code, out.read(), err.read(), max_rss_kib * 1024)


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
