"""Namespaces as rclcpp and roscpp resolve them, for every node a launch file runs in
robomodel (seed 004: robot_state_publisher with ``namespace=`` and ``frame_prefix: r1/`` and a
joint_state_publisher(_gui) in the same namespace; one robot, then two).

Checked with robomodel's own graph (what ``robomodel topic list`` prints) and the frames on /tf;
the viewer's sliders (joint_state_publisher_gui's role) publish on the namespaced topic and move
that robot's frames only."""

from __future__ import annotations

import math
import threading
from pathlib import Path

import pytest

from robomodel.launch.ros2 import load_launch
from robomodel.launch.runner import LaunchRunner, RunOptions
from robomodel.runtime.msg import TFMessage
from tests.conftest import unique_domain
from tests.timing import scaled, wait_until

ARM = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base"/>
  <link name="link_1"/>
  <link name="link_2"/>
  <joint name="joint_1" type="revolute">
    <parent link="base"/><child link="link_1"/><origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
  <joint name="tip" type="fixed">
    <parent link="link_1"/><child link="link_2"/><origin xyz="0.2 0 0"/>
  </joint>
</robot>
"""

# Seed 004's robot_state_publisher (namespace, frame_prefix from [namespace, '/']) and a
# joint_state_publisher(_gui) in the same namespace.
ONE_ROBOT = """
import os
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    with open(os.path.join(os.path.dirname(__file__), 'arm.urdf')) as f:
        robot_desc = f.read()
    namespace = LaunchConfiguration('robot_name')
    frame_prefix = LaunchConfiguration('frame_prefix', default=[namespace, '/'])
    return LaunchDescription([
        DeclareLaunchArgument('robot_name', default_value='r1'),
        DeclareLaunchArgument('gui', default_value='joint_state_publisher_gui'),
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             output='screen', namespace=namespace,
             parameters=[{'robot_description': robot_desc, 'frame_prefix': frame_prefix}]),
        Node(package=LaunchConfiguration('gui'), executable=LaunchConfiguration('gui'),
             namespace=namespace),
    ])
"""

TWO_ROBOTS = """
import os
from launch import LaunchDescription
from launch.actions import GroupAction, IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource


def generate_launch_description():
    one = os.path.join(os.path.dirname(__file__), 'one.launch.py')
    return LaunchDescription([
        GroupAction([IncludeLaunchDescription(PythonLaunchDescriptionSource(one),
                                              launch_arguments={'robot_name': name}.items())])
        for name in ('r1', 'r2')
    ])
"""


def _package(tmp_path: Path) -> Path:
    launch = tmp_path / "launch"
    launch.mkdir()
    (launch / "arm.urdf").write_text(ARM)
    (launch / "one.launch.py").write_text(ONE_ROBOT)
    (launch / "two.launch.py").write_text(TWO_ROBOTS)
    return launch


class _Run:
    """A launch run in this process on the in-process bus, with a /tf listener."""

    def __init__(
        self, path: Path, args: dict[str, str], *, headless: bool = True, bus: str = "inproc"
    ) -> None:
        launch = load_launch(path, args=args)
        domain = int(unique_domain()) if bus == "zenoh" else None
        options = RunOptions(
            bus=bus, domain_id=domain, headless=headless, open_browser=False, port=0
        )
        self.runner = LaunchRunner(
            [s.node for s in launch.steps if s.node is not None], options, steps=launch.steps
        )
        self.runner.open_bus()
        self.tf: list[TFMessage] = []
        listener = self.runner.context.create_node("tf_listener")
        listener.create_subscription(TFMessage, "/tf", self.tf.append, 100)
        self.runner.start_nodes()
        self._spin = threading.Thread(target=self.runner.spin, daemon=True)
        self._spin.start()

    def publishers(self) -> dict[str, set[str]]:
        """Topic -> its publishing nodes, as ``robomodel topic list -v`` reads the graph."""
        graph = self.runner.context.graph()
        return {t: {e.node for e in info.publishers} for t, info in graph.topics.items()}

    def frames(self) -> set[str]:
        return {t.child_frame_id for m in list(self.tf) for t in m.transforms}

    def angle(self, child: str) -> float | None:
        """The last /tf rotation about z of ``child`` [rad]."""
        for message in reversed(list(self.tf)):
            for t in message.transforms:
                if t.child_frame_id == child:
                    q = t.transform.rotation
                    return 2.0 * math.atan2(q.z, q.w)
        return None

    def close(self) -> None:
        self.runner._stop.set()  # what a required node ending does
        self._spin.join(timeout=scaled(30))
        self.runner.shutdown()


@pytest.mark.parametrize("gui", ["joint_state_publisher", "joint_state_publisher_gui"])
def test_one_robot_in_a_namespace(tmp_path: Path, gui: str) -> None:
    run = _Run(_package(tmp_path) / "one.launch.py", {"robot_name": "r1", "gui": gui})
    try:
        wait_until(lambda: "r1/link_1" in run.frames(), 30, what="r1/link_1 on /tf")
        topics = run.publishers()
        assert topics["/r1/joint_states"] == {f"/r1/{gui}"}
        assert "/joint_states" not in topics  # nothing on the global topic
        assert topics["/r1/robot_description"] == {"/r1/robot_state_publisher"}
        assert topics["/tf"] == {"/r1/robot_state_publisher"}  # tf2_ros: /tf is absolute
        assert run.frames() == {"r1/link_1"}
    finally:
        run.close()


def test_two_robots_r1_and_r2(tmp_path: Path) -> None:
    run = _Run(_package(tmp_path) / "two.launch.py", {})
    try:
        wait_until(
            lambda: {"r1/link_1", "r2/link_1"} <= run.frames(), 30, what="both robots on /tf"
        )
        topics = run.publishers()
        assert topics["/r1/joint_states"] == {"/r1/joint_state_publisher_gui"}
        assert topics["/r2/joint_states"] == {"/r2/joint_state_publisher_gui"}
        assert "/joint_states" not in topics
        assert topics["/tf"] == {"/r1/robot_state_publisher", "/r2/robot_state_publisher"}
    finally:
        run.close()


def test_the_viewer_sliders_move_the_robot_of_their_namespace(tmp_path: Path) -> None:
    """Not headless: the viewer plays both joint_state_publisher_gui nodes; each robot's
    sliders publish on its own namespaced topic, and moving r2's moves r2's frames only (on
    Zenoh: the viewer has a bus session of its own, as in ``robomodel launch``)."""
    pytest.importorskip("viser")
    pytest.importorskip("zenoh")
    run = _Run(_package(tmp_path) / "two.launch.py", {}, headless=False, bus="zenoh")
    try:
        viewer = run.runner.gui.viewer
        assert viewer is not None
        sessions = {s.namespace: s for s in viewer.sessions}
        assert set(sessions) == {"/r1", "/r2"}
        for ns, session in sessions.items():
            assert session.jsp is not None and session.prefix == ns[1:] + "/"
            assert session.jsp.node.resolve_topic_name("joint_states") == f"{ns}/joint_states"
            assert session.link_frames() == (
                f"{ns[1:]}/base",
                f"{ns[1:]}/link_1",
                f"{ns[1:]}/link_2",
            )
        wait_until(
            lambda: run.publishers().get("/r2/joint_states") == {"/r2/joint_state_publisher"},
            30,
            what="the viewer's r2 sliders on /r2/joint_states",
        )
        sessions["/r2"].jsp.set_positions({"joint_1": 1.0})
        sessions["/r2"].jsp.publish_now()
        wait_until(
            lambda: abs((run.angle("r2/link_1") or 0.0) - 1.0) < 1e-6, 30, what="r2/link_1 at 1 rad"
        )
        # r1's publisher may not have sent its first /tf yet on a busy machine
        wait_until(lambda: run.angle("r1/link_1") is not None, 30, what="r1/link_1 on /tf")
        assert run.angle("r1/link_1") == pytest.approx(0.0)
    finally:
        run.close()


CONTROLLERS = """/r1/controller_manager:
  ros__parameters:
    update_rate: 100
    joint_state_broadcaster:
      type: joint_state_broadcaster/JointStateBroadcaster
    joint1_position_controller:
      type: position_controllers/JointGroupPositionController
/r1/joint1_position_controller:
  ros__parameters:
    joints: [joint1]
"""


def test_controller_manager_spawners_and_controllers_in_a_namespace(tmp_path: Path) -> None:
    """ros2_control_node, robot_state_publisher and spawners with ``namespace='r1'``: the
    spawners' default ``-c controller_manager`` is ``/r1/controller_manager`` (relative, as
    rclpy resolves it), and the controllers' topics are under /r1."""
    from robomodel.launch.model import NodeSpec, ParamSource
    from robomodel.launch.ros2.model import LaunchStep
    from robomodel.xacro import process_file
    from tests.conftest import EXAMPLES

    urdf = process_file(str(EXAMPLES / "two_link_arm/urdf/two_link_arm.urdf.xacro")).toxml()
    config = tmp_path / "controllers.yaml"
    config.write_text(CONTROLLERS)
    ns = "/r1/"
    nodes = [
        NodeSpec("ros2", "controller_manager", "ros2_control_node", None, namespace=ns,
                 parameters=(ParamSource(file=config),)),
        NodeSpec("ros2", "robot_state_publisher", "robot_state_publisher", None, namespace=ns,
                 parameters=(ParamSource(values={"robot_description": urdf}),)),
        NodeSpec("ros2", "controller_manager", "spawner", None, namespace=ns,
                 args=("joint_state_broadcaster", "joint1_position_controller")),
    ]  # fmt: skip
    runner = LaunchRunner(
        nodes,
        RunOptions(bus="inproc", headless=True),
        steps=tuple(LaunchStep("node", n) for n in nodes),
    )
    runner.open_bus()
    try:
        runner.start_nodes()
        spawner = runner.started[2].handle
        runner.context.spin(until=lambda: spawner.exit_code() is not None)
        assert spawner.exit_code() == 0
        graph = runner.context.graph()
        assert "/r1/controller_manager/list_controllers" in graph.services
        assert "/controller_manager/list_controllers" not in graph.services
        topics = set(graph.topics)
        assert {"/r1/joint_states", "/r1/joint1_position_controller/commands"} <= topics
        assert "/joint_states" not in topics
    finally:
        runner.shutdown()


def test_names_resolve_as_rcl_and_roscpp_do() -> None:
    """Relative names go in the namespace, ``~`` in the node, ``/x`` stays; remaps match the
    resolved name (either side may be relative) and give a resolved one."""
    from robomodel.launch.model import NodeSpec
    from robomodel.launch.nodes.base import NodeContext, ViewerRequest

    def ctx(namespace: str, remaps: tuple[tuple[str, str], ...] = ()) -> NodeContext:
        spec = NodeSpec("ros1", "p", "e", "jsp", namespace=namespace, remaps=remaps)
        return NodeContext(spec, None, None, ViewerRequest(), lambda _line: None)

    assert ctx("/r1/").resolve_name("joint_states") == "/r1/joint_states"
    assert ctx("/").resolve_name("joint_states") == "/joint_states"
    assert ctx("/r1/").resolve_name("/tf") == "/tf"
    assert ctx("/r1/").resolve_name("~/state") == "/r1/jsp/state"
    remapped = ctx("/r1/", (("joint_states", "states"), ("/tf", "tf_r1")))
    assert remapped.resolve_name("joint_states") == "/r1/states"
    assert remapped.resolve_name("/tf") == "/r1/tf_r1"
    assert ctx("/r1/", (("/r1/joint_states", "/js"),)).resolve_name("joint_states") == "/js"
