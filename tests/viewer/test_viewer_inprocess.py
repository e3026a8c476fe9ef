"""The viewer in this process (no browser): loading, reload from dependencies, bad files."""

from __future__ import annotations

import shutil
import time
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from robomodel.description.packages import PackageIndex
from robomodel.errors import RobomodelError
from robomodel.viewer import RobotSource, Viewer, ViewerOptions
from tests.conftest import EXAMPLES, past_the_bus_line
from tests.timing import scaled
from tests.viewer.conftest import wait_for
from tests.viewer.robots import write_arm


@pytest.fixture
def started() -> Iterator[list[Viewer]]:
    viewers: list[Viewer] = []
    yield viewers
    for viewer in viewers:
        viewer.close()


def _start(viewers: list[Viewer], *sources: RobotSource, **options: object) -> Viewer:
    viewer = Viewer(
        ViewerOptions(sources=sources, port=0, reload_period_s=0.05, **options)  # type: ignore[arg-type]
    )
    viewer.start()
    viewers.append(viewer)
    return viewer


def test_yaml_dependency_change_reloads_and_keeps_joint_values(
    started: list[Viewer], tmp_path: Path
) -> None:
    package = tmp_path / "example_description"
    shutil.copytree(EXAMPLES / "example_description", package)
    viewer = _start(
        started,
        RobotSource(str(package / "urdf/example.urdf.xacro")),
        package_index=PackageIndex(packages={"example_description": package}),
    )
    session = viewer.sessions[0]
    assert session.loaded is not None
    assert any(d.endswith("parameters.yaml") for d in session.loaded.dependencies)
    session.queue_positions({"arm_joint_1": 0.5})
    wait_for(lambda: session.jsp and session.jsp.free_joints["arm_joint_1"].position == 0.5)
    old_size = session.robot.link("base_link").visuals[0].geometry.size_m  # type: ignore[union-attr]
    params = package / "config/parameters.yaml"
    time.sleep(0.01)
    params.write_text(params.read_text().replace('base_length: "0.65"', 'base_length: "0.9"'))
    wait_for(lambda: viewer.reloads == 1, what="a reload after the YAML changed")
    new_size = session.robot.link("base_link").visuals[0].geometry.size_m  # type: ignore[union-attr]
    assert old_size[0] == pytest.approx(0.65) and new_size[0] == pytest.approx(0.9)
    assert session.jsp is not None
    assert session.jsp.free_joints["arm_joint_1"].position == pytest.approx(0.5)


def test_a_file_that_does_not_parse_at_start_is_served_and_loads_when_fixed(
    started: list[Viewer], tmp_path: Path
) -> None:
    path = write_arm(tmp_path)
    good = path.read_text()
    path.write_text(good.replace("</robot>", ""))
    viewer = _start(started, RobotSource(str(path)))
    session = viewer.sessions[0]
    assert session.robot is None and session.failure is not None
    assert "arm.urdf:" in session.failure.message
    wait_for(lambda: "showing the last good model" in viewer.status.content)
    time.sleep(0.01)
    path.write_text(good)
    wait_for(lambda: session.robot is not None and session.display is not None)
    wait_for(lambda: viewer.status.content == "OK", what="the status to clear")


def test_link_poses_in_the_fixed_frame(started: list[Viewer], tmp_path: Path) -> None:
    viewer = _start(started, RobotSource(str(write_arm(tmp_path))))
    session = viewer.sessions[0]
    session.queue_positions({"joint1": np.pi / 2})
    assert session.display is not None
    names = session.display.link_names

    def tool_position() -> np.ndarray | None:
        poses = session.link_poses(viewer.buffer, "base_link", np.eye(4))
        if poses is None or not poses.visible.all():
            return None
        return poses.xyz[names.index("tool")]

    # joint1 turns about x by 90 degrees: the tool (1.1 m up link1) points along -y.
    wait_for(
        lambda: (p := tool_position()) is not None and np.allclose(p, (0.0, -1.1, 0.1), atol=1e-9),
        what="the tool at (0, -1.1, 0.1)",
    )


def test_scene_updates_are_capped_at_the_frame_rate(started: list[Viewer], tmp_path: Path) -> None:
    """TF at 200 Hz (a simulation) reaches the page at most Frame Rate times a second."""
    from robomodel.runtime.msg import TFMessage
    from robomodel.runtime.msg.types.geometry_msgs import Transform, TransformStamped, Vector3
    from robomodel.runtime.msg.types.std_msgs import Header

    with pytest.raises(RobomodelError, match=r"frame rate must be 1\.\.1000 Hz"):
        Viewer(ViewerOptions(sources=(RobotSource(str(write_arm(tmp_path))),), frame_rate_hz=0))
    viewer = _start(started, RobotSource(str(write_arm(tmp_path))), frame_rate_hz=10.0)
    assert viewer.context is not None
    publisher = viewer.context.create_node("flood").create_publisher(TFMessage, "/tf")

    def flood(duration_s: float) -> int:
        wait_for(lambda: not viewer._dirty, what="a quiet viewer")
        before = viewer.updates_sent
        end = time.monotonic() + duration_s
        x = 0.0
        while time.monotonic() < end:
            x += 1e-3
            tf = TransformStamped(
                Header(frame_id="world"), "base_link", Transform(Vector3(x, 0, 0))
            )
            publisher.publish(TFMessage([tf]))
            time.sleep(0.005)
        return viewer.updates_sent - before

    sent = flood(1.0)
    assert 1 <= sent <= 10 + 2  # ~200 TF messages merged into at most 10 updates a second
    viewer.frame_rate_number.value = 2.0  # Global Options > Frame Rate, as a user types it
    wait_for(lambda: viewer.frame_rate_hz == 2.0, what="the new frame rate")
    assert 1 <= flood(1.0) <= 2 + 2


def test_an_idle_viewer_wakes_for_what_is_due_not_every_few_milliseconds(
    started: list[Viewer], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """With nothing moving, the update loop sleeps until its next deadline or one frame (the
    10 Hz joint states and TF of its own publishers, the status and reload polls), rather than
    waking every 5 ms: an idle viewer beside a user's other work costs little CPU."""
    viewer = _start(started, RobotSource(str(write_arm(tmp_path))), frame_rate_hz=30.0)
    assert viewer.context is not None
    wait_for(lambda: viewer.updates_sent > 0, what="a first update")
    turns: list[float] = []
    real_spin = viewer.context.spin_once
    monkeypatch.setattr(viewer.context, "spin_once", lambda t=0.0: turns.append(t) or real_spin(t))
    wait_for(lambda: len(turns) >= 20, what="twenty turns of the loop")
    started_s = time.monotonic()
    counted = len(turns)
    time.sleep(1.0)
    per_s = (len(turns) - counted) / (time.monotonic() - started_s)
    # the frame (30 Hz) and its own 10 Hz publishers bound it; a 5 ms loop turns 200 times a second
    assert per_s < 100, f"{per_s:.0f} turns a second"
    assert max(turns) <= 1 / 30 + 1e-9


BROKEN_MACRO = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="bad">
  <xacro:macro name="leg" params="n">
    <link name="leg_${n + undefined_length}"/>
    <joint name="hip_${n}" type="fixed"><parent link="base_link"/><child link="leg_${n}"/></joint>
  </xacro:macro>
  <link name="base_link"/>
  <xacro:leg n="1"/>
</robot>
"""


def test_xacro_error_carries_file_line_and_macro_stack_to_the_page(
    started: list[Viewer], tmp_path: Path
) -> None:
    good = tmp_path / "robot.urdf.xacro"
    good.write_text(BROKEN_MACRO.replace("n + undefined_length", "n"))
    viewer = _start(started, RobotSource(str(good)))
    session = viewer.sessions[0]
    assert session.robot is not None and session.failure is None
    time.sleep(0.01)
    good.write_text(BROKEN_MACRO)
    wait_for(lambda: session.failure is not None, what="the broken edit to be seen")
    assert session.failure is not None
    assert "robot.urdf.xacro:4:" in session.failure.message
    assert "undefined_length" in session.failure.message
    wait_for(lambda: "in macro 'leg'" in viewer.status.content, what="the macro stack")
    assert "`robot.urdf.xacro:4:" in viewer.status.content
    assert session.robot is not None and session.robot.has_link("leg_1")  # last good model


def test_scenery_is_posed_in_its_frame_and_hidden_while_unconnected(
    started: list[Viewer], tmp_path: Path
) -> None:
    from robomodel.runtime.msg import TFMessage
    from robomodel.runtime.msg.types.geometry_msgs import (
        Quaternion,
        Transform,
        TransformStamped,
        Vector3,
    )
    from robomodel.runtime.msg.types.std_msgs import Header
    from robomodel.runtime.qos import latched
    from robomodel.viewer import SceneryShape

    wall = SceneryShape("wall_0", "world", "box", (0.1, 4.0, 1.0), (2.25, 0.0, 0.5))
    ball = SceneryShape("ball_1", "ball_1", "sphere", (0.2, 0.0, 0.0), rgba=(1, 0, 0, 1))
    viewer = _start(
        started, RobotSource(str(write_arm(tmp_path))), fixed_frame="world", scenery=(wall, ball)
    )
    assert viewer.scenery is not None and viewer.context is not None
    wall_node, ball_node = viewer.scenery.nodes
    # The wall is in the fixed frame itself: drawn at once, as tf2 answers world -> world with
    # the identity before any transform arrives. The ball waits for its frame.
    wait_for(lambda: viewer.scenery.shown == 1, what="the wall drawn in world")  # type: ignore[union-attr]
    assert wall_node.visible and not ball_node.visible
    node = viewer.context.create_node("scenery_test")

    def tf(parent: str, child: str, x: float, yaw: float = 0.0) -> TransformStamped:
        q = Quaternion(z=float(np.sin(yaw / 2)), w=float(np.cos(yaw / 2)))
        return TransformStamped(Header(frame_id=parent), child, Transform(Vector3(x, 0, 0), q))

    static = node.create_publisher(TFMessage, "/tf_static", latched())
    static.publish(TFMessage([tf("world", "base_link", 0.0)]))
    assert wall_node.visible and not ball_node.visible
    assert np.allclose(wall_node.position, (2.25, 0.0, 0.5))
    moving = node.create_publisher(TFMessage, "/tf")
    moving.publish(TFMessage([tf("world", "ball_1", 1.0, yaw=np.pi / 2)]))
    wait_for(lambda: viewer.scenery.shown == 2, what="the ball in its own frame")  # type: ignore[union-attr]
    assert np.allclose(ball_node.position, (1.0, 0.0, 0.0))
    viewer.fixed_frame = "base_link"  # another fixed frame: the same world, seen from there
    static.publish(TFMessage([tf("world", "base_link", 1.0, yaw=np.pi / 2)]))
    wait_for(
        lambda: np.allclose(wall_node.position, (0.0, -1.25, 0.5), atol=1e-9),
        what="the wall re-posed in base_link",
    )
    with pytest.raises(ValueError, match="box, cylinder, sphere"):
        SceneryShape("x", "world", "cone", (1, 1, 1))


def test_scenery_from_a_source_follows_spawned_and_deleted_models(
    started: list[Viewer], tmp_path: Path
) -> None:
    """gzclient shows a model spawned (or deleted) after it started: so does the viewer."""
    from robomodel.viewer import SceneryShape

    wall = SceneryShape("wall_0", "world", "box", (0.1, 4.0, 1.0), (2.25, 0.0, 0.5))
    crate = SceneryShape("crate_1", "world", "box", (0.5, 0.5, 0.5), (0.0, 1.5, 0.25))
    world: list[tuple[SceneryShape, ...]] = [(wall,)]
    viewer = _start(
        started,
        RobotSource(str(write_arm(tmp_path))),
        fixed_frame="world",
        scenery=world[0],
        scenery_source=lambda: world[0],
    )
    wait_for(lambda: viewer.scenery is not None and viewer.scenery.shown == 1, what="the wall")
    first = viewer.scenery
    world[0] = (wall, crate)  # spawn_model -sdf: the server's world gains a model
    wait_for(
        lambda: viewer.scenery is not None and viewer.scenery.shown == 2, what="the spawned crate"
    )
    assert viewer.scenery is not first and viewer.scenery.shapes == (wall, crate)
    assert np.allclose(viewer.scenery.nodes[1].position, (0.0, 1.5, 0.25))
    assert not first.nodes  # the old nodes were taken out of the scene, not left behind
    scene = viewer.server.scene
    assert scene.get_handle_by_name("/scenery/crate_1/g") is not None
    world[0] = (crate,)  # delete_model of the wall
    wait_for(
        lambda: viewer.scenery is not None and viewer.scenery.shapes == (crate,),
        what="the wall gone",
    )
    assert scene.get_handle_by_name("/scenery/wall_0") is None
    assert scene.get_handle_by_name("/scenery/wall_0/g") is None
    assert scene.get_handle_by_name("/scenery/crate_1") is not None
    world[0] = ()
    wait_for(lambda: viewer.scenery is None, what="no scenery left")


def test_external_without_a_state_publisher_draws_from_the_other_ones_tf(
    started: list[Viewer], tmp_path: Path
) -> None:
    """Under `robomodel sim`/`control run` the process runs robot_state_publisher itself: the
    viewer adds none (no duplicate /tf) and draws the robot from that one's transforms."""
    from robomodel.runtime.msg import Header, JointState, Time
    from robomodel.runtime.nodes.robot_state_publisher import RobotStatePublisher

    path = write_arm(tmp_path)
    viewer = _start(started, RobotSource(str(path)), external=True, state_publisher=False)
    session = viewer.sessions[0]
    assert session.rsp is None and session.jsp is None
    assert viewer.context is not None
    RobotStatePublisher(viewer.context, path.read_text())  # the simulator's own
    node = viewer.context.create_node("driver")
    states = node.create_publisher(JointState, "/joint_states")
    publishers = [e.node for e in viewer.context.graph().topics["/tf"].publishers]
    assert publishers.count("/robot_state_publisher") == 1  # the simulator's, not a second one
    assert session.display is not None
    names = session.display.link_names

    sent = [0]

    def tool() -> np.ndarray | None:
        sent[0] += 1  # newer stamps: robot_state_publisher skips repeated ones
        states.publish(JointState(Header(Time(sent[0], 0)), ["joint1"], [np.pi / 2]))
        poses = session.link_poses(viewer.buffer, "base_link", np.eye(4))
        return None if poses is None or not poses.visible.all() else poses.xyz[names.index("tool")]

    wait_for(
        lambda: (p := tool()) is not None and np.allclose(p, (0.0, -1.1, 0.1), atol=1e-9),
        what="the tool posed from the other robot_state_publisher's /tf",
    )


def test_a_description_from_a_topic_is_drawn_with_the_robot_s_tf(started: list[Viewer]) -> None:
    """``robomodel view --bus zenoh --joint-states external`` with no file: RViz's RobotModel
    with Description Source: Topic. The robot comes from another process (here robomodel's
    publish-state, a stand-in for a real robot's robot_state_publisher): its latched
    /robot_description, and its /tf for the poses; the viewer runs no state publisher."""
    import signal
    import subprocess

    from tests.conftest import ROBOMODEL, unique_domain

    domain = unique_domain()
    robot = subprocess.Popen(
        [*ROBOMODEL, "publish-state", str(EXAMPLES / "gripper_description/urdf/planar_3dof.urdf"),
         "--delta", "0.02", "--domain-id", domain],
        stderr=subprocess.PIPE,
        text=True,
    )  # fmt: skip
    try:
        assert robot.stderr is not None and "publishing robot" in past_the_bus_line(robot.stderr)
        viewer = _start(
            started,
            RobotSource("", topic="/robot_description"),
            bus="zenoh",
            domain_id=int(domain),
            external=True,
        )
        session = viewer.sessions[0]
        wait_for(lambda: session.robot is not None and session.display is not None)
        assert session.robot.name == "planar_3dof" and session.rsp is None  # type: ignore[union-attr]
        assert viewer.fixed_frame == "base_link"
        wait_for(
            lambda: viewer.buffer.can_transform("base_link", "gripper"), what="the robot's /tf"
        )
        first = viewer.buffer.lookup_transform("base_link", "gripper")
        wait_for(  # --delta moves every joint: the poses drawn follow the robot's /tf
            lambda: (
                viewer.buffer.lookup_transform("base_link", "gripper").translation_m
                != first.translation_m
            ),
            what="the gripper to move",
        )
        wait_for(lambda: viewer.status.content == "OK", what="the status to clear")
    finally:
        robot.send_signal(signal.SIGINT)
        robot.wait(scaled(10))
