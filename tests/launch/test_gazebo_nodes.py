"""gazebo_ros and controller_manager nodes of ROS 1 launch files: their command lines, and the
simulation server that spawn_model spawns into."""

from __future__ import annotations

import logging
import re
from pathlib import Path
from typing import Any

import pytest
import yaml

from robomodel.errors import RobomodelError
from robomodel.launch.nodes.controllers import parse_spawner_args, ros1_spec_source
from robomodel.launch.nodes.gazebo import parse_spawn_args, resolve_world
from robomodel.launch.param_server import ParamServer
from tests.conftest import EXAMPLES
from tests.timing import scaled

pytest.importorskip("mujoco")


def test_spawn_model_options() -> None:
    args = parse_spawn_args(
        ("-urdf", "-param", "robot_description", "-model", "rrbot", "-x", "1", "-z", "0.1",
         "-Y", "1.57", "-J", "joint1", "0.5", "-J", "joint2", "-0.25", "-unpause",
         "-robot_namespace", "/r1", "__name:=spawner", "__log:=/tmp/x.log")
    )  # fmt: skip
    assert args.model == "rrbot" and args.format == "urdf" and args.param == "robot_description"
    assert args.xyz_m == (1.0, 0.0, 0.1) and args.rpy_rad == (0.0, 0.0, 1.57)
    assert args.joints == {"joint1": 0.5, "joint2": -0.25}
    assert args.unpause and args.robot_namespace == "/r1"
    assert args.gazebo_namespace == "/gazebo"


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (("-urdf", "-param", "robot_description"), "you must specify model name"),
        (("-param", "p", "-model", "m"), "exactly one of -urdf and -sdf"),
        (("-urdf", "-model", "m"), "exactly one of -param NAME and -file PATH"),
        (("-urdf", "-param", "p", "-model", "m", "-x", "one"), "-x needs a number, got 'one'"),
        (("-urdf", "-param", "p", "-model", "m", "-q"), "unknown option '-q'"),
        (("-urdf", "-param", "p", "-model"), "-model needs a value"),
    ],
)
def test_spawn_model_errors(argv: tuple[str, ...], message: str) -> None:
    with pytest.raises(RobomodelError, match=re.escape(message)):
        parse_spawn_args(argv)


def test_spawner_options() -> None:
    args = parse_spawner_args(
        ("--stopped", "--timeout=5", "--namespace", "/rrbot", "jsc", "j1", "__name:=s")
    )
    assert args.controllers == ("jsc", "j1")
    assert args.stopped and args.timeout_s == 5.0 and args.namespace == "/rrbot"
    with pytest.raises(RobomodelError, match="at least one controller"):
        parse_spawner_args(("--stopped",))
    with pytest.raises(RobomodelError, match="unrecognized argument '--bogus'"):
        parse_spawner_args(("--bogus", "a"))


def test_worlds_resolve_as_gzserver_finds_them(tmp_path: Path, monkeypatch: Any) -> None:
    assert resolve_world("") is None
    bundled = resolve_world("worlds/empty.world")
    assert bundled is not None and bundled.endswith("gazebo_ros/worlds/empty.world")
    mine = tmp_path / "worlds" / "mine.world"
    mine.parent.mkdir()
    mine.write_text("<sdf version='1.6'><world name='w'/></sdf>")
    monkeypatch.setenv("GAZEBO_RESOURCE_PATH", str(tmp_path))
    assert resolve_world("worlds/mine.world") == str(mine)
    with pytest.raises(RobomodelError, match=r"cannot find world 'worlds/willowgarage\.world'"):
        resolve_world("worlds/willowgarage.world")


def _rrbot_xml() -> str:
    from robomodel.description.packages import PackageIndex
    from robomodel.xacro import process_file

    path = EXAMPLES / "rrbot_description" / "urdf" / "rrbot.xacro"
    index = PackageIndex(package_paths=[EXAMPLES], use_environment=False)
    return str(process_file(str(path), package_index=index).toxml())


def _server(params: ParamServer) -> Any:
    from robomodel.description.packages import PackageIndex
    from robomodel.runtime import Context
    from robomodel.sim import default_world
    from robomodel.sim.server import SimServer

    context = Context("inproc")
    index = PackageIndex(package_paths=[EXAMPLES], use_environment=False)
    server = SimServer(
        default_world(),
        context=context,
        package_index=index,
        spec_source=ros1_spec_source(params),
        real_time_factor=None,
    )
    return server, context


def _loaded_params() -> ParamServer:
    params = ParamServer()
    data = yaml.safe_load((EXAMPLES / "rrbot_control/config/rrbot_control.yaml").read_text())
    for name, value in data["rrbot"].items():
        params.set(f"/rrbot/{name}", value)
    return params


def test_spawned_robot_gets_a_controller_manager_with_parameter_server_controllers(
    caplog: pytest.LogCaptureFixture,
) -> None:
    from robomodel.control.client import ManagerClient

    server, context = _server(_loaded_params())
    try:
        server.drive(0.05)
        entry = server.spawn("rrbot", _rrbot_xml(), joint_positions={"joint2": 0.3})
        manager = entry.control.manager
        assert manager.service_prefix == "/rrbot/controller_manager"  # the plugin's namespace
        client = ManagerClient(context, "/rrbot/controller_manager")
        assert client.load("joint1_position_controller")
        assert client.configure("joint1_position_controller")
        assert client.switch(["joint1_position_controller"]) == (True, "")
        spec = manager.specs["joint1_position_controller"]
        assert spec.params["joint"] == "joint1" and spec.params["pid.p"] == 100.0
        joint2 = server.sim.model.joint("joint2").qposadr[0]
        assert server.sim.data.qpos[joint2] == pytest.approx(0.3)  # -J
        with caplog.at_level(logging.ERROR, logger="robomodel.control"):
            assert not client.load("x")
        assert "namespace: '/rrbot/x'" in caplog.text  # ROS 1's message, in the manager's log
    finally:
        server.close()
        context.shutdown()


def test_a_second_spawn_keeps_time_joint_states_and_controllers() -> None:
    server, context = _server(_loaded_params())
    try:
        first = server.spawn("rrbot", _rrbot_xml())
        first.control.manager.spawn(["joint_state_controller", "joint1_position_controller"])
        server.drive(0.2)
        t_before = server.sim.time_s
        joint1 = server.sim.model.joint("joint1").qposadr[0]
        q_before = float(server.sim.data.qpos[joint1])
        assert t_before > 0.0
        with pytest.raises(RobomodelError, match=r"controller manager in /rrbot"):
            server.spawn("rrbot2", _rrbot_xml(), xyz_m=(1.0, 0.0, 0.0))
        other = _rrbot_xml().replace("<robotNamespace>/rrbot<", "<robotNamespace>/r2<")
        server.spawn("rrbot2", other, xyz_m=(1.0, 0.0, 0.0))
        assert server.sim.time_s == pytest.approx(t_before)
        assert float(server.sim.data.qpos[joint1]) == pytest.approx(q_before)
        states = {c["name"]: c["state"] for c in first.control.manager.list_controllers()}
        assert states == {
            "joint_state_controller": "active",
            "joint1_position_controller": "active",
        }
        assert [r.model_name for r in server.robots] == ["rrbot", "rrbot2"]
        server.delete("rrbot2")
        assert [r.model_name for r in server.robots] == ["rrbot"]
    finally:
        server.close()
        context.shutdown()


def test_rqt_plot_arguments_become_plot_fields() -> None:
    from robomodel.launch.nodes.base import plot_fields

    args = ("/rrbot/joint_states/position[0]", "/turtle1/pose/x:y", "--clear-config", "__name:=p")
    assert plot_fields(args) == [
        "/rrbot/joint_states/position[0]",
        "/turtle1/pose/x",
        "/turtle1/pose/y",
    ]


def test_shapes_world_launch_runs_the_shapes_world() -> None:
    """gazebo_ros's shapes_world.launch, a friend of empty_world.launch: its world name
    resolves through the built-in worlds/ (GAZEBO_RESOURCE_PATH's role) and the server runs."""
    import subprocess

    from tests.conftest import ROBOMODEL

    result = subprocess.run(
        [*ROBOMODEL, "launch", "gazebo_ros", "shapes_world.launch", "--headless",
         "--bus", "inproc", "--duration", "1"],
        capture_output=True, text=True, timeout=scaled(120),
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    assert "gazebo_ros/worlds/shapes.world" in result.stderr
    assert "started /gazebo (gazebo_ros/gzserver)" in result.stderr


def test_spawn_model_sdf_adds_rigid_shapes_and_refuses_articulated_models() -> None:
    """spawn_model -sdf: a model of rigid shapes joins the world where -x -y -z put it; one
    with joints is refused with what to do instead."""
    from robomodel.sim.world import WorldError

    server, context = _server(ParamServer())
    crate = (
        "<sdf version='1.6'><model name='ignored'><link name='l'><inertial><mass>2</mass>"
        "</inertial><collision name='c'><geometry><box><size>0.2 0.2 0.2</size></box>"
        "</geometry></collision></link></model></sdf>"
    )
    from robomodel.launch.gui import _world_scenery  # what the launch's viewer draws

    try:
        assert not [s for s in _world_scenery(server) if "crate" in s.name]
        from robomodel.launch.nodes.gazebo import pose_message
        from robomodel.runtime.msg.types.gazebo_msgs import SpawnModel, SpawnModel_Request

        request = SpawnModel_Request(
            model_name="crate", model_xml=crate, initial_pose=pose_message((1, 2, 0.5), (0, 0, 0))
        )
        reply = context.call_service("/gazebo/spawn_sdf_model", SpawnModel, request)
        assert reply.success, reply
        (shape,) = [s for s in server.world.shapes if s.model == "crate"]
        assert shape.pose[:3] == pytest.approx((1.0, 2.0, 0.5)) and shape.mass_kg == 2.0
        (drawn,) = [s for s in _world_scenery(server) if "crate" in s.name]
        assert drawn.kind == "box" and drawn.frame == drawn.name  # it moves: its own TF frame
        server.drive(0.2)  # it falls onto the ground
        model = server.sim.model
        names = [model.body(i).name for i in range(model.nbody)]
        body = server.sim.data.body(next(n for n in names if "crate" in n))
        assert float(body.xpos[2]) < 0.5
        with pytest.raises(WorldError, match="has joints"):
            server.spawn_sdf(
                "arm", "<model name='a'><link name='x'/><joint name='j' type='revolute'/></model>"
            )
    finally:
        server.close()
        context.shutdown()


def test_gzserver_arguments_as_gazebo_reads_them() -> None:
    from robomodel.launch.nodes.gazebo import parse_server_args

    assert parse_server_args(["-u", "", "--verbose", "-e", "ode", "w.world"]) == (True, "w.world")
    # -s takes a system plugin: it is not the world (ROS 2's gzserver.launch.py passes them)
    assert parse_server_args(["w.world", "-s", "libgazebo_ros_init.so"]) == (False, "w.world")
    assert parse_server_args(["-r", "-v", "4", "empty.sdf"]) == (False, "empty.sdf")


def test_a_spawn_from_another_thread_waits_for_the_chunk_being_stepped(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """spawn_model calls the spawn service in its own thread while the launch's main thread
    drives the simulation (make demo crashed on a half-built bridge): the rebuild and the
    stepping take turns."""
    import threading
    import time

    from robomodel.sim.bus import SimBridge

    add_robot = SimBridge._add_robot

    def slow_add_robot(self: Any, *args: Any) -> None:  # widens the window a lidar makes
        time.sleep(0.02)
        add_robot(self, *args)

    monkeypatch.setattr(SimBridge, "_add_robot", slow_add_robot)
    server, context = _server(_loaded_params())
    errors: list[BaseException] = []

    def spawn_two() -> None:
        try:
            server.spawn("rrbot", _rrbot_xml())
            box = (
                '<robot name="box"><link name="box"><inertial><mass value="1"/>'
                '<inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'
                '<collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>'
                "</link></robot>"
            )
            for k in range(3):
                server.spawn(f"box{k}", box, xyz_m=(1.0 + k, 0.0, 0.5))
        except BaseException as exc:  # reported by the main thread
            errors.append(exc)

    try:
        thread = threading.Thread(target=spawn_two)
        thread.start()
        while thread.is_alive():
            server.drive(0.002)
        server.drive(0.1)
        assert not errors, errors
        assert {entry.model_name for entry in server.robots} == {
            "rrbot",
            *(f"box{k}" for k in range(3)),
        }
        assert server.sim is not None and server.sim.time_s > 0.0
    finally:
        server.close()
        context.shutdown()
