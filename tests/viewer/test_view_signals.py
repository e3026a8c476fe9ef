"""``robomodel view`` ends on Ctrl-C whichever of its threads the kernel hands the SIGINT to
(a process-wide signal goes to any thread that does not block it; Python runs its handler
only on the main thread, when that thread runs)."""

from __future__ import annotations

import ctypes
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.conftest import EXAMPLES, ROBOMODEL, end_process
from tests.timing import scaled, wait_until

_TGKILL = {"x86_64": 234, "aarch64": 131}  # tgkill's system call number


def _tgkill(pid: int, tid: int, signum: int) -> None:
    """Send ``signum`` to thread ``tid`` of process ``pid`` (Linux's tgkill)."""
    number = _TGKILL.get(os.uname().machine)
    if number is None:
        pytest.skip(f"tgkill's number is not known here ({os.uname().machine})")
    libc = ctypes.CDLL(None, use_errno=True)
    if libc.syscall(number, pid, tid, signum) != 0:
        raise OSError(ctypes.get_errno(), f"tgkill({pid}, {tid}, {signum})")


_FUTEX = {"x86_64": "202", "aarch64": "98"}  # futex's system call number


def _in_futex(pid: int) -> bool:
    """Whether the main thread of ``pid`` sleeps in a futex now and 50 ms later."""
    path = Path(f"/proc/{pid}/task/{pid}/syscall")
    futex = _FUTEX.get(os.uname().machine, "")
    first = path.read_text().split(" ", 1)[0]
    time.sleep(0.05)
    return first == futex and path.read_text().split(" ", 1)[0] == futex


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="tgkill is Linux's")
def test_view_ends_on_a_sigint_that_another_thread_received(tmp_path: Path) -> None:
    urdf = EXAMPLES / "gripper_description" / "urdf" / "planar_3dof.urdf"
    proc = subprocess.Popen(
        [*ROBOMODEL, "view", str(urdf), "--no-browser", "--port", "0", "--bus", "inproc"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    try:
        assert proc.stdout is not None
        line = proc.stdout.readline()
        assert "serving" in line, line + (proc.stderr.read() if proc.stderr else "")
        # the main thread waits for Ctrl-C once it sleeps in a futex (an Event's lock), there
        # after the serving line; a SIGINT before would end the start-up (exit 130)
        wait_until(lambda: _in_futex(proc.pid), 30, what="the viewer's main thread waiting")
        others = sorted(int(t) for t in os.listdir(f"/proc/{proc.pid}/task") if int(t) != proc.pid)
        assert others, "the viewer has threads besides its main one"
        _tgkill(proc.pid, others[-1], signal.SIGINT)
        code = proc.wait(timeout=scaled(30))
        assert code == 0, proc.stderr.read() if proc.stderr else ""
    finally:
        end_process(proc)
