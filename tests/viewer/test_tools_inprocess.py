"""The rqt tools in a viewer in this process (in-process bus, no browser)."""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

from robomodel.runtime.msg import Float64, Twist
from robomodel.runtime.node import Node
from robomodel.runtime.params import SetResult
from robomodel.viewer import RobotSource, Viewer, ViewerOptions
from tests.timing import scaled
from tests.viewer.conftest import wait_for
from tests.viewer.robots import write_arm


@pytest.fixture
def viewer(tmp_path: Path) -> Iterator[Viewer]:
    viewer = Viewer(ViewerOptions(sources=(RobotSource(str(write_arm(tmp_path))),), port=0))
    viewer.start()
    yield viewer
    viewer.close()


def on_loop(viewer: Viewer, work: Callable[[], Any]) -> Any:
    """Run ``work`` on the viewer's loop thread (which owns the nodes) and return its result."""
    done = threading.Event()
    box: list[Any] = []

    def run() -> None:
        box.append(work())
        done.set()

    viewer._post(run)
    assert done.wait(scaled(10))
    return box[0]


def test_steering_publishes_twist_at_10_hz_and_zero_once(viewer: Viewer) -> None:
    assert viewer.context is not None
    context = viewer.context
    twists: list[Twist] = []
    on_loop(
        viewer,
        lambda: context.create_node("probe").create_subscription(
            Twist, "/my/cmd_vel", twists.append
        ),
    )
    steering = viewer.tools.steering
    steering.topic.value = "/my/cmd_vel"
    steering.linear.value = 0.4
    steering.angular.value = -0.8
    wait_for(lambda: len(twists) >= 3, what="three Twists")
    assert (twists[-1].linear.x, twists[-1].angular.z) == (0.4, -0.8)
    steering.halt()
    wait_for(lambda: twists[-1].linear.x == 0.0, what="the zero command")
    count = len(twists)
    wait_for(lambda: steering.command.zero_sent, what="zero sent")
    threading.Event().wait(scaled(0.35))
    assert len(twists) <= count + 1  # zero is sent once, not every tick


def test_publisher_plot_and_parameters_on_the_bus(viewer: Viewer) -> None:
    assert viewer.context is not None
    context = viewer.context
    tools = viewer.tools
    received: list[Float64] = []

    def make_node() -> Node:
        node = context.create_node("tuned")
        node.declare_parameter("gain", 1.5)
        node.declare_parameter("enabled", True)
        node.parameters.add_set_callback(
            lambda c: (
                SetResult(False, "gain must be positive")
                if c.get("gain", 1.0) <= 0
                else SetResult(True)
            )
        )
        node.create_subscription(Float64, "/cmd", received.append)
        return node

    node: Node = on_loop(viewer, make_node)
    pub = tools.publisher
    pub.topic.value = "/cmd"
    pub.expression.value = "offset + i"
    pub.variables.value = "offset=10"
    pub.rate.value = 20.0
    pub.enabled.value = True
    wait_for(lambda: len(received) >= 3, what="published expressions")
    assert [m.data for m in received[:3]] == [10.0, 11.0, 12.0]
    # The plot sees the topic once the graph shows it, and records samples.
    wait_for(lambda: "/cmd" in tools.tools.topics, what="/cmd in the graph")
    tools.plot.add("/cmd/data")
    wait_for(lambda: tools.plot.data.series and len(tools.plot.data.series[0].values) >= 3)
    wait_for(lambda: tools.plot.chart is not None, what="the chart")
    x, y = tools.plot.data.window(10.0)
    assert x.size >= 2 and y[-1] >= 12.0
    tools.plot.add("/cmd/nothing")
    assert "has no field 'nothing'" in tools.plot.status.content
    pub.enabled.value = False
    # Parameters: another node's parameters, set and refused.
    wait_for(lambda: "/tuned" in tools.parameters.node_dropdown.options, what="node in graph")
    tools.parameters.node_dropdown.value = "/tuned"
    wait_for(lambda: "gain" in tools.parameters.controls, what="parameter controls")
    assert tools.parameters.controls["gain"].value == 1.5
    result: list[bool] = []
    tools.tools.bus.submit(lambda: result.append(tools.parameters.set("/tuned", "gain", 4.0)))
    wait_for(lambda: result, what="a set")
    assert result == [True] and node.get_parameter("gain") == 4.0
    tools.tools.bus.submit(lambda: result.append(tools.parameters.set("/tuned", "gain", -1.0)))
    wait_for(lambda: len(result) == 2, what="a refused set")
    assert result[1] is False and node.get_parameter("gain") == 4.0
    assert "gain must be positive" in tools.parameters.result.content
    assert tools.parameters.controls["gain"].value == 4.0  # the old value is back


def test_the_graph_s_scan_odometry_and_ground_truth_get_displays_in_the_fixed_frame(
    viewer: Viewer,
) -> None:
    """Without a config the viewer adds a LaserScan, an Odometry and a Ground truth display
    for the graph's topics (what its Overlays folder did), once each, placed through TF in
    the fixed frame (base_link): odometry blue, ground truth orange."""
    import numpy as np

    from robomodel.runtime.msg import (
        Header,
        LaserScan,
        Odometry,
        TFMessage,
        Transform,
        TransformStamped,
        Vector3,
    )
    from robomodel.runtime.qos import Durability, QoSProfile

    assert viewer.context is not None
    context = viewer.context
    panel = viewer.displays_panel

    def create() -> tuple[Any, Any, Any]:
        node = context.create_node("odometry")
        static = node.create_publisher(
            TFMessage, "/tf_static", QoSProfile(10, Durability.TRANSIENT_LOCAL)
        )
        static.publish(
            TFMessage(
                [
                    TransformStamped(
                        Header(frame_id="base_link"), "odom", Transform(Vector3(z=1.0))
                    ),
                    TransformStamped(
                        Header(frame_id="base_link"), "laser", Transform(Vector3(x=2.0))
                    ),
                ]
            )
        )
        return (
            node,
            node.create_publisher(Odometry, "/odom", 10),
            node.create_publisher(LaserScan, "/scan", 10),
            node.create_publisher(Odometry, "/ground_truth/odom", 10),
        )

    _node, odom, scan, truth = on_loop(viewer, create)
    wait_for(lambda: len(panel.follower.added) == 3, what="the displays for the graph's topics")
    shown = {d.name: (d.class_name, d.topic) for d in viewer.displays.displays}
    assert shown == {"Grid": ("Grid", ""), "RobotModel": ("RobotModel", ""), "TF": ("TF", ""),
                     "LaserScan": ("LaserScan", "/scan"),
                     "Odometry": ("Odometry", "/odom"),
                     "Ground truth": ("Odometry", "/ground_truth/odom")}  # fmt: skip
    wait_for(lambda: len(viewer.displays._subscribed) == 3, what="their subscriptions")

    def publish() -> None:
        for x, y in ((0.0, 0.0), (1.0, 0.0), (1.0, 0.05), (1.0, 1.0)):
            msg = Odometry(Header(frame_id="odom"), "base_link")
            msg.pose.pose.position.x, msg.pose.pose.position.y = x, y
            msg.pose.pose.orientation.w = 1.0
            odom.publish(msg)
        scan.publish(
            LaserScan(Header(frame_id="laser"), range_min=0.1, range_max=5.0, ranges=[1.0])
        )
        for x in (0.0, 0.5):  # the ground truth, in odom too here
            msg = Odometry(Header(frame_id="odom"), "base_link")
            msg.pose.pose.position.x = x
            msg.pose.pose.orientation.w = 1.0
            truth.publish(msg)

    on_loop(viewer, publish)
    odometry, ground_truth = panel.follower.added["Odometry"], panel.follower.added["Ground truth"]
    wait_for(lambda: len(odometry.trail.poses) == 3, what="the odometry arrows")
    # RViz's Position Tolerance (0.1 m) skips the 5 cm step; odom is 1 m above base_link
    xyz = np.array([T[:3, 3] for T in odometry.trail.matrices()])
    assert xyz == pytest.approx(np.array([[0, 0, 1], [1, 0, 1], [1, 1, 1.0]]))
    wait_for(lambda: len(ground_truth.trail.poses) == 2, what="the ground-truth arrows")
    assert (odometry.option("Shape/Color"), ground_truth.option("Shape/Color")) == (
        "40; 200; 255", "255; 150; 0")  # fmt: skip
    # RViz's arrow scaled to half the robot's size, so that the trail never hides the robot;
    # a display the user adds has RViz's 1 m shaft
    from robomodel.viewer.layout import zero_pose_extent_m

    robot = viewer.sessions[0].robot
    assert robot is not None
    half_m = 0.5 * zero_pose_extent_m(robot)
    for added in (odometry, ground_truth):
        length_m = added.option("Shape/Shaft Length") + added.option("Shape/Head Length")
        assert length_m == pytest.approx(half_m)
        assert added.option("Shape/Head Radius") == pytest.approx(0.1 * half_m / 1.3)
    assert odometry.node("arrows").head_length == pytest.approx(0.3 * half_m / 1.3)
    user = on_loop(viewer, lambda: panel.add("Odometry", values={"Topic": "/odom"}))
    assert (user.option("Shape/Shaft Length"), user.option("Keep")) == (1.0, 100)
    on_loop(viewer, lambda: panel.remove(panel.rows[-1]))
    # the trails only: no covariance shapes (a diff drive's 1e6 variances span a kilometre)
    assert not odometry.option("Covariance/Value") and not ground_truth.option("Covariance/Value")
    assert not any(key.startswith("covariance") for key in odometry._nodes)
    laser = panel.follower.added["LaserScan"]
    wait_for(lambda: laser.node("points") is not None, what="the scan drawn")
    assert np.asarray(laser.node("points").points) == pytest.approx(
        np.array([[3.0, 0.0, 0.0]]), abs=1e-3
    )
    # a display removed stays removed; a topic already shown is not added again
    on_loop(viewer, lambda: panel.remove(panel.rows[[r.display for r in panel.rows].index(laser)]))
    on_loop(viewer, lambda: context.create_node("more").create_publisher(LaserScan, "/scan2", 1))
    wait_for(lambda: "/scan2" in panel.topics, what="/scan2 in the graph")
    on_loop(viewer, panel.follower)
    names = [d.name for d in viewer.displays.displays]
    assert names == ["Grid", "RobotModel", "TF", "Odometry", "Ground truth"]


def test_stamped_steering_refused_expression_and_no_tools(viewer: Viewer, tmp_path: Path) -> None:
    from robomodel.runtime.msg import TwistStamped

    assert viewer.context is not None
    context = viewer.context
    stamped: list[TwistStamped] = []
    on_loop(
        viewer,
        lambda: context.create_node("probe").create_subscription(
            TwistStamped, "/stamped", stamped.append
        ),
    )
    steering = viewer.tools.steering
    steering.stamped.value = True
    steering.topic.value = "/stamped"
    steering.angular.value = 1.5
    wait_for(lambda: stamped and stamped[-1].twist.angular.z == 1.5, what="a TwistStamped")
    assert stamped[-1].header.stamp.sec > 0
    # A slider's range follows its maximum.
    steering.angular_max.value = 1.0
    wait_for(lambda: steering.angular.max == 1.0 and steering.angular.value == 1.0)
    pub = viewer.tools.publisher
    pub.expression.value = "__import__('os').getcwd()"
    pub.enabled.value = True
    wait_for(lambda: "refused" in pub.status.content, what="the refusal shown")
    assert "cannot call" in pub.status.content and pub.enabled.value is False
    quiet = Viewer(
        ViewerOptions(sources=(RobotSource(str(write_arm(tmp_path))),), port=0, tools=False)
    )
    quiet.start()
    try:
        assert quiet.tools is None
    finally:
        quiet.close()
