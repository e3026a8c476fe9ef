"""Simulated cameras: the simplebot's depth camera sees wall.world's wall where its
geometry puts it, CameraInfo's K, every topic at the update rate (other forms:
test_camera_forms.py)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from robomodel.loading import load
from robomodel.runtime import Context, ManualClock
from robomodel.runtime.msg.schema import get_message_type
from robomodel.sim import Placement, Simulation, read_world
from robomodel.sim.bus import SimBridge
from robomodel.sim.sensors.camera import CameraSensor

from .conftest import SIMPLEBOT_CAMERA, WALL_WORLD

IMAGE = get_message_type("sensor_msgs/msg/Image")
INFO = get_message_type("sensor_msgs/msg/CameraInfo")
CLOUD = get_message_type("sensor_msgs/msg/PointCloud2")
# the example's plugin (ROS 1, libgazebo_ros_openni_kinect.so) names its topics so
TOPICS = {
    "/camera/rgb/image_raw": IMAGE,
    "/camera/rgb/camera_info": INFO,
    "/camera/depth/image_raw": IMAGE,
    "/camera/depth/camera_info": INFO,
    "/camera/depth/points": CLOUD,
}


def _rpy_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    cr, sr, cp, sp, cy, sy = (f(a) for a in (roll, pitch, yaw) for f in (math.cos, math.sin))
    return np.array([
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ])  # fmt: skip


class Scene:
    """The simplebot with its camera in front of wall.world's wall, on a ROS 1 bus."""

    def __init__(self) -> None:
        self.robot = load(str(SIMPLEBOT_CAMERA))
        self.sim = Simulation(read_world(WALL_WORLD))
        self.sim.add_robot(self.robot, placement=Placement(xyz_m=(0.0, 0.0, 0.076)))
        self.context = Context(clock=ManualClock())
        self.bridge = SimBridge(self.sim, self.context, ros_version=1)
        self.got: dict[str, list[Any]] = {topic: [] for topic in TOPICS}
        node = self.context.create_node("test")
        for topic, msg_type in TOPICS.items():
            node.create_subscription(msg_type, topic, self.got[topic].append)
        (self.camera,) = [s for s in self.bridge.sensors if isinstance(s, CameraSensor)]

    def wait_for(self, count: int) -> None:
        """Step until every topic has ``count`` messages (sim time: no wall clock)."""
        while min(len(v) for v in self.got.values()) < count:
            assert self.sim.time_s < 10.0, {t: len(v) for t, v in self.got.items()}
            self.sim.step(10)
            self.context.advance(0.0)

    def optical_pose(self) -> tuple[np.ndarray, np.ndarray]:
        """World position and rotation of camera_optical_link: the sensor's site (camera_link,
        pose 0) composed with the URDF's optical joint."""
        d, site = self.sim.data, self.camera.site
        joint = {j.name: j for j in self.robot.joints}["camera_optical_joint"]
        rotation = d.site_xmat[site].reshape(3, 3) @ _rpy_matrix(*joint.origin.rpy_rad)
        return d.site_xpos[site].copy(), rotation


@pytest.fixture(scope="module")
def scene() -> Scene:
    s = Scene()
    s.sim.step(300)  # settle on the wheels
    s.wait_for(2)
    return s


def _wall_pixels(s: Scene, f: float, w: int, h: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(surely wall, surely sky, depth [m]) per pixel from the wall's box and the camera pose:
    a pixel is sure when it and its 8 neighbours agree (the edges may go either way)."""
    (wall,) = [shape for shape in s.sim.world.shapes if shape.model == "wall"]
    x, y, z = wall.pose[:3]
    sx, sy, sz = wall.size
    face = x - sx / 2  # the near face, toward the robot at the origin
    origin, rotation = s.optical_pose()
    u, v = np.meshgrid(np.arange(-1, w + 1), np.arange(-1, h + 1))
    rays = np.stack([(u - (w - 1) / 2) / f, (v - (h - 1) / 2) / f, np.ones_like(u, float)], -1)
    world = rays @ rotation.T  # optical z = 1: the ray parameter is the z depth
    t = (face - origin[0]) / world[..., 0]
    hit = origin + t[..., None] * world
    on = (t > 0) & (np.abs(hit[..., 1] - y) <= sy / 2) & (np.abs(hit[..., 2] - z) <= sz / 2)
    sky = ~on & (world[..., 2] > 0)

    def sure(mask: np.ndarray) -> np.ndarray:
        out = np.ones((h, w), bool)
        for du in (0, 1, 2):
            for dv in (0, 1, 2):
                out &= mask[dv : dv + h, du : du + w]
        return out

    return sure(on), sure(sky), t[1:-1, 1:-1]


def test_camera_info_k_matches_the_fov_and_the_image_size(scene: Scene) -> None:
    info = scene.got["/camera/rgb/camera_info"][-1]
    hfov, w, h = 1.3962634, 320, 240  # the example's <horizontal_fov> and <image>
    f = w / (2 * math.tan(hfov / 2))
    assert (info.width, info.height, info.distortion_model) == (w, h, "plumb_bob")
    assert list(info.k) == pytest.approx([f, 0, (w + 1) / 2, 0, f, (h + 1) / 2, 0, 0, 1])
    assert list(info.p) == pytest.approx([f, 0, (w + 1) / 2, 0, 0, f, (h + 1) / 2, 0, 0, 0, 1, 0])
    assert info.header.frame_id == "camera_optical_link"
    assert scene.got["/camera/depth/camera_info"][-1].k == info.k


def test_the_wall_is_where_its_geometry_puts_it_in_the_image(scene: Scene) -> None:
    image = scene.got["/camera/rgb/image_raw"][-1]
    info = scene.got["/camera/rgb/camera_info"][-1]
    assert (image.encoding, image.step, image.header.frame_id) == (
        "rgb8",
        3 * image.width,
        "camera_optical_link",
    )
    rgb = np.frombuffer(image.data, np.uint8).reshape(image.height, image.width, 3)
    wall, sky, _ = _wall_pixels(scene, info.k[0], image.width, image.height)
    assert wall.sum() > 0.3 * wall.size and sky.sum() > 0.05 * sky.size  # both in view
    assert (rgb[sky] == 0).all()  # MuJoCo's empty background
    assert (rgb[wall].max(axis=1) > 40).all()  # the lit wall


def test_depth_image_and_cloud_lie_on_the_wall_within_1_cm(scene: Scene) -> None:
    depth_msg = scene.got["/camera/depth/image_raw"][-1]
    cloud = scene.got["/camera/depth/points"][-1]
    f = scene.got["/camera/depth/camera_info"][-1].k[0]
    assert depth_msg.encoding == "32FC1" and cloud.header.frame_id == "camera_optical_link"
    w, h = depth_msg.width, depth_msg.height
    depth = np.frombuffer(depth_msg.data, "<f4").reshape(h, w)
    wall, sky, expected = _wall_pixels(scene, f, w, h)
    assert np.abs(depth[wall] - expected[wall]).max() < 0.01
    assert np.isnan(depth[sky]).all()  # ROS 1: beyond pointCloudCutoffMax is NaN
    assert (cloud.width, cloud.height, cloud.point_step, cloud.row_step) == (w, h, 32, 32 * w)
    assert [(p.name, p.offset, p.datatype) for p in cloud.fields] == [
        ("x", 0, 7), ("y", 4, 7), ("z", 8, 7), ("rgb", 16, 7)]  # fmt: skip
    raw = np.frombuffer(cloud.data, np.uint8).reshape(h, w, 32)
    xyz = raw[..., :12].copy().view("<f4").reshape(h, w, 3).astype(float)
    origin, rotation = scene.optical_pose()
    points = origin + xyz @ rotation.T
    (wall_shape,) = [s for s in scene.sim.world.shapes if s.model == "wall"]
    face = wall_shape.pose[0] - wall_shape.size[0] / 2
    assert np.abs(points[wall][:, 0] - face).max() < 0.01
    above_floor = np.isfinite(points[..., 2]) & (points[..., 2] > 0.02)
    assert above_floor.sum() >= wall.sum()  # every point off the floor is on the wall
    assert np.abs(points[above_floor][:, 0] - face).max() < 0.01
    assert not cloud.is_dense  # the sky's points are NaN


def test_every_topic_publishes_at_the_update_rate_in_sim_time(scene: Scene) -> None:
    before = {topic: len(v) for topic, v in scene.got.items()}
    scene.wait_for(max(before.values()) + 5)
    stamps = [m.header.stamp.to_seconds() for m in scene.got["/camera/rgb/image_raw"]]
    assert np.diff(stamps[-5:]) == pytest.approx([0.1] * 4, abs=1e-6)  # <update_rate> 10
    for topic in TOPICS:
        assert [m.header.stamp.to_seconds() for m in scene.got[topic][-5:]] == stamps[-5:]
