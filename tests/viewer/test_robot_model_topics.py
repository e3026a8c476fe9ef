"""A RobotModel display naming a description the viewer did not load loads that robot, as
RViz's does: RViz 2 subscribes to its Description Topic (std_msgs/String, transient
local); the robot is drawn from TF like the viewer's own, and goes with its display."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from robomodel.runtime.msg import String, TFMessage
from robomodel.runtime.qos import latched
from robomodel.runtime.tf_listener import to_msg
from robomodel.tf import TransformStamped
from robomodel.viewer import RobotSource, Viewer, ViewerOptions
from robomodel.viewer.displays.base import StatusLevel
from robomodel.viewer.displays.robot_model import LinkUpdates
from tests.ros1wire.conftest import Ros1, ros1  # noqa: F401  (the fixture)
from tests.viewer.conftest import wait_for
from tests.viewer.planar_viewer import PLANAR, planar_viewer  # noqa: F401  (the fixture)
from tests.viewer.test_tools_inprocess import on_loop

MAST = """<robot name="mast">
  <link name="mast_base"><visual><geometry><box size="0.2 0.2 0.2"/></geometry></visual></link>
  <link name="mast_top"><visual><geometry><sphere radius="0.1"/></geometry></visual></link>
  <joint name="lift" type="fixed">
    <parent link="mast_base"/><child link="mast_top"/><origin xyz="0 0 1"/>
  </joint>
</robot>"""


def _static(parent: str, child: str, xyz: tuple[float, float, float]) -> object:
    T = np.eye(4)
    T[:3, 3] = xyz
    return to_msg(TransformStamped.from_matrix(parent, child, T, 0))


def _link_xyz(viewer: Viewer, robot: str, link: str) -> np.ndarray | None:
    """Where the page draws ``link`` of the robot named ``robot`` (None: not drawn); read on
    the loop thread, which rebuilds a drawing when its description changes."""

    def read() -> np.ndarray | None:
        session = next((s for s in viewer.sessions if s.robot is not None and s.robot.name == robot), None)  # fmt: skip
        if session is None or session.display is None:
            return None
        drawing = session.display
        handle = drawing._links[drawing.link_names.index(link)]
        # a copy: placing writes the handle's array in place
        return np.array(handle.position) if handle.visible else None

    return on_loop(viewer, read)  # type: ignore[no-any-return]


def test_a_robot_model_on_another_topic_loads_draws_and_drops_that_robot(viewer: Viewer) -> None:
    assert viewer.context is not None
    node = on_loop(viewer, lambda: viewer.context.create_node("mast_publisher"))
    description = on_loop(viewer, lambda: node.create_publisher(String, "/r2/robot_description", latched()))  # fmt: skip
    statics = on_loop(viewer, lambda: node.create_publisher(TFMessage, "/tf_static", latched(10)))
    tree = TFMessage([_static("base_link", "mast_base", (0.0, 2.0, 0.0)),
                      _static("mast_base", "mast_top", (0.0, 0.0, 1.0))])  # fmt: skip
    on_loop(viewer, lambda: statics.publish(tree))
    assert description.get_subscription_count() == 0  # the viewer did not load it
    panel = viewer.displays_panel
    model = on_loop(viewer, lambda: panel.add("RobotModel", name="Mast",
                                              values={"Description Topic": "r2/robot_description"}))  # fmt: skip
    wait_for(lambda: model.status.text == "Waiting for the robot description on [/r2/robot_description]",
             what="the waiting status")  # fmt: skip
    assert model.status.level is StatusLevel.WARN
    assert description.get_subscription_count() == 1  # transient local: RViz 2's QoS
    on_loop(viewer, lambda: description.publish(String("<robot name='mast'><link name='a'/>")))
    wait_for(lambda: model.status.level is StatusLevel.ERROR, what="the URDF error")
    assert model.status.text.startswith("URDF: ")
    on_loop(viewer, lambda: description.publish(String(MAST)))
    wait_for(lambda: (p := _link_xyz(viewer, "mast", "mast_top")) is not None and np.allclose(p, (0, 2, 1)),
             what="the mast's top drawn from TF at (0, 2, 1)")  # fmt: skip
    wait_for(lambda: model.status.text == "Showing mast", what="its status")
    mast = next(s for s in viewer.sessions if s.robot is not None and s.robot.name == "mast")
    assert mast.display is not None and mast.display.shown
    assert mast.rsp is None and mast.jsp is None  # RViz publishes nothing for its robot
    own = viewer.sessions[0]
    assert own.robot is not None and own.robot.name == "planar_3dof" and own.display is not None
    on_loop(viewer, lambda: model.set_enabled(False))  # RViz's onDisable: unsubscribe, clear
    wait_for(lambda: mast not in viewer.sessions, what="the mast dropped while disabled")
    on_loop(viewer, lambda: model.set_enabled(True))  # the latched description comes again
    wait_for(lambda: model.status.text == "Showing mast", what="the mast back")
    mast = next(s for s in viewer.sessions if s.robot is not None and s.robot.name == "mast")
    assert mast.display is not None
    root = mast.display.root
    assert root in viewer.server.scene._handle_from_node_name  # viser 1.1's table of nodes

    on_loop(viewer, lambda: panel.remove(panel.rows[-1]))  # the display removed: the robot goes
    wait_for(lambda: mast not in viewer.sessions, what="the mast dropped")
    wait_for(lambda: description.get_subscription_count() == 0, what="its subscription ended")
    assert root not in viewer.server.scene._handle_from_node_name  # viser 1.1's table of nodes
    assert viewer.sessions == [own] and own.display.shown


def test_on_ros_1_the_robot_comes_from_the_master_s_parameter(ros1: Ros1, monkeypatch: pytest.MonkeyPatch) -> None:  # noqa: F811  # fmt: skip
    """RViz 1's RobotModel reads its Robot Description parameter from the master, asking again
    every second until it is set (here by Debian's rosparam, after the display was added)."""
    monkeypatch.setenv("ROS_IP", "127.0.0.1")
    ros1.roscore()
    options = ViewerOptions(sources=(RobotSource(str(PLANAR)),), port=0, bus="ros1",
                            master=ros1.uri, reload_period_s=0.05)  # fmt: skip
    viewer = Viewer(options)
    viewer.start()
    try:
        panel = viewer.displays_panel
        model = on_loop(viewer, lambda: panel.add("rviz/RobotModel", values={"Description Topic": "/r2/robot_description"}))  # fmt: skip
        wait_for(lambda: model.status.text.startswith("Waiting for the robot description"),
                 what="the waiting status")  # fmt: skip
        assert ros1.run("/usr/bin/rosparam", "set", "/r2/robot_description", MAST).returncode == 0
        # loaded from the parameter; its TF is not on this graph: RViz's status for its links
        wait_for(lambda: model.status.text == "No transform from [mast_base] to [base_link]",
                 what="the robot from the parameter")  # fmt: skip
        mast = next(s for s in viewer.sessions if s.robot is not None and s.robot.name == "mast")
        assert mast.display is not None and mast.display.shown
        on_loop(viewer, lambda: model.set_option("Description Topic", "/r3/robot_description"))
        wait_for(lambda: mast not in viewer.sessions, what="the mast dropped with its topic")
        wait_for(lambda: model.status.text.startswith("Waiting for the robot description on [/r3/"),
                 what="the new parameter awaited")  # fmt: skip
    finally:
        viewer.close()


def test_tf_prefix_places_link_l_at_prefix_slash_l() -> None:
    """RViz looks link L up at ``<TF Prefix>/L`` (rviz_default_plugins
    robot/tf_link_updater.cpp): a robot_state_publisher with frame_prefix ``r1/`` is drawn by a
    RobotModel whose TF Prefix is ``r1``; another prefix gives RViz's status for its links."""
    from robomodel.runtime.nodes.robot_state_publisher import RobotStatePublisher

    options = ViewerOptions(sources=(RobotSource(str(PLANAR)),), port=0, fixed_frame="r1/mast_base")  # fmt: skip
    viewer = Viewer(options)
    viewer.start()
    try:
        assert viewer.context is not None
        on_loop(viewer, lambda: RobotStatePublisher(viewer.context, MAST, namespace="/r2",
                                                    parameters={"frame_prefix": "r1/"}))  # fmt: skip
        panel = viewer.displays_panel
        values = {"Description Topic": "/r2/robot_description", "TF Prefix": "r1"}
        model = on_loop(viewer, lambda: panel.add("RobotModel", values=values))
        wait_for(lambda: (p := _link_xyz(viewer, "mast", "mast_top")) is not None and np.allclose(p, (0, 0, 1)),
                 what="the mast's top at r1/mast_top")  # fmt: skip
        # named with the prefix its frames have, as a FILE's robot with --prefix is
        wait_for(lambda: model.status.text == "Showing r1/mast", what="its status")
        on_loop(viewer, lambda: model.set_option("TF Prefix", "r9"))
        wait_for(lambda: model.status.text == "No transform from [r9/mast_base] to [r1/mast_base]",
                 what="RViz's status for a frame TF lacks")  # fmt: skip
        assert model.status.level is StatusLevel.ERROR
        wait_for(lambda: _link_xyz(viewer, "mast", "mast_top") is None, what="the top not drawn")
        on_loop(viewer, lambda: model.set_option("TF Prefix", "r1/"))
        wait_for(lambda: model.status.text == "Showing r1/mast", what="drawn again at r1/")
        wait_for(lambda: _link_xyz(viewer, "mast", "mast_top") is not None, what="the top again")
    finally:
        viewer.close()


def test_link_updates_follow_rviz_s_update_interval() -> None:
    """RViz's RobotModel ``update``: every cycle below 0.0001 s, else once the interval passed
    since the last placement; at once for a new fixed frame or a new drawing."""
    updates = LinkUpdates()
    assert updates.due(0.0, "map")
    updates.placed(0.0, "map")
    assert updates.due(0.001, "map")  # Update Interval 0: every cycle
    updates.interval_s = 0.5
    updates.placed(10.0, "map")
    assert not updates.due(10.49, "map") and updates.next_s() == 10.5
    assert updates.due(10.5, "map")
    assert updates.due(10.1, "odom")  # RViz's fixedFrameChanged
    updates.reset()
    assert updates.due(10.1, "map")  # a new drawing
    assert updates.placements == 2


def test_links_are_placed_at_most_once_per_update_interval(viewer: Viewer) -> None:
    """With an Update Interval of an hour, a joint that moves (its /tf in the viewer's buffer,
    scene updates sent since) leaves the drawn links where they were; at 0 they follow."""
    session = viewer.sessions[0]
    model = next(d for d in viewer.displays.displays if d.class_name == "RobotModel")
    wait_for(lambda: _link_xyz(viewer, "planar_3dof", "gripper") is not None, what="the arm")
    start = _link_xyz(viewer, "planar_3dof", "gripper")
    on_loop(viewer, lambda: model.set_option("Update Interval", 3600.0))
    wait_for(lambda: session.link_updates.interval_s == 3600.0, what="the interval taken")
    placements = session.link_updates.placements
    session.queue_positions({"joint_1": np.pi / 2})
    wait_for(lambda: viewer.buffer.lookup_transform("base_link", "gripper").translation_m[1] > 0.5,
             what="the gripper's new /tf")  # fmt: skip
    sent = viewer.updates_sent
    wait_for(lambda: viewer.updates_sent > sent + 2, what="scene updates after the move")
    assert session.link_updates.placements == placements  # not placed again within the hour
    assert np.allclose(_link_xyz(viewer, "planar_3dof", "gripper"), start)  # type: ignore[arg-type]
    on_loop(viewer, lambda: model.set_option("Update Interval", 0.0))
    wait_for(lambda: (p := _link_xyz(viewer, "planar_3dof", "gripper")) is not None and p[1] > 0.5,
             what="the gripper drawn where /tf has it")  # fmt: skip
    # counted just after the links are written, on the thread that places them
    wait_for(lambda: session.link_updates.placements > placements, what="the placement counted")


def test_a_robot_of_another_process_on_the_zenoh_bus(tmp_path: Path) -> None:
    """Over rmw_zenoh's wire: another process (robomodel publish-state, robot_state_publisher
    in /r2 with frame_prefix r1/) publishes its description and TF; a viewer of another robot
    draws it once a RobotModel names /r2/robot_description with TF Prefix r1."""
    import signal
    import subprocess

    from tests.conftest import ROBOMODEL, past_the_bus_line, unique_domain
    from tests.timing import scaled
    from tests.viewer.robots import write_arm

    domain = unique_domain()
    robot = subprocess.Popen(
        [*ROBOMODEL, "publish-state", str(PLANAR), "--namespace", "r2", "--prefix", "r1/",
         "--domain-id", domain],
        stderr=subprocess.PIPE,
        text=True,
    )  # fmt: skip
    options = ViewerOptions(sources=(RobotSource(str(write_arm(tmp_path))),), port=0, bus="zenoh",
                            domain_id=int(domain), fixed_frame="r1/base_link")  # fmt: skip
    viewer = Viewer(options)
    try:
        assert robot.stderr is not None and "publishing robot" in past_the_bus_line(robot.stderr)
        viewer.start()
        panel = viewer.displays_panel
        values = {"Description Topic": "/r2/robot_description", "TF Prefix": "r1"}
        model = on_loop(viewer, lambda: panel.add("RobotModel", name="R2", values=values))
        wait_for(lambda: model.status.text == "Showing r1/planar_3dof", what="the other robot")
        wait_for(lambda: viewer.buffer.can_transform("r1/base_link", "r1/gripper"), what="its TF")
        expected = viewer.buffer.lookup_transform("r1/base_link", "r1/gripper").translation_m
        wait_for(lambda: (p := _link_xyz(viewer, "planar_3dof", "gripper")) is not None and np.allclose(p, expected),
                 what="its gripper where its TF puts r1/gripper")  # fmt: skip
        assert [s.robot.name for s in viewer.sessions if s.robot] == ["arm", "planar_3dof"]
        on_loop(viewer, lambda: panel.remove(panel.rows[-1]))
        wait_for(lambda: len(viewer.sessions) == 1, what="the other robot dropped")
    finally:
        viewer.close()
        robot.send_signal(signal.SIGINT)
        robot.wait(scaled(10))


MAST_CONFIG = """Visualization Manager:
  Class: ""
  Displays:
    - Class: rviz_default_plugins/RobotModel
      Enabled: true
      Name: Mast
      Description Source: Topic
      Description Topic:
        Value: /r2/robot_description
  Global Options:
    Fixed Frame: base_link
"""


def test_a_config_s_robot_model_on_another_topic_loads_that_robot(tmp_path: Path) -> None:
    """The same from a .rviz file: RViz 2 opens it and draws the robot published there (and
    not the viewer's own, which no RobotModel of the file names)."""
    from robomodel.viewer.rviz_document import open_rviz_document
    from robomodel.viewer.rviz_model import RvizDialect

    path = tmp_path / "mast.rviz"
    path.write_text(MAST_CONFIG)
    document, _ = open_rviz_document(str(path), RvizDialect.ROS2)
    viewer = Viewer(ViewerOptions(sources=(RobotSource(str(PLANAR)),), port=0, rviz=document))
    viewer.start()
    try:
        assert viewer.context is not None
        node = on_loop(viewer, lambda: viewer.context.create_node("mast_publisher"))
        description = on_loop(viewer, lambda: node.create_publisher(String, "/r2/robot_description", latched()))  # fmt: skip
        on_loop(viewer, lambda: description.publish(String(MAST)))
        model = viewer.displays.get("Mast")
        wait_for(lambda: any(s.robot is not None and s.robot.name == "mast" and s.display is not None
                             for s in viewer.sessions), what="the mast loaded")  # fmt: skip
        mast = next(s for s in viewer.sessions if s.robot is not None and s.robot.name == "mast")
        wait_for(lambda: mast.display.shown, what="the mast shown")  # type: ignore[union-attr]
        assert viewer.sessions[0].display is not None and not viewer.sessions[0].display.shown
        wait_for(lambda: model.status.text == "No transform from [mast_base] to [base_link]",
                 what="RViz's status: no TF for the mast yet")  # fmt: skip
    finally:
        viewer.close()
