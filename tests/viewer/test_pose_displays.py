"""Pose, PoseArray, PoseWithCovariance, Odometry, Path and Wrench displays on a fake scene:
their shapes where TF puts them, RViz's defaults and statuses."""

from __future__ import annotations

import math

import numpy as np
import pytest

from robomodel.runtime.msg import get_message_type
from robomodel.viewer.displays import display_class
from tests.viewer.fake_scene import FakeScene, fake_context, lookup_from

PoseStamped = get_message_type("geometry_msgs/msg/PoseStamped")
PoseArray = get_message_type("geometry_msgs/msg/PoseArray")
Pose = get_message_type("geometry_msgs/msg/Pose")
PoseWithCovarianceStamped = get_message_type("geometry_msgs/msg/PoseWithCovarianceStamped")
Odometry = get_message_type("nav_msgs/msg/Odometry")
Path = get_message_type("nav_msgs/msg/Path")
WrenchStamped = get_message_type("geometry_msgs/msg/WrenchStamped")


def at(x: float = 0.0, y: float = 0.0, yaw: float = 0.0) -> object:
    pose = Pose()
    pose.position.x, pose.position.y = x, y
    pose.orientation.z, pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    return pose


def shifted(x: float) -> np.ndarray:
    T = np.eye(4)
    T[0, 3] = x
    return T


def start(class_name: str, **values: object) -> tuple[object, FakeScene]:
    scene = FakeScene()
    return display_class(class_name)("d", fake_context(scene), {"Topic": "/t", **values}), scene


def test_pose_arrow_in_fixed_frame_and_missing_transform() -> None:
    display, scene = start("Pose")
    msg = PoseStamped(pose=at(1.0, 0.0, math.pi / 2))
    msg.header.frame_id = "base"
    display.receive(msg)
    assert display.draw(lookup_from({})).text == "No transform from [base] to [map]"
    assert display.draw(lookup_from({"base": shifted(2.0)})).text == "1 messages received"
    (node,) = scene.visible().values()
    assert node.kind == "arrows"
    # RViz's default arrow: shaft 1 + head 0.3 along the pose's x (here the fixed frame's +y)
    np.testing.assert_allclose(node.kwargs["points"], [[[3, 0, 0], [3, 1.3, 0]]], atol=1e-12)
    assert node.kwargs["colors"] == (255, 25, 0)
    assert (node.kwargs["shaft_radius"], node.kwargs["head_radius"]) == (0.05, 0.1)
    display.set_option("Shape", "Axes")
    display.draw(lookup_from({"base": shifted(2.0)}))
    (node,) = scene.visible().values()
    assert node.kind == "batched_axes" and node.kwargs["axes_length"] == 1.0


def test_pose_array_flat_arrows_default() -> None:
    display, scene = start("PoseArray")
    msg = PoseArray(poses=[at(0, 0), at(1, 1, math.pi)])
    msg.header.frame_id = "map"
    display.receive(msg)
    display.draw(lookup_from({"map": np.eye(4)}))
    (node,) = scene.visible().values()
    assert node.kind == "line_segments" and node.kwargs["points"].shape == (6, 2, 3)
    np.testing.assert_allclose(node.kwargs["points"][3], [[1, 1, 0], [0.7, 1, 0]], atol=1e-12)


def test_pose_with_covariance_ellipsoid() -> None:
    display, scene = start("PoseWithCovariance")
    msg = PoseWithCovarianceStamped()
    msg.header.frame_id = "odom"
    msg.pose.pose = at(1.0, 2.0)
    cov = np.zeros((6, 6))
    cov[:3, :3] = np.diag([4.0, 1.0, 0.25])
    msg.pose.covariance = list(cov.ravel())
    display.receive(msg)
    display.draw(lookup_from({"odom": shifted(1.0)}))
    ellipsoid = scene.nodes["/displays/d/covariance"]
    assert ellipsoid.kind == "icosphere" and ellipsoid.kwargs["position"] == (2.0, 2.0, 0.0)
    assert sorted(ellipsoid.kwargs["scale"]) == [0.5, 1.0, 2.0]
    assert ellipsoid.kwargs["opacity"] == 0.3 and ellipsoid.kwargs["color"] == (204, 51, 204)
    display.set_option("Covariance/Value", False)
    display.draw(lookup_from({"odom": shifted(1.0)}))
    assert "/displays/d/covariance" not in scene.nodes


def odom(x: float, yaw: float = 0.0) -> object:
    msg = Odometry()
    msg.header.frame_id = "odom"
    msg.pose.pose = at(x, 0.0, yaw)
    return msg


def test_odometry_keeps_arrows_by_tolerance_and_keep() -> None:
    display, scene = start("Odometry", Keep=3, **{"Covariance/Value": False})
    lookup = lookup_from({"odom": np.eye(4)})
    for x in (0.0, 0.05, 0.2, 0.4, 0.6, 0.8):  # 0.05 is within the 0.1 m tolerance
        display.receive(odom(x))
    assert display.draw(lookup).text == "3 arrows kept"
    node = scene.nodes["/displays/d/arrows"]
    np.testing.assert_allclose(node.kwargs["points"][:, 0, 0], [0.4, 0.6, 0.8])
    display.receive(odom(0.8, yaw=0.5))  # turned more than 0.1 rad: kept
    display.draw(lookup)
    assert len(display.trail.poses) == 3
    display.set_option("Keep", 1)
    assert scene.nodes["/displays/d/arrows"].kwargs["points"].shape == (1, 2, 3)


def test_path_line_through_poses_with_offset_and_buffer() -> None:
    display, scene = start("Path", **{"Offset/Z": 0.5})
    msg = Path(poses=[PoseStamped(pose=at(0, 0)), PoseStamped(pose=at(1, 0)), PoseStamped(pose=at(1, 1))])  # fmt: skip
    msg.header.frame_id = "map"
    display.receive(msg)
    assert display.draw(lookup_from({"map": np.eye(4)})).text == "1 messages received"
    (node,) = scene.visible().values()
    assert node.kind == "line_segments" and node.kwargs["colors"] == (25, 255, 0)
    np.testing.assert_allclose(node.kwargs["points"][:, 1], [[1, 0, 0], [1, 1, 0]])
    assert node.kwargs["position"] == (0.0, 0.0, 0.5)
    display.receive(msg)
    display.draw(lookup_from({"map": np.eye(4)}))
    assert len(scene.visible()) == 1  # Buffer Length 1


def test_wrench_arrows_nan_refused_and_history() -> None:
    display, scene = start("Wrench")
    msg = WrenchStamped()
    msg.header.frame_id = "tool"
    msg.wrench.force.z = 1.0  # 1 N x scale 2 = 2 m > width 0.5
    msg.wrench.torque.x = 0.1  # 0.2 m: not longer than the width, hidden
    display.receive(msg)
    display.draw(lookup_from({"tool": shifted(1.0)}))
    (force,) = scene.visible().values()
    assert force.name.endswith("_force") and force.kwargs["colors"] == (204, 51, 51)
    np.testing.assert_allclose(force.kwargs["points"], [[[1, 0, 0], [1, 0, 2.6]]])
    bad = WrenchStamped()
    bad.header.frame_id = "tool"
    bad.wrench.force.x = float("nan")
    display.receive(bad)
    status = display.draw(lookup_from({"tool": shifted(1.0)}))
    assert status.text == "Message contained invalid floating point values (nans or infs)"
    display.set_option("Accept NaN Values", True)
    display.receive(bad)
    assert display.draw(lookup_from({"tool": shifted(1.0)})).level.value == "ok"


@pytest.mark.parametrize(
    ("class_name", "option", "default"),
    [("Odometry", "Shape/Shaft Length", 1.0), ("PoseArray", "Arrow Length", 0.3),
     ("Path", "Line Width", 0.03), ("Wrench", "Arrow Width", 0.5), ("Map", "Alpha", 0.7),
     ("PointCloud2", "Decay Time", 0.0), ("Image", "Median window", 5),
     ("Camera", "Overlay Alpha", 0.5)],
)  # fmt: skip
def test_rviz_defaults(class_name: str, option: str, default: object) -> None:
    display, _ = start(class_name)
    assert display.option(option) == default


# An Odometry display as RViz 2 saves it (nav2_bringup's nav2_default_view.rviz form):
# properties with children are maps with their own value under "Value".
ODOMETRY_ROS2 = {
    "Angle Tolerance": 0.1,
    "Covariance": {
        "Position": {"Alpha": 0.3, "Color": "204; 51; 204", "Scale": 2, "Value": True},
        "Value": False,
    },
    "Keep": 50,
    "Position Tolerance": 0.1,
    "Shape": {
        "Alpha": 1,
        "Axes Length": 1,
        "Axes Radius": 0.1,
        "Color": "0; 25; 255",
        "Head Length": 0.3,
        "Head Radius": 0.1,
        "Shaft Length": 1,
        "Shaft Radius": 0.05,
        "Value": "Axes",
    },
    "Topic": {
        "Depth": 5,
        "Durability Policy": "Volatile",
        "History Policy": "Keep Last",
        "Reliability Policy": "Reliable",
        "Value": "/odom",
    },
}


def test_odometry_reads_and_writes_rviz2_nested_properties() -> None:
    from robomodel.viewer.displays.rviz_io import display_entry, display_values
    from robomodel.viewer.rviz_model import RvizDialect, RvizDisplay, freeze

    cls = display_class("Odometry")
    values, skipped = display_values(cls, ODOMETRY_ROS2, RvizDialect.ROS2)
    assert skipped == []
    assert values["Shape/Value"] == "Axes" and values["Shape/Color"] == "0; 25; 255"
    assert values["Covariance/Value"] is False and values["Covariance/Position/Scale"] == 2
    assert values["Keep"] == 50 and values["Topic"] == "/odom"
    display, scene = start("Odometry", **values)
    display.receive(odom(1.0))
    display.draw(lookup_from({"odom": np.eye(4)}))
    (node,) = scene.visible().values()
    assert node.kind == "batched_axes"  # Shape: Axes from the file
    base = RvizDisplay("rviz_default_plugins/Odometry", "d", True, freeze(ODOMETRY_ROS2))
    entry = display_entry(display, RvizDialect.ROS2, base)
    assert entry.settings["Shape"]["Value"] == "Axes"
    assert entry.settings["Covariance"]["Position"]["Scale"] == 2
    fresh = display_entry(display_class("Odometry")("o", display.context), RvizDialect.ROS2)
    assert fresh.settings["Shape"]["Value"] == "Arrow" and fresh.settings["Shape"]["Color"] == "255; 25; 0"  # fmt: skip
    assert fresh.settings["Covariance"]["Value"] is True


def test_wrench_is_rviz_1_s_wrench_stamped() -> None:
    from robomodel.viewer.displays import UnknownDisplayError

    assert display_class("rviz/WrenchStamped") is display_class("rviz_default_plugins/Wrench")
    with pytest.raises(UnknownDisplayError):
        display_class("rviz_default_plugins/WrenchStamped")  # RViz 2 has no such class


def test_odometry_keeps_a_bounded_trail_over_thirty_minutes_of_driving() -> None:
    """Seed 002's step 8 for 30 minutes at 1 m/s on a 5 m circle, odometry at 10 Hz, drawn
    once a (simulated) second: RViz's Keep (100) arrows are all that
    stays; the covariance shapes go with their arrows, and the messages waiting for a draw
    are bounded too."""
    from robomodel.viewer.limits import MAX_ODOMETRY_PENDING

    display, scene = start("Odometry", **{"Covariance/Value": False})  # Keep 100
    lookup = lookup_from({"odom": np.eye(4)})
    rate_hz, radius_m, speed_mps = 10, 5.0, 1.0

    def drive(step: int) -> object:
        angle = speed_mps * step / rate_hz / radius_m
        msg = odom(0.0, yaw=angle + math.pi / 2)
        msg.pose.pose.position.x, msg.pose.pose.position.y = radius_m * math.cos(angle), radius_m * math.sin(angle)  # fmt: skip
        msg.pose.covariance = [0.001 if i in (0, 7, 35) else 0.0 for i in range(36)]
        return msg

    for step in range(30 * 60 * rate_hz):
        display.receive(drive(step))
        if step % rate_hz == 0:
            display.draw(lookup)
    display.draw(lookup)
    assert len(display.trail.poses) == 100
    assert list(scene.nodes) == ["/displays/d/arrows"]
    assert scene.nodes["/displays/d/arrows"].kwargs["points"].shape == (100, 2, 3)
    covariance, scene = start("Odometry", Keep=10)  # shown: RViz's default
    for step in range(50):
        covariance.receive(drive(step))
        covariance.draw(lookup)
    shapes = [n for n in scene.nodes if "covariance" in n]
    assert len(covariance.trail.poses) == 10 and 10 <= len(shapes) <= 4 * 10
    for _ in range(3 * MAX_ODOMETRY_PENDING):  # a burst between two draws keeps the newest
        display.receive(odom(7.0))
    assert len(display._pending) == MAX_ODOMETRY_PENDING
