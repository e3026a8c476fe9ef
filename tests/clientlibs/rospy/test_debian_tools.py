"""rospy nodes written as ros_tutorials writes them, run on robomodel's rospy, seen and driven
by Debian's real ROS 1 tools (``rostopic``, ``rosservice``, ``rosparam``, ``rosnode``) on one
roscore shared by the module."""

from __future__ import annotations

import ast
import os
import signal
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.conftest import end_process
from tests.ros1wire.conftest import ROSCORE, Ros1
from tests.timing import scaled

# Every test runs on the module's roscore: one worker starts it once
pytestmark = pytest.mark.xdist_group("rospy_debian_tools")

HERE = Path(__file__).parent
NODES = HERE / "nodes"
PACKAGES = HERE / "packages"
ROSTOPIC, ROSSERVICE, ROSPARAM, ROSNODE = (
    f"/usr/bin/{tool}" for tool in ("rostopic", "rosservice", "rosparam", "rosnode")
)


def _genpy_rospy_tutorials(out: Path) -> Path:
    """rospy_tutorials' Python module for Debian's rosservice, as catkin builds it (genpy's
    own generator); Debian ships no rospy_tutorials. The folder to put on PYTHONPATH."""
    package = out / "rospy_tutorials"
    (package / "srv").mkdir(parents=True)
    tool = ["/usr/bin/python3", "/usr/lib/genpy/gensrv_py.py", "-p", "rospy_tutorials"]
    source = PACKAGES / "rospy_tutorials" / "srv" / "AddTwoInts.srv"
    for argv in ([str(source)], ["--initpy"]):
        subprocess.run([*tool, "-o", str(package / "srv"), *argv], check=True, capture_output=True)
    (package / "__init__.py").write_text("")
    return out


class Graph(Ros1):
    """The module's roscore, its Debian tools (with rospy_tutorials built for them) and
    rospy nodes run by the venv's Python with robomodel's rospy."""

    generated: Path

    @property
    def env(self) -> dict[str, str]:
        env = super().env
        env["ROS_PACKAGE_PATH"] = str(PACKAGES)
        return env

    def tool(self, *argv: str, timeout_s: float = 30) -> subprocess.CompletedProcess[str]:
        env = {**self.env, "PYTHONPATH": str(self.generated)}
        return subprocess.run(
            list(argv), capture_output=True, text=True, env=env, timeout=scaled(timeout_s)
        )

    def node(self, script: str, *argv: str, log: Path) -> subprocess.Popen[str]:
        env = {**self.env, "PYTHONPATH": os.environ.get("PYTHONPATH", "")}
        out = log.open("w")
        proc = subprocess.Popen(
            [sys.executable, "-u", str(NODES / script), *argv],
            stdout=out,
            stderr=subprocess.STDOUT,
            text=True,
            env=env,
            start_new_session=True,
        )
        self.procs.append(proc)
        return proc


@pytest.fixture(scope="module")
def graph(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Graph]:
    for tool in (ROSCORE, ROSTOPIC, ROSSERVICE, ROSPARAM, ROSNODE):
        if not Path(tool).exists():
            pytest.fail(f"Debian's ROS 1 is missing ({tool}): tools/system-deps test installs it")
    home = tmp_path_factory.mktemp("rospy")
    found = Graph(home)
    found.generated = _genpy_rospy_tutorials(home / "generated")
    found.roscore()
    try:
        yield found
    finally:
        found.close()


def _lines(log: Path) -> str:
    return log.read_text() if log.exists() else ""


def _nodes(graph: Graph) -> list[str]:
    return graph.tool(ROSNODE, "list").stdout.split()


def test_talker_is_heard_by_rostopic_echo_and_logs_to_rosout(graph: Graph, tmp_path: Path) -> None:
    log = tmp_path / "talker.log"
    talker = graph.node("talker", log=log)
    echo = graph.tool(ROSTOPIC, "echo", "-n", "2", "/chatter")
    assert echo.stdout.count('data: "hello world ') == 2, echo.stdout + echo.stderr
    name = next(n for n in _nodes(graph) if n.startswith("/talker_"))  # anonymous=True
    assert name.split("_")[1] == str(talker.pid)
    info = graph.tool(ROSTOPIC, "info", "/chatter").stdout
    assert "std_msgs/String" in info and name in info, info
    rosout = graph.tool(ROSTOPIC, "echo", "-n", "1", "/rosout_agg")
    assert f'name: "{name}"' in rosout.stdout and "level: 2" in rosout.stdout, rosout.stdout
    assert 'msg: "hello world ' in rosout.stdout and "/chatter" in rosout.stdout
    assert end_process(talker, signal.SIGINT, timeout_s=scaled(20)) == 0, _lines(log)
    assert "Traceback" not in _lines(log)
    assert "[INFO] [" in _lines(log)
    graph.until(lambda: name not in _nodes(graph), "the talker's unregistration")


def test_listener_hears_rostopic_pub(graph: Graph, tmp_path: Path) -> None:
    log = tmp_path / "listener.log"
    listener = graph.node("listener", "chatter:=/words", log=log)
    graph.until(lambda: any(n.startswith("/listener_") for n in _nodes(graph)), "the listener")
    pub = graph.start(
        [ROSTOPIC, "pub", "-r", "5", "/words", "std_msgs/String", "data: 'hi from rostopic'"]
    )
    graph.until(lambda: "I heard hi from rostopic" in _lines(log), "the listener's line")
    graph.stop(pub)
    assert end_process(listener, signal.SIGINT, timeout_s=scaled(20)) == 0, _lines(log)


def test_add_two_ints_answers_rosservice_and_the_tutorial_client(
    graph: Graph, tmp_path: Path
) -> None:
    log = tmp_path / "server.log"
    server = graph.node("add_two_ints_server", log=log)
    graph.until(lambda: "Ready to add two ints." in _lines(log), "the server")
    call = graph.tool(ROSSERVICE, "call", "/add_two_ints", "3", "39")
    assert call.stdout.strip() == "sum: 42", call.stdout + call.stderr
    info = graph.tool(ROSSERVICE, "info", "/add_two_ints").stdout
    assert "Type: rospy_tutorials/AddTwoInts" in info and "Args: a b" in info, info
    client = subprocess.run(
        [sys.executable, str(NODES / "add_two_ints_client"), "-5", "12"],
        capture_output=True,
        text=True,
        env={**graph.env, "PYTHONPATH": os.environ.get("PYTHONPATH", "")},
        timeout=scaled(60),
    )
    assert client.stdout.splitlines() == ["Requesting -5+12", "-5 + 12 = 7"], client.stderr
    assert "Returning [-5 + 12 = 7]" in _lines(log)
    assert end_process(server, signal.SIGINT, timeout_s=scaled(20)) == 0, _lines(log)
    graph.until(
        lambda: "/add_two_ints" not in graph.tool(ROSSERVICE, "list").stdout, "unregistration"
    )


def test_ctrl_c_ends_the_sleeping_loop_and_the_goodbye_is_heard(
    graph: Graph, tmp_path: Path
) -> None:
    log, heard = tmp_path / "goodbye.log", tmp_path / "echo.log"
    echo = graph.start([ROSTOPIC, "echo", "-p", "/farewell"], log=heard)
    talker = graph.node("goodbye_talker", log=log)
    graph.until(lambda: "still here" in _lines(heard), "rostopic echo hearing the talker")
    # rospy's wall-clock sleep is not cut short: the loop ends at is_shutdown(), no traceback
    assert end_process(talker, signal.SIGINT, timeout_s=scaled(20)) == 0, _lines(log)
    assert "Traceback" not in _lines(log), _lines(log)
    graph.until(lambda: "goodbye" in _lines(heard), "the on_shutdown hook's message")
    graph.stop(echo)


def test_a_rostest_node_passes_and_fails_by_its_exit_status(graph: Graph, tmp_path: Path) -> None:
    talker = graph.node("talker", log=tmp_path / "talker.log")
    passing = graph.node("hears_talker_test", str(scaled(30)), log=tmp_path / "pass.log")
    assert passing.wait(scaled(60)) == 0, _lines(tmp_path / "pass.log")
    assert "test_hears_hello" in _lines(tmp_path / "pass.log")
    assert end_process(talker, signal.SIGINT, timeout_s=scaled(20)) == 0
    graph.until(lambda: not any(n.startswith("/talker_") for n in _nodes(graph)), "no talker")
    failing = graph.node("hears_talker_test", "1", log=tmp_path / "fail.log")
    assert failing.wait(scaled(60)) == 1, _lines(tmp_path / "fail.log")
    assert "FAILED (failures=1)" in _lines(tmp_path / "fail.log")


def _results(log: Path) -> dict[str, object]:
    found: dict[str, object] = {}
    for line in _lines(log).splitlines():
        key, sep, value = line.partition(": ")
        if sep and key.isidentifier():
            found[key] = ast.literal_eval(value)
    return found


def test_names_params_latch_timers_and_logging(graph: Graph, tmp_path: Path) -> None:
    assert graph.tool(ROSPARAM, "set", "/course/robot", "{size: 3}").returncode == 0
    assert graph.tool(ROSPARAM, "set", "/robot_size", "2").returncode == 0
    log = tmp_path / "features.log"
    argv = ("__ns:=/lab", "__name:=probe", "_rate:=5.5", "chatter:=words", "extra")
    node = graph.node("feature_node", *argv, log=log)
    graph.until(lambda: "features ready" in _lines(log), "the feature node")
    # a latched topic: a subscriber that comes later gets the last message
    latched = graph.tool(ROSTOPIC, "echo", "-n", "1", "/lab/state")
    assert 'data: "ready"' in latched.stdout, latched.stdout + latched.stderr
    assert graph.tool(ROSPARAM, "get", "/lab/probe/rate").stdout.strip() == "5.5"
    assert graph.tool(ROSPARAM, "get", "/lab/probe/written").stdout.split() == [
        "-", "1", "-", "2", "-", "3",
    ]  # fmt: skip
    pub = graph.start([ROSTOPIC, "pub", "-r", "5", "/lab/trigger", "std_msgs/String", "data: go"])
    refused = graph.tool(ROSSERVICE, "call", "/lab/probe/refuse", "true")
    assert refused.returncode != 0 and "no thanks" in refused.stderr, refused.stderr
    graph.until(lambda: "trigger" in _results(log), "wait_for_message")
    graph.stop(pub)
    words = graph.start([ROSTOPIC, "pub", "-r", "5", "/lab/words", "std_msgs/String", "data: abc"])
    echo = graph.tool(ROSTOPIC, "echo", "-n", "1", "/lab/echo")
    graph.stop(words)
    assert 'data: "echo: abc"' in echo.stdout, echo.stdout + echo.stderr
    assert end_process(node, signal.SIGINT, timeout_s=scaled(20)) == 0, _lines(log)
    results = _results(log)
    assert results == {
        "name": "/lab/probe",
        "namespace": "/lab/",
        "caller_id": "/lab/probe",
        "resolved_private": "/lab/probe/gain",
        "resolved_relative": "/lab/words",
        "myargv": ["extra"],
        "rate_param": 5.5,
        "default": 42,
        "global": {"size": 3},
        "has_written": True,
        "has_doomed": False,
        "missing_raises": "'/lab/probe/missing'",
        "search": "/robot_size",
        "names_has_written": True,
        "service_error": True,
        "service_missing": True,
        "wait_service_timeout": "timeout exceeded while waiting for service /nowhere",
        "published_has_state": True,
        "node_uri": True,
        "robomodel_node": "Node",
        "oneshot": True,
        "timer_ticks": 3,
        "timer_event_has_last": True,
        "trigger": "go",
        "wait_timeout": "timeout exceeded while waiting for message on topic /lab/never",
        "shutdown_hook": True,
        "spin_returned": True,
    }, _lines(log)
    text = _lines(log)
    assert text.count("once ") == 1 and text.count("throttled ") == 1 and text.count("same") == 1
    assert "[WARN] [" in text and "[ERROR] [" in text


def test_tf_listener_and_broadcaster_with_debian_tf(graph: Graph, tmp_path: Path) -> None:
    # Debian's tf: yaw 90 degrees, half a metre along x (x y z yaw pitch roll parent child ms)
    static = graph.start(
        ["/usr/lib/tf/static_transform_publisher", "0.5", "0", "0", "1.5707963267948966", "0",
         "0", "world", "sensor", "50"]
    )  # fmt: skip
    log = tmp_path / "tf.log"
    node = graph.node("tf_node", log=log)
    graph.until(lambda: "lookup_error" in _results(log), "the tf node's lookups")
    assert _results(log) == {
        "lookup": [0.5, 0.0, 0.0],
        "yaw": 1.5708,
        "point": [0.5, 1.0],  # x of the sensor frame is y of the world
        "can_unknown": False,
        "lookup_error": True,
    }, _lines(log)
    echo_log = tmp_path / "tf_echo.log"
    echo = graph.start(["/usr/lib/tf/tf_echo", "world", "robot"], echo_log)
    graph.until(lambda: "Translation: [1.000, 2.000, 3.000]" in _lines(echo_log), "tf_echo")
    assert "in RPY (radian) [0.000, -0.000, 1.571]" in _lines(echo_log), _lines(echo_log)
    for proc in (echo, static):
        graph.stop(proc)
    assert end_process(node, signal.SIGINT, timeout_s=scaled(20)) == 0, _lines(log)
