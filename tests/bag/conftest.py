"""Processes for the bag tests: a publisher of a known /joint_states sequence, the CLI."""

from __future__ import annotations

import signal
import subprocess
import sys
import textwrap
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.conftest import ROBOMODEL, unique_domain

TALKER = textwrap.dedent(
    """
    import sys
    from robomodel.runtime import Context, latched
    from robomodel.runtime.msg import Header, JointState, String, Time
    ctx = Context("zenoh", domain_id=int(sys.argv[1]))
    limit = int(sys.argv[2])
    period_s = float(sys.argv[3])
    node = ctx.create_node("talker")
    pub = node.create_publisher(JointState, "/joint_states")
    node.create_publisher(String, "/robot_description", latched()).publish(String("<robot/>"))
    count = [0]
    def tick():
        if limit and count[0] >= limit:
            return
        count[0] += 1
        k = count[0]
        pub.publish(JointState(
            header=Header(Time(k, 1000 * k), "base"),
            name=["a", "b"], position=[0.1 * k, -0.5 * k], velocity=[float(k)], effort=[],
        ))
    node.create_timer(period_s, tick)
    print("ready", flush=True)
    try:
        ctx.spin()
    except KeyboardInterrupt:
        pass
    ctx.shutdown()
    """
)


def run_cli(*args: str, timeout: float = 30) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*ROBOMODEL, *args], capture_output=True, text=True, timeout=timeout)


def stop(proc: subprocess.Popen[str], sig: int = signal.SIGTERM) -> None:
    if proc.poll() is None:
        proc.send_signal(sig)
        try:
            proc.wait(10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


class Talker:
    def __init__(self, tmp_path: Path, *, limit: int = 0, period_s: float = 0.01) -> None:
        script = tmp_path / "talker.py"
        script.write_text(TALKER)
        self.domain = unique_domain()
        self.proc = subprocess.Popen(
            [sys.executable, str(script), self.domain, str(limit), str(period_s)],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        assert self.proc.stdout is not None and self.proc.stdout.readline().strip() == "ready"


@pytest.fixture
def talker(tmp_path: Path) -> Iterator[Talker]:
    started = Talker(tmp_path)
    yield started
    stop(started.proc)
