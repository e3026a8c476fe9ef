"""A user's own nodes run as processes: ``robomodel run`` in the foreground, ``robomodel
launch`` beside its mapped nodes (ROS 1 on the master it starts, ROS 2 with launch_ros's
arguments), with tracebacks shown, respawn and required as ROS has them."""

from __future__ import annotations

import json
import os
import signal
import subprocess
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import ROBOMODEL, end_process, free_port
from tests.timing import scaled, wait_until

WS = Path(__file__).parent / "user_ws" / "src"


def _json_line(text: str, prefix: str) -> dict[str, Any]:
    for line in text.splitlines():
        if line.startswith(prefix) and line[len(prefix) :].lstrip().startswith("{"):
            found: dict[str, Any] = json.loads(line[len(prefix) :])
            return found
    raise AssertionError(f"no line {prefix}{{...}} in:\n{text}")


def test_run_passes_ros_arguments_through_and_ends_the_node_on_sigterm(tmp_path: Path) -> None:
    stop = tmp_path / "never"
    env = {**os.environ, "STAY_UNTIL": str(stop), "PYTHONUNBUFFERED": "1"}
    argv = ["--ros-args", "-r", "__node:=talker2", "-p", "rate:=2"]
    proc = subprocess.Popen(
        [*ROBOMODEL, "run", "--package-path", str(WS), "py_nodes", "echo_args", *argv],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )
    try:
        assert proc.stdout is not None
        seen = json.loads(proc.stdout.readline())
        assert seen["args"] == argv and seen["argv0"] == "echo_args"
        assert seen["flavour"] == "rosidl"
        node_pid = seen["pid"]
        assert node_pid != proc.pid
        proc.send_signal(signal.SIGTERM)  # forwarded to the node's group
        assert proc.wait(scaled(10)) == 128 + signal.SIGTERM
    finally:
        end_process(proc)
    with pytest.raises(ProcessLookupError):
        os.kill(node_pid, 0)


def test_a_ros1_launch_runs_user_nodes_on_the_master_it_starts(tmp_path: Path) -> None:
    """roslaunch's behaviour: a master started, parameters set on it, a crashing node's
    traceback shown while the others go on, respawn, and a required node ending the launch."""
    from robomodel.runtime.transport.ros1.param_client import MasterParams

    uri = f"http://127.0.0.1:{free_port()}/"
    stop = tmp_path / "stop"
    log = tmp_path / "launch.log"
    env = {**os.environ, "ROS_MASTER_URI": uri, "ROS_LOG_DIR": str(tmp_path / "ros_log")}
    with log.open("w") as out:
        proc = subprocess.Popen(
            [*ROBOMODEL, "launch", "--headless", "--package-path", str(WS), "catkin_nodes",
             "all.launch", f"stop_file:={stop}"],
            stdout=out, stderr=subprocess.STDOUT, text=True, env=env,
        )  # fmt: skip
        try:

            def text() -> str:
                return log.read_text()

            wait_until(
                lambda: text().count("quitter: done") >= 2 and "[/robot1/echo] {" in text(),
                scaled(60),
                what=lambda: f"the nodes' output:\n{text()}",
            )
            seen = _json_line(text(), "[/robot1/echo] ")
            assert seen["master"] == uri and seen["flavour"] == "genpy"
            assert seen["args"] == ["--loud", "chatter:=talk", "__name:=echo", "__ns:=/robot1"]
            assert MasterParams(uri).get("/robot1/echo/frame") == "base"
            assert "[/crasher] ZeroDivisionError: division by zero" in text()
            assert '[/crasher]   File "' in text()  # the node's own traceback, line by line
            assert "[/crasher] process has died [pid" in text()
            assert proc.poll() is None  # a node that is not required does not end the launch
            stop.touch()
            assert proc.wait(scaled(30)) == 0
        finally:
            end_process(proc)
    assert "[launch] required node /waiter ended (code 0): shutting down" in log.read_text()
    waiter_stdout = (tmp_path / "ros_log" / "waiter-stdout.log").read_text()
    assert json.loads(waiter_stdout)["args"] == ["__name:=waiter"]  # output="log": its file


def test_a_ros2_launch_shows_a_crashing_node_s_traceback_as_ros2_launch(tmp_path: Path) -> None:
    log = tmp_path / "launch.log"
    with log.open("w") as out:
        proc = subprocess.Popen(
            [*ROBOMODEL, "launch", "--headless", "--bus", "inproc", "--package-path", str(WS),
             "py_nodes", "args.launch.py"],
            stdout=out, stderr=subprocess.STDOUT, text=True,
        )  # fmt: skip
        try:
            wait_until(
                lambda: (
                    "[ERROR] [crasher-2]: process has died" in log.read_text()
                    and "[INFO] [echo_args-1]: process has finished cleanly" in log.read_text()
                ),
                scaled(60),
                what=lambda: f"both nodes ended:\n{log.read_text()}",
            )
            text = log.read_text()
            assert "[crasher-2] ZeroDivisionError: division by zero" in text
            seen = _json_line(text, "[echo_args-1] ")
            assert seen["args"][:7] == ["--loud", "--ros-args", "-r", "__node:=echo", "-r",
                                        "__ns:=/robot1", "-r"]  # fmt: skip
            assert proc.poll() is None  # the launch goes on
        finally:
            end_process(proc)


def test_rospy_tutorials_talker_listener_launch_runs_its_two_nodes(tmp_path: Path) -> None:
    """The package layout of ros/ros_tutorials' rospy_tutorials: its own launch file runs the
    talker and listener scripts, and the listener hears the talker over the master."""
    uri = f"http://127.0.0.1:{free_port()}/"
    log = tmp_path / "launch.log"
    env = {**os.environ, "ROS_MASTER_URI": uri}
    with log.open("w") as out:
        proc = subprocess.Popen(
            [*ROBOMODEL, "launch", "--headless", "--package-path", str(WS), "rospy_tutorials",
             "talker_listener.launch"],
            stdout=out, stderr=subprocess.STDOUT, text=True, env=env,
        )  # fmt: skip
        try:
            wait_until(
                lambda: "I heard hello world" in log.read_text(),
                scaled(60),
                what=lambda: f"the listener hearing the talker:\n{log.read_text()}",
            )
            assert ": 2 nodes running" in log.read_text()
        finally:
            end_process(proc)
