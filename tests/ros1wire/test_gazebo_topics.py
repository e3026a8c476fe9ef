"""Seed 001: ``roslaunch ur5_gazebo ur_gazebo_control.launch`` against robomodel's
master, seen by Debian's rostopic / rosservice / rosnode: Gazebo's and roscore's standard
topics (``/gazebo/model_states``, ``/gazebo/link_states``, ``/gazebo/set_*_state``,
``/rosout``, ``/rosout_agg``), the state services, and the robomodel nodes' log lines on
/rosout, republished by the master's /rosout node on /rosout_agg."""

from __future__ import annotations

import subprocess
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import yaml

from tests.clientlibs.rospy.debian_messages import GENPY, write_definitions
from tests.ros1wire.conftest import Ros1
from tests.timing import scaled

# Seed 001's `rostopic list` after the launch and the controllers, less what robomodel's
# simulator does not have (dynamic_reconfigure's /gazebo/parameter_*)
SEED_001_TOPICS = {
    "/clock", "/gazebo/link_states", "/gazebo/model_states", "/gazebo/set_link_state",
    "/gazebo/set_model_state", "/joint1_position_controller/command",
    "/joint6_position_controller/command", "/joint_states", "/rosout", "/rosout_agg", "/tf",
    "/tf_static",
}  # fmt: skip


def gazebo_msgs_python(tmp_path: Path) -> Path:
    """gazebo_msgs for Debian's rosservice, as ``catkin_make`` would build it: genpy's own
    generators on the vendored noetic definitions, with the definitions they depend on
    (geometry_msgs, std_msgs; Debian ships their Python modules but not their .msg files)
    written out from the Noetic type store. The folder to put on PYTHONPATH."""
    from robomodel.runtime.transport.ros1.ros1_types import DEFINITIONS

    include = tmp_path / "include"
    write_definitions(include, ("geometry_msgs/Pose", "geometry_msgs/Twist",
                                "geometry_msgs/Wrench", "std_msgs/Header"))  # fmt: skip
    out = tmp_path / "python" / "gazebo_msgs"
    source = DEFINITIONS / "gazebo_msgs"
    flags = [f"-Igazebo_msgs:{source / 'msg'}", f"-Igeometry_msgs:{include / 'geometry_msgs/msg'}",
             f"-Istd_msgs:{include / 'std_msgs/msg'}"]  # fmt: skip
    for kind, script in (("msg", "genmsg_py.py"), ("srv", "gensrv_py.py")):
        files = [str(f) for f in sorted((source / kind).iterdir())]
        for argv in (flags + files, ["--initpy"]):
            subprocess.run(
                ["/usr/bin/python3", str(GENPY / script), "-p", "gazebo_msgs",
                 "-o", str(out / kind), *argv],
                check=True, capture_output=True,
            )  # fmt: skip
    (out / "__init__.py").write_text("")
    return out.parent


@pytest.fixture(scope="module")
def gazebo_msgs(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """:func:`gazebo_msgs_python` once for the module's tests (read only: they import it)."""
    return gazebo_msgs_python(tmp_path_factory.mktemp("gazebo_msgs"))


def _launch_seed_001(ros1: Ros1, tmp_path: Path) -> Path:
    log = tmp_path / "launch.log"
    proc = ros1.robomodel(
        "launch", "ur5_gazebo", "ur_gazebo_control.launch", "--headless", "--ros1-master",
        ros1.uri, log=log,
    )  # fmt: skip
    ros1.until(
        lambda: "Started controllers" in log.read_text() or proc.poll() is not None,
        "the controllers",
        timeout_s=scaled(120),
    )
    assert proc.poll() is None, log.read_text()
    return log


SEED_001 = pytest.mark.xdist_group("gazebo_topics_seed_001")
"""The tests of the shared seed 001 launch: one worker starts it once."""


@pytest.fixture(scope="module")
def seed_001(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[Ros1, Path]]:
    """Seed 001's UR5 launch hosting the master, for the module's tests that look at it (each
    starting its own took most of their time): the graph and the launch's log."""
    graph = Ros1(tmp_path_factory.mktemp("seed_001"))
    try:
        yield graph, _launch_seed_001(graph, graph.home)
    finally:
        graph.close()


def _yaml(result: subprocess.CompletedProcess[str]) -> Any:
    assert result.returncode == 0, result.stderr
    return yaml.safe_load(result.stdout.split("\n---")[0])


@SEED_001
def test_seed_001_topics_services_and_rosout(
    seed_001: tuple[Ros1, Path], gazebo_msgs: Path, tmp_path: Path
) -> None:
    ros1, log = seed_001
    topics = set(ros1.run("/usr/bin/rostopic", "list").stdout.split())
    assert topics >= SEED_001_TOPICS, sorted(SEED_001_TOPICS - topics)
    services = set(ros1.run("/usr/bin/rosservice", "list").stdout.split())
    wanted = {"/gazebo/get_model_state", "/gazebo/get_link_state", "/gazebo/set_link_state",
              "/gazebo/set_model_state", "/gazebo/get_model_properties",
              "/gazebo/pause_physics"}  # fmt: skip
    assert wanted <= services, sorted(wanted - services)
    assert not {"/pause_physics", "/spawn_entity", "/get_model_list"} & services  # ROS 2's
    kind = ros1.run("/usr/bin/rostopic", "type", "/gazebo/model_states").stdout.strip()
    assert kind == "gazebo_msgs/ModelStates"

    # spawn_model -model robot -z 0.1: the model's pose, as gazebo_ros answers it
    python = gazebo_msgs

    def rosservice(*argv: str) -> subprocess.CompletedProcess[str]:
        env = {**ros1.env, "PYTHONPATH": str(python)}
        argv = ("/usr/bin/rosservice", *argv)
        return subprocess.run(argv, capture_output=True, text=True, env=env, timeout=scaled(30))

    state = _yaml(
        rosservice(
            "call", "/gazebo/get_model_state", "{model_name: robot, relative_entity_name: world}"
        )
    )
    assert state["success"] is True and state["status_message"] == "GetModelState: got properties"
    assert abs(state["pose"]["position"]["z"] - 0.1) < 1e-6
    assert state["header"]["frame_id"] == "world"
    echo = subprocess.run(
        ["/usr/bin/rostopic", "echo", "-n", "1", "/gazebo/model_states"],
        capture_output=True, text=True, env={**ros1.env, "PYTHONPATH": str(python)}, timeout=scaled(30),
    )  # fmt: skip
    models = _yaml(echo)
    assert models["name"] == ["ground_plane", "robot"]
    link = _yaml(
        rosservice(
            "call",
            "/gazebo/get_link_state",
            "{link_name: 'robot::shoulder_link', reference_frame: ''}",
        )
    )
    assert link["success"] is True
    assert abs(link["link_state"]["pose"]["position"]["z"] - (0.1 + 0.089159)) < 1e-3

    # a robomodel node's log line on /rosout, and the master's /rosout node republishing it
    echoes = {
        topic: ros1.start(["/usr/bin/rostopic", "echo", "-n", "1", topic], tmp_path / f"{n}.log")
        for n, topic in enumerate(("/rosout", "/rosout_agg"))
    }

    def subscribed() -> bool:
        infos = [ros1.run("/usr/bin/rostopic", "info", t).stdout for t in echoes]
        return all(info.count("/rostopic_") >= 1 for info in infos)

    ros1.until(subscribed, "rostopic echo /rosout and /rosout_agg")
    # the controller manager logs the refusal (ERROR) on its node's logger
    refused = ros1.robomodel_run("control", "load", "no_such", "-c", "/controller_manager")
    assert refused.returncode != 0, refused.stdout
    for proc in echoes.values():
        proc.wait(scaled(30))
    # (rostopic's own warnings about /use_sim_time come first: the message starts at header)
    texts = [(tmp_path / f"{n}.log").read_text() for n in range(2)]
    lines = [yaml.safe_load(t[t.index("header:") :].split("\n---")[0]) for t in texts]
    for line in lines:
        assert line["level"] == 8  # ERROR
        assert "no_such" in line["msg"] and line["name"].startswith("/")
    assert lines[0]["name"] == lines[1]["name"]
    nodes = ros1.run("/usr/bin/rosnode", "list").stdout.split()
    assert "/rosout" in nodes and lines[0]["name"] in nodes, (nodes, log.read_text()[-2000:])


def test_robomodel_master_has_roscores_rosout_node(ros1: Ros1, tmp_path: Path) -> None:
    """As on a real roscore: the /rosout node, subscribed to /rosout with no publisher of its
    own there, republishing every line on /rosout_agg."""
    ros1.robomodel("master", "--port", str(ros1.port))
    ros1.wait_for_master()
    # /run_id is set before the /rosout node registers (roslaunch sets it before it starts
    # rosout too): wait for the node, then nothing but it is there
    ros1.until(lambda: "/rosout" in ros1.names("nodes"), "/rosout")
    assert ros1.run("/usr/bin/rosnode", "list").stdout.split() == ["/rosout"]
    info = ros1.run("/usr/bin/rostopic", "info", "/rosout").stdout
    assert "Publishers: None" in info and " * /rosout (" in info
    # roscpp's logger services, as roscore's rosout answers them (Debian's rosservice)
    assert ros1.run("/usr/bin/rosservice", "list").stdout.split() == [
        "/rosout/get_loggers", "/rosout/set_logger_level",
    ]  # fmt: skip
    assert ros1.run("/usr/bin/rosservice", "type", "/rosout/get_loggers").stdout.strip() == (
        "roscpp/GetLoggers"
    )
    set_level = ros1.run("/usr/bin/rosservice", "call", "/rosout/set_logger_level",
                         "ros.rosout", "DEBUG")  # fmt: skip
    assert set_level.returncode == 0, set_level.stderr
    bogus = ros1.run("/usr/bin/rosservice", "call", "/rosout/set_logger_level", "ros", "loud")
    assert bogus.returncode == 2 and "responded with an error" in bogus.stdout + bogus.stderr
    loggers = yaml.safe_load(ros1.run("/usr/bin/rosservice", "call", "/rosout/get_loggers").stdout)
    assert loggers["loggers"] == [
        {"name": "ros", "level": "info"}, {"name": "ros.rosout", "level": "debug"},
    ]  # fmt: skip
    agg = ros1.start(["/usr/bin/rostopic", "echo", "-n", "1", "/rosout_agg"], tmp_path / "agg.log")
    ros1.until(
        lambda: "/rostopic_" in ros1.run("/usr/bin/rostopic", "info", "/rosout_agg").stdout,
        "rostopic echo /rosout_agg",
    )
    pub = ros1.run(
        "/usr/bin/rostopic", "pub", "-1", "/rosout", "rosgraph_msgs/Log",
        "{level: 4, name: /somebody, msg: careful}",
    )  # fmt: skip
    assert pub.returncode == 0, pub.stderr
    agg.wait(scaled(30))
    text = (tmp_path / "agg.log").read_text()
    line = yaml.safe_load(text[text.index("header:") :].split("\n---")[0])
    assert (line["level"], line["name"], line["msg"]) == (4, "/somebody", "careful")


@SEED_001
def test_seed_001_model_states_at_the_physics_rate(
    seed_001: tuple[Ros1, Path], gazebo_msgs: Path, tmp_path: Path
) -> None:
    """gazebo_ros publishes the states at every world update while subscribed (1 kHz with
    Gazebo's 1 ms steps): Debian's ``rostopic hz`` sees about the physics rate, far above the
    100 Hz of /clock. (That nothing is built while nobody subscribes is
    tests/sim/test_model_states.py's.)"""
    ros1, _ = seed_001
    env = {**ros1.env, "PYTHONPATH": str(gazebo_msgs)}
    log = tmp_path / "hz.log"
    with log.open("w") as out:
        hz = subprocess.Popen(
            ["/usr/bin/rostopic", "hz", "-w", "2000", "/gazebo/model_states"],
            stdout=out, stderr=subprocess.STDOUT, text=True, env=env, start_new_session=True,
        )  # fmt: skip
    ros1.procs.append(hz)

    def rates() -> list[float]:
        return [float(line.split(":")[1]) for line in log.read_text().splitlines()
                if line.startswith("average rate:")]  # fmt: skip

    ros1.until(lambda: len(rates()) >= 4 or hz.poll() is not None, "rostopic hz's rates")
    assert hz.poll() is None, log.read_text()
    # rostopic hz's first reports cover its start-up; the later ones the steady rate
    assert max(rates()[2:]) > 400.0, log.read_text()
    ros1.stop(hz)
