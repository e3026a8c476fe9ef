"""SIGTERM to an rclpy program, as ``kill``, a launch ending or a container stopping send it:
the tutorial talker (tests/clientlibs/rclpy/nodes/) run as a script, on the in-process bus (no
Zenoh: the signal handling is the point). As rclpy's handler: the context stops, ``spin`` raises
``ExternalShutdownException``, which the tutorial's ``except`` catches, and the program ends
cleanly (exit code 0) instead of being killed by the signal."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

from tests.conftest import end_process

TALKER = Path(__file__).with_name("nodes") / "publisher_member_function.py"


def test_sigterm_ends_an_rclpy_program_through_external_shutdown() -> None:
    env = {**os.environ, "ROBOMODEL_RCLPY_BUS": "inproc"}
    proc = subprocess.Popen(
        [sys.executable, str(TALKER)], env=env, stderr=subprocess.PIPE, text=True
    )
    assert proc.stderr is not None
    assert 'Publishing: "Hello World: 0"' in proc.stderr.readline()  # spinning now
    assert end_process(proc, signal.SIGTERM, timeout_s=10.0) == 0
    rest = proc.stderr.read().splitlines()
    assert all("]: Publishing: " in line for line in rest), rest[-5:]  # no traceback
