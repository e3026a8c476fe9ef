"""Debian 12's real ROS 1 as the other side of robomodel's ROS 1 wire: roscore, rostopic,
rosparam, rosnode, rosservice, rosbag, rviz and the C++ robot_state_publisher, installed by
``tools/system-deps test``. Every process a test starts runs in a process group of its own and
is ended (SIGINT, then SIGKILL) when the test ends."""

from __future__ import annotations

import http.client
import os
import shutil
import subprocess
import xmlrpc.client
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import EXAMPLES, ROBOMODEL, end_process, free_port
from tests.timing import scaled, wait_until

ROSCORE = "/usr/bin/roscore"


@dataclass
class Ros1:
    """One ROS 1 graph for a test: its master's URI, the environment of every process, the
    processes started."""

    home: Path
    port: int = field(default_factory=free_port)
    procs: list[subprocess.Popen[str]] = field(default_factory=list)

    @property
    def uri(self) -> str:
        return f"http://127.0.0.1:{self.port}/"

    @property
    def env(self) -> dict[str, str]:
        return {
            **{k: v for k, v in os.environ.items() if not k.startswith("ROS")},
            "ROS_MASTER_URI": self.uri,
            "ROS_PACKAGE_PATH": f"{EXAMPLES}:/usr/share",
            "ROS_HOME": str(self.home / ".ros"),
            "HOME": str(self.home),
            "ROS_IP": "127.0.0.1",
            "PYTHONUNBUFFERED": "1",
            "LANG": "C.UTF-8",
        }

    def start(self, argv: list[str], log: Path | None = None) -> subprocess.Popen[str]:
        out = log.open("w") if log is not None else subprocess.DEVNULL
        proc = subprocess.Popen(
            argv,
            stdout=out,
            stderr=subprocess.STDOUT,
            text=True,
            env=self.env,
            start_new_session=True,
        )
        self.procs.append(proc)
        return proc

    def robomodel(self, *argv: str, log: Path | None = None) -> subprocess.Popen[str]:
        return self.start([*ROBOMODEL, *argv], log)

    def robomodel_run(
        self, *argv: str, timeout: float | None = None
    ) -> subprocess.CompletedProcess[str]:
        return self.run(*ROBOMODEL, *argv, timeout=scaled(60) if timeout is None else timeout)

    def run(
        self, *argv: str, timeout: float | None = None, cwd: Path | None = None
    ) -> subprocess.CompletedProcess[str]:
        timeout = scaled(30) if timeout is None else timeout
        return subprocess.run(
            list(argv), capture_output=True, text=True, env=self.env, timeout=timeout, cwd=cwd
        )

    def until(self, check: Callable[[], bool], what: str, timeout_s: float = 60.0) -> None:
        """``wait_until`` at the pace of a ROS 1 tool's call (``timeout_s`` is scaled)."""
        wait_until(check, timeout_s, what=what, interval_s=0.3)

    def master(self) -> xmlrpc.client.ServerProxy:
        """An XML-RPC client of this graph's master whose calls give up after a scaled 10 s."""
        return xmlrpc.client.ServerProxy(self.uri, transport=_TimedTransport(scaled(10)))

    def master_answers(self) -> bool:
        """Whether the master answers and has ``/run_id`` (set by roscore's roslaunch and by
        ``robomodel master`` once it serves): what ``rosparam get /run_id`` asks, as one call
        from this process instead of a Python start of Debian's tool at each try of a wait."""
        try:
            with self.master() as master:
                code, _, _ = master.getParam("/test", "/run_id")
        except (OSError, http.client.HTTPException, xmlrpc.client.Error):
            return False
        return bool(code == 1)

    def wait_for_master(self, what: str = "master") -> None:
        self.until(self.master_answers, what)

    def names(self, kind: str) -> set[str]:
        """What ``rostopic list``, ``rosservice list`` or ``rosnode list`` would list (``kind``
        ``"topics"``, ``"services"`` or ``"nodes"``), from the master's ``getSystemState`` in
        this process: for waits that need a name to appear, not the tool's output."""
        with self.master() as master:
            code, message, (publishers, subscribers, services) = master.getSystemState("/test")
        assert code == 1, message
        entries = {"topics": publishers + subscribers, "services": services}.get(kind)
        if entries is not None:
            return {name for name, _nodes in entries}
        assert kind == "nodes", kind
        return {node for name, nodes in publishers + subscribers + services for node in nodes}

    def roscore(self) -> subprocess.Popen[str]:
        """A real roscore, once its master answers and its /rosout node is registered (roslaunch
        sets /run_id before it starts rosout)."""
        proc = self.start([ROSCORE, "-p", str(self.port)])
        self.until(lambda: self.master_answers() and "/rosout" in self.names("nodes"), "roscore")
        return proc

    def stop(self, proc: subprocess.Popen[str], timeout_s: float | None = None) -> int:
        return end_process(proc, timeout_s=20 if timeout_s is None else timeout_s, group=True)

    def close(self) -> None:
        for proc in reversed(self.procs):
            self.stop(proc)


class _TimedTransport(xmlrpc.client.Transport):
    """xmlrpc.client's transport with a timeout on its connection (it has none)."""

    def __init__(self, timeout_s: float) -> None:
        super().__init__()
        self._timeout_s = timeout_s

    def make_connection(self, host: Any) -> http.client.HTTPConnection:
        connection = super().make_connection(host)
        connection.timeout = self._timeout_s
        return connection


@pytest.fixture
def ros1(tmp_path: Path) -> Iterator[Ros1]:
    for tool in (ROSCORE, "/usr/bin/rostopic", "/usr/bin/rosparam", "/usr/bin/rosnode"):
        if not Path(tool).exists():
            pytest.fail(f"Debian's ROS 1 is missing ({tool}): tools/system-deps test installs it")
    graph = Ros1(tmp_path)
    try:
        yield graph
    finally:
        graph.close()


def has(tool: str) -> bool:
    return shutil.which(tool) is not None
