"""A user's own node (an rclpy or rospy program of their package) as a child process.

The command line is the one ROS builds for the node:

- ROS 1 (roslaunch's ``nodeprocess``): the node's ``args``, its remaps ``from:=to``, then
  ``__name:=NAME`` and ``__ns:=NS``; ``ROS_NAMESPACE`` and ``ROS_MASTER_URI`` in its
  environment. Its parameters are on the master, where the launch set them.
- ROS 2 (launch_ros's ``Node``): its ``arguments``, then ``--ros-args`` with ``-r __node:=``,
  ``-r __ns:=``, ``-r from:=to``, a ``--params-file`` per parameter source (values are written
  to a temporary file, as launch_ros does) and its ``ros_arguments``.

The child runs with robomodel's interpreter, ``ROBOMODEL_MESSAGE_FLAVOUR`` set to the flavour of
its package (genpy for catkin, rosidl for ament), unbuffered output, in a process group of its
own (ended as a group, as roslaunch ends its nodes). Its standard error is always shown
(a traceback appears as the node printed it), its standard output when ``output="screen"``
(ROS 2's launch: ``log`` keeps stdout in the node's log file); each line prefixed with the
node's name as ``ros2 launch`` prefixes it (``[talker-1]``). When it ends the launch says so as
ROS does (``process has died [pid, exit code, cmd]``).
"""

from __future__ import annotations

import contextlib
import os
import subprocess
import sys
import tempfile
import threading
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import IO, Any

from robomodel.launch.executables import UserExecutable
from robomodel.launch.model import NodeSpec
from robomodel.launch.processes import end_group

__all__ = [
    "UserNodeProcess",
    "node_command",
    "node_environment",
    "process_label",
    "ros_log_dir",
    "run_foreground",
]


def ros_log_dir(environ: Mapping[str, str] = os.environ) -> Path:
    """ROS's log folder: ``ROS_LOG_DIR``, else ``ROS_HOME/log``, else ``~/.ros/log``."""
    if environ.get("ROS_LOG_DIR"):
        return Path(environ["ROS_LOG_DIR"])
    home = environ.get("ROS_HOME") or os.path.join(os.path.expanduser("~"), ".ros")
    return Path(home) / "log"


def _params_file(values: Mapping[str, Any], temporary: list[Path]) -> Path:
    """A ROS 2 parameters file holding ``values`` for every node (``/**``), as launch_ros writes
    a Node's ``parameters=[{...}]``; removed when the node is stopped."""
    import yaml

    descriptor, name = tempfile.mkstemp(prefix="launch_params_", suffix=".yaml")
    with os.fdopen(descriptor, "w", encoding="utf-8") as handle:
        yaml.safe_dump({"/**": {"ros__parameters": dict(values)}}, handle)
    temporary.append(Path(name))
    return Path(name)


def node_command(
    spec: NodeSpec,
    executable: UserExecutable,
    *,
    python: str = sys.executable,
    temporary: list[Path] | None = None,
) -> list[str]:
    """The node's command line as roslaunch (ROS 1) or launch_ros (ROS 2) builds it."""
    words = [*executable.command(python), *spec.args]
    namespace = spec.namespace.rstrip("/") or "/"
    if spec.dialect == "ros1":
        words += [f"{a}:={b}" for a, b in spec.remaps]
        if spec.name:
            words.append(f"__name:={spec.name}")
        if namespace != "/":
            words.append(f"__ns:={namespace}")
        return words
    ros: list[str] = []
    if spec.name:
        ros += ["-r", f"__node:={spec.name}"]
    if namespace != "/":
        ros += ["-r", f"__ns:={namespace}"]
    for left, right in spec.remaps:
        ros += ["-r", f"{left}:={right}"]
    files = temporary if temporary is not None else []
    for source in spec.parameters:
        if source.file is not None:
            ros += ["--params-file", str(source.file)]
        elif source.values:
            ros += ["--params-file", str(_params_file(source.values, files))]
    ros += list(spec.ros_arguments)
    if ros:
        words += ["--ros-args", *ros]
    return words


def node_environment(
    spec: NodeSpec,
    executable: UserExecutable,
    *,
    master_uri: str | None = None,
    domain_id: int | None = None,
    environ: Mapping[str, str] = os.environ,
) -> dict[str, str]:
    """The node's environment: the launch's, its flavour, its ROS variables, ``<env>``."""
    env = dict(environ)
    env["ROBOMODEL_MESSAGE_FLAVOUR"] = executable.flavour
    env["PYTHONUNBUFFERED"] = "1"  # lines reach the launch as the node prints them
    paths = [*executable.pythonpath(), *filter(None, [env.get("PYTHONPATH", "")])]
    if paths:
        env["PYTHONPATH"] = os.pathsep.join(paths)
    if spec.dialect == "ros1":
        if master_uri:
            env["ROS_MASTER_URI"] = master_uri
        namespace = spec.namespace.rstrip("/")
        if namespace:
            env["ROS_NAMESPACE"] = namespace
    elif domain_id is not None:
        env["ROS_DOMAIN_ID"] = str(domain_id)
    env.update(dict(spec.env))
    return env


def process_label(spec: NodeSpec, number: int) -> str:
    """``talker-3`` as ros2 launch names its processes (the executable and a launch-wide count
    of the processes started); roslaunch names them by the node (``/talker``)."""
    if spec.dialect == "ros1":
        return spec.fqn
    return f"{Path(spec.executable).name}-{number}"


class UserNodeProcess:
    """A user's node running as a child process (see the module docstring)."""

    def __init__(
        self,
        spec: NodeSpec,
        executable: UserExecutable,
        log: Callable[[str], None],
        *,
        master_uri: str | None = None,
        domain_id: int | None = None,
        number: int = 1,
    ) -> None:
        self.spec = spec
        self.label = process_label(spec, number)
        self._log = log
        self._temporary: list[Path] = []
        self.command = node_command(spec, executable, temporary=self._temporary)
        env = node_environment(spec, executable, master_uri=master_uri, domain_id=domain_id)
        screen = spec.output == "screen"
        self._stdout_file: IO[bytes] | None = None
        stdout: Any = subprocess.PIPE
        if not screen:
            folder = ros_log_dir(env)
            folder.mkdir(parents=True, exist_ok=True)
            self.stdout_path = folder / f"{self.label.strip('/').replace('/', '-')}-stdout.log"
            self._stdout_file = open(self.stdout_path, "ab")  # noqa: SIM115 - closed at exit
            stdout = self._stdout_file
        cwd = spec.cwd if spec.cwd not in (None, "ROS_HOME", "node") else None
        if spec.cwd == "node" and executable.path is not None:
            cwd = str(executable.path.parent)
        self.proc = subprocess.Popen(
            self.command,
            stdin=subprocess.DEVNULL,
            stdout=stdout,
            stderr=subprocess.PIPE,
            env=env,
            cwd=cwd,
            start_new_session=True,  # its own process group, ended as a group (roslaunch)
        )
        self._code: int | None = None
        self._pumps = [
            threading.Thread(target=self._pump, args=(stream,), daemon=True)
            for stream in (self.proc.stdout, self.proc.stderr)
            if stream is not None
        ]
        for pump in self._pumps:
            pump.start()
        self._reporter = threading.Thread(target=self._report, daemon=True)
        self._reporter.start()

    def _pump(self, stream: IO[bytes]) -> None:
        with stream:
            for raw in stream:
                text = raw.decode("utf-8", errors="replace").rstrip("\n")
                self._log(f"[{self.label}] {text}")

    def _report(self) -> None:
        """Wait for the child, show its last lines, then say how it ended (as ROS does)."""
        code = self.proc.wait()
        for pump in self._pumps:
            pump.join(5.0)
        pid, command = self.proc.pid, " ".join(self.command)
        if self.spec.dialect == "ros1":  # roslaunch's words
            self._log(
                f"[{self.label}] process has finished cleanly"
                if code == 0
                else f"[{self.label}] process has died [pid {pid}, exit code {code}, cmd {command}]."
            )
        elif code == 0:  # launch's ExecuteProcess words
            self._log(f"[INFO] [{self.label}]: process has finished cleanly [pid {pid}]")
        else:
            self._log(
                f"[ERROR] [{self.label}]: process has died [pid {pid}, exit code {code}, "
                f"cmd '{command}']."
            )
        self._code = code

    def stop(self) -> None:
        """SIGINT to its group, then SIGTERM and SIGKILL (roslaunch's timeouts)."""
        try:
            end_group(self.proc)
        finally:
            self._reporter.join(5.0)
            if self._stdout_file is not None:
                self._stdout_file.close()
            for path in self._temporary:
                path.unlink(missing_ok=True)

    def exit_code(self) -> int | None:
        return self._code


def run_foreground(command: list[str], env: Mapping[str, str]) -> int:
    """Run a node as ``ros2 run`` / ``rosrun`` do: in the foreground, its exit code returned.

    The child gets a process group of its own, which becomes the terminal's foreground group
    (as a shell hands the terminal to a job), so a keyboard node reads its keys and Ctrl-C
    reaches it; SIGINT and SIGTERM sent to this process are forwarded to its group, and the
    group is ended when the node ends (nothing it started outlives it).
    """
    import signal

    # its own group (os.setpgrp: Popen's process_group is Python 3.11's)
    proc = subprocess.Popen(command, env=dict(env), preexec_fn=os.setpgrp)
    terminal = _foreground_terminal()
    if terminal is not None:
        _hand_terminal(terminal, proc.pid)

    def forward(signum: int, _frame: object) -> None:
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.killpg(proc.pid, signum)

    previous = {sig: signal.signal(sig, forward) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        code: int = proc.wait()
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
        if terminal is not None:
            _hand_terminal(terminal, os.getpgrp())
        end_group(proc, sigint_timeout_s=2.0, sigterm_timeout_s=1.0)
    return 128 + -code if code < 0 else code


def _foreground_terminal() -> int | None:
    """Standard input's terminal, when this process's group is its foreground group."""
    try:
        if os.isatty(0) and os.tcgetpgrp(0) == os.getpgrp():
            return 0
    except OSError:
        pass
    return None


def _hand_terminal(fd: int, pgid: int) -> None:
    """Make ``pgid`` the terminal's foreground group (SIGTTOU ignored meanwhile, as shells do)."""
    import signal

    previous = signal.signal(signal.SIGTTOU, signal.SIG_IGN)
    try:
        os.tcsetpgrp(fd, pgid)
    except OSError:
        pass
    finally:
        signal.signal(signal.SIGTTOU, previous)
