"""``robomodel sim``: scripted headless runs with --cmd-vel and --report json, and bad input."""

from __future__ import annotations

import json

import pytest

from robomodel.cli.main import main
from robomodel.cli.sim import parse_rate
from tests.conftest import ROBOMODEL, past_the_bus_line, unique_domain
from tests.timing import scale, scaled

from .conftest import SIMPLEBOT_LIDAR, SIMPLEBOT_YAML, WALL_WORLD


def test_scripted_run_reports_ground_truth_and_odometry(capsys: pytest.CaptureFixture[str]) -> None:
    code = main(
        [
            "sim", str(SIMPLEBOT_LIDAR), "--controllers", str(SIMPLEBOT_YAML),
            "--world", str(WALL_WORLD), "--spawn", "0", "0", "0.076", "--headless",
            "--duration", "5", "--rate", "max", "--cmd-vel", "0.2 0 0", "--report", "json",
            "--bus", "inproc",
        ]
    )  # fmt: skip
    assert code == 0
    report = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    assert set(report) >= {
        "ground_truth_xy", "ground_truth_yaw", "odom_xy", "odom_yaw",
        "sim_time_s", "wall_time_s", "real_time_factor",
    }  # fmt: skip
    assert report["sim_time_s"] == pytest.approx(5.0)
    assert report["ground_truth_xy"][0] == pytest.approx(1.0, rel=0.05)
    assert report["odom_xy"][0] == pytest.approx(report["ground_truth_xy"][0], rel=0.02)
    assert abs(report["ground_truth_yaw"]) < 0.01
    assert report["real_time_factor"] > 1.0


def test_spawn_pose_and_rotation(capsys: pytest.CaptureFixture[str]) -> None:
    code = main(
        [
            "sim", str(SIMPLEBOT_LIDAR), "--headless", "--duration", "0.5", "--rate", "max",
            "--spawn", "1", "2", "0.076", "0", "0", "1.0", "--report", "json", "--bus", "inproc",
        ]
    )  # fmt: skip
    assert code == 0
    report = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    assert report["ground_truth_xy"] == pytest.approx([1.0, 2.0], abs=0.01)
    assert report["ground_truth_yaw"] == pytest.approx(1.0, abs=0.01)
    assert report["odom_xy"] is None  # no controllers


def test_broken_world_is_a_clear_error(tmp_path, capsys: pytest.CaptureFixture[str]) -> None:  # type: ignore[no-untyped-def]
    world = tmp_path / "bad.world"
    world.write_text("<sdf>\n<world>\n<model>\n</world></sdf>\n")
    code = main(
        ["sim", str(SIMPLEBOT_LIDAR), "--world", str(world), "--headless", "--bus", "inproc"]
    )
    assert code == 2
    err = capsys.readouterr().err
    assert f"{world}:4" in err and "does not parse" in err


def test_rate_parsing() -> None:
    assert parse_rate("realtime", 1.0) == 1.0
    assert parse_rate("max", 1.0) is None
    assert parse_rate("20", 1.0) == 20.0
    from robomodel.errors import RobomodelError

    with pytest.raises(RobomodelError, match="--rate"):
        parse_rate("fast", 1.0)
    with pytest.raises(RobomodelError, match="positive"):
        parse_rate("-1", 1.0)


def test_rate_factor_paces_the_run(capsys: pytest.CaptureFixture[str]) -> None:
    code = main(
        [
            "sim", str(SIMPLEBOT_LIDAR), "--headless", "--duration", "0.6", "--rate", "4",
            "--spawn", "0", "0", "0.076", "--report", "json", "--bus", "inproc",
        ]
    )  # fmt: skip
    assert code == 0
    report = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    # paced to 4x (the sim alone runs >20x): never faster; slower only on a busy machine
    assert 2.5 / scale() < report["real_time_factor"] < 4.4


def test_paused_single_step_and_services_from_another_process() -> None:
    """gazebo -u, then /gazebo/step, /gazebo/unpause_physics and /gazebo/reset_world from the
    `service` verb of another process; /clock follows; xacro arguments reach the description."""
    import subprocess
    import time

    from .conftest import UR5

    domain = unique_domain()
    cli = ROBOMODEL
    bus = ["--domain-id", domain]
    sim = subprocess.Popen(
        [*cli, "sim", str(UR5), "prefix:=left_", "--headless", "--paused", "--rate", "1", *bus],
        stderr=subprocess.PIPE,
        text=True,
    )  # fmt: skip

    def run(*args: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [*cli, *args, *bus], capture_output=True, text=True, timeout=scaled(30)
        )

    def clock_s() -> float:
        echo = run("topic", "echo", "/clock", "--once", "--timeout", f"{scaled(10):.1f}")
        assert echo.returncode == 0, echo.stderr
        sec = int(echo.stdout.split("sec: ")[1].split()[0])
        nanosec = int(echo.stdout.split("nanosec: ")[1].split()[0])
        return sec + nanosec * 1e-9

    try:
        assert sim.stderr is not None and "robomodel sim: world" in past_the_bus_line(sim.stderr)
        for _ in range(50):  # the simulator's services appear in the graph
            listed = run("service", "list")
            if "/gazebo/step" in listed.stdout:
                break
            time.sleep(0.2)
        assert {"/gazebo/pause_physics", "/gazebo/reset_world"} <= set(listed.stdout.split())
        step = "{world_control: {multi_step: %d}}"  # ros_gz_interfaces/ControlWorld
        assert run("service", "call", "/gazebo/step", step % 250).returncode == 0
        assert clock_s() == pytest.approx(0.25, abs=1e-6)  # exactly 250 steps of 1 ms
        assert clock_s() == pytest.approx(0.25, abs=1e-6)  # and still paused
        tf = run("topic", "echo", "/tf_static", "--once", "--timeout", f"{scaled(10):.1f}")
        assert "left_base_link" in tf.stdout  # prefix:=left_ reached the xacro
        assert run("service", "call", "/gazebo/unpause_physics").returncode == 0
        deadline = time.monotonic() + scaled(30)
        while (running := clock_s()) <= 0.5:  # the clock runs again
            assert time.monotonic() < deadline, f"/clock stays at {running} s"
        assert run("service", "call", "/gazebo/pause_physics").returncode == 0
        assert run("service", "call", "/gazebo/reset_world").returncode == 0
        assert run("service", "call", "/gazebo/step", step % 3).returncode == 0
        assert clock_s() == pytest.approx(0.003, abs=1e-6)
        bad = run("service", "call", "/gazebo/step", "{steps: 3}")
        assert bad.returncode == 2 and "has no field 'steps'" in bad.stderr
        assert "world_control (ros_gz_interfaces/msg/WorldControl)" in bad.stderr
    finally:
        sim.terminate()
        sim.wait(timeout=scaled(10))


def test_prefix_runs_through_the_simulator_state_publisher_and_tf() -> None:
    """``--prefix r1_``: bodies, robot_state_publisher's frame_prefix and the weld all agree,
    so ``world -> r1_link3`` is one connected tree on the bus (tf2_echo answers it)."""
    import subprocess

    from .conftest import RRBOT, RRBOT_YAML

    domain = unique_domain()
    cli = ROBOMODEL
    bus = ["--domain-id", domain]
    sim = subprocess.Popen(
        [*cli, "sim", str(RRBOT), "--controllers", str(RRBOT_YAML), "--prefix", "r1_",
         "--headless", *bus],
        stderr=subprocess.DEVNULL,
    )  # fmt: skip
    try:
        echo = subprocess.run(
            [*cli, "tf", "world", "r1_link3", "--once", "--timeout", f"{scaled(20):.1f}", *bus],
            capture_output=True, text=True, timeout=scaled(60),
        )  # fmt: skip
        assert echo.returncode == 0, echo.stderr
        assert "Translation: [" in echo.stdout
        unprefixed = subprocess.run(  # a lookup expected to time out: its 2 s is not scaled
            [*cli, "tf", "world", "link3", "--once", "--timeout", "2", *bus],
            capture_output=True, text=True, timeout=scaled(60),
        )  # fmt: skip
        assert unprefixed.returncode != 0  # every frame of the robot carries the prefix
    finally:
        sim.terminate()
        sim.wait(timeout=scaled(10))


def test_two_robots_from_the_command_line(capsys: pytest.CaptureFixture[str]) -> None:
    """Two spawn_entity calls in one command: one --prefix and --spawn each, one shared
    controller file (each robot's controllers in its own namespace, /r1 and /r2)."""
    from .conftest import SIMPLEBOT

    code = main(
        [
            "sim", str(SIMPLEBOT), str(SIMPLEBOT), "--controllers", str(SIMPLEBOT_YAML),
            "--prefix", "r1_", "--prefix", "r2_", "--spawn", "0", "0", "0.076",
            "--spawn", "0", "2", "0.076", "0", "0", "1.5707963", "--headless", "--duration", "5",
            "--rate", "max", "--cmd-vel", "0.2 0 0", "--report", "json", "--bus", "inproc",
        ]
    )  # fmt: skip
    assert code == 0
    captured = capsys.readouterr()
    assert "robots 'simplebot' (r1_), 'simplebot' (r2_)" in captured.err
    report = json.loads(captured.out.strip().splitlines()[-1])
    r1, r2 = report["robots"]
    assert (r1["prefix"], r2["prefix"]) == ("r1_", "r2_")
    assert report["ground_truth_xy"] == r1["ground_truth_xy"]  # the first robot at top level
    assert r1["ground_truth_xy"] == pytest.approx([1.0, 0.0], abs=0.05)
    assert r2["ground_truth_xy"] == pytest.approx([0.0, 3.0], abs=0.05)  # drove along +y
    for robot in (r1, r2):  # each odometry in its own odom frame, started at its spawn
        assert robot["odom_xy"][0] == pytest.approx(1.0, rel=0.05)


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        ([], "2 robots need 2 distinct --prefix options"),
        (["--prefix", "a_", "--prefix", "a_"], "2 robots need 2 distinct --prefix options"),
        (["--prefix", "a_", "--prefix", "b_", "--spawn", "0"], "2 robots need 2 --spawn poses"),
        (
            ["--prefix", "a_", "--prefix", "b_", "--spawn", "0", "--spawn", "1", "--prefix", "c_"],
            "3 --prefix options for 2 robot(s)",
        ),
        (
            ["--prefix", "a_", "--prefix", "b_", "--spawn", "0", "--spawn", "1"]
            + ["--controllers", str(SIMPLEBOT_YAML)] * 3,
            "3 --controllers files for 2 robot(s)",
        ),
    ],
)
def test_several_robots_need_a_prefix_and_a_pose_each(
    extra: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    code = main(["sim", str(SIMPLEBOT_LIDAR), str(SIMPLEBOT_LIDAR), *extra, "--headless"])
    assert code == 2
    assert message in capsys.readouterr().err


def test_a_prefixed_diff_drive_names_its_frames_with_the_prefix(tmp_path) -> None:  # type: ignore[no-untyped-def]
    from robomodel.cli._sim_robots import prefixed_controllers

    config = prefixed_controllers(str(SIMPLEBOT_YAML), "r1_")
    drive = next(s for s in config.controllers if s.type.endswith("DiffDriveController"))
    assert drive.params["odom_frame_id"] == "r1_odom"
    assert drive.params["base_frame_id"] == "r1_base_link"
    assert drive.params["tf_frame_prefix_enable"] is False
    plain = prefixed_controllers(str(SIMPLEBOT_YAML), "")  # no prefix: the file as written
    drive = next(s for s in plain.controllers if s.type.endswith("DiffDriveController"))
    assert "odom_frame_id" not in drive.params
    own = tmp_path / "own.yaml"  # a file that chose its own frame prefix keeps it
    own.write_text(
        SIMPLEBOT_YAML.read_text().replace(
            "  type: diff_drive_controller/DiffDriveController\n",
            "  type: diff_drive_controller/DiffDriveController\n  tf_frame_prefix: robot1\n",
        )
    )
    kept = prefixed_controllers(str(own), "r1_")
    drive = next(s for s in kept.controllers if s.type.endswith("DiffDriveController"))
    assert "tf_frame_prefix_enable" not in drive.params


def test_two_mobile_robots_are_one_connected_tf_tree() -> None:
    """world -> r2_odom (simulator) -> r2_base_link (diff drive) -> r2_left_wheel (RSP)."""
    import subprocess

    from .conftest import SIMPLEBOT

    domain = unique_domain()
    cli = ROBOMODEL
    bus = ["--domain-id", domain]
    sim = subprocess.Popen(
        [*cli, "sim", str(SIMPLEBOT), str(SIMPLEBOT), "--controllers", str(SIMPLEBOT_YAML),
         "--prefix", "r1_", "--prefix", "r2_", "--spawn", "0", "0", "0.076",
         "--spawn", "0", "2", "0.076", "--headless", *bus],
        stderr=subprocess.DEVNULL,
    )  # fmt: skip
    try:
        for frame, y in (("r1_left_wheel", 0.0), ("r2_left_wheel", 2.0)):
            echo = subprocess.run(
                [*cli, "tf", "world", frame, "--once", "--timeout", f"{scaled(20):.1f}", *bus],
                capture_output=True, text=True, timeout=scaled(60),
            )  # fmt: skip
            assert echo.returncode == 0, echo.stderr[-2000:]
            translation = echo.stdout.split("Translation: [")[1].split("]")[0]
            _x_m, y_m, _z = (float(v) for v in translation.split(","))
            assert y_m == pytest.approx(y + 0.125, abs=0.05)  # the left wheel, 0.125 m to the left
        topics = subprocess.run(
            [*cli, "topic", "list", *bus], capture_output=True, text=True, timeout=scaled(30)
        ).stdout.split()
        assert {"/r1/simplebot_controller/cmd_vel", "/r2/simplebot_controller/cmd_vel"} <= set(
            topics
        )
    finally:
        sim.terminate()
        sim.wait(timeout=scaled(10))


def test_each_robot_gets_its_own_namespace() -> None:
    import argparse

    from robomodel.cli.sim import robot_requests

    args = argparse.Namespace(
        inputs=["a.urdf", "b.urdf", "c.urdf", "x:=1"],
        prefix=["r1_", "2_", "left/"],
        spawn=[[0.0], [1.0], [2.0]],
        controllers=[],
    )
    requests, mappings = robot_requests(args)
    assert [r.namespace for r in requests] == ["/r1", "/robot2", "/left"]
    assert mappings == {"x": "1"} and [r.xyz_m[0] for r in requests] == [0.0, 1.0, 2.0]
    one, _ = robot_requests(argparse.Namespace(inputs=["a.urdf"], prefix=["r1_"], spawn=[], controllers=[]))  # fmt: skip
    assert one[0].namespace == "/"  # one robot: the controller file's own namespace
