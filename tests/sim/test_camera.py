"""Simulated cameras (issue 31): the simplebot's depth camera sees wall.world's wall where its
geometry puts it; CameraInfo, topic names of gazebo_ros's ROS 1 and ROS 2 plugins, rate."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from lxml import etree

from robomodel.loading import load
from robomodel.runtime import Context, ManualClock
from robomodel.runtime.msg._schema import get_message_type
from robomodel.sim import Placement, Simulation, read_world
from robomodel.sim.bus import SimBridge
from robomodel.sim.sensors import _gl
from robomodel.sim.sensors.camera import CameraSensor
from robomodel.sim.sensors.camera_spec import camera_topics, parse_camera

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


def _sensor(xml: str) -> etree._Element:
    return etree.fromstring(xml)


def test_topic_names_of_the_ros2_plugin_with_namespace_and_remappings() -> None:
    # gazebo_plugins/worlds/gazebo_ros_depth_camera_demo.world (ros2 d52f7c4), its sensor
    depth = _sensor("""<sensor type="depth" name="camera1"><camera/>
      <plugin name="camera_controller" filename="libgazebo_ros_camera.so">
        <ros><namespace>demo_cam</namespace>
          <remapping>mycamera/image_raw:=mycamera/image_demo</remapping>
          <remapping>mycamera/depth/image_raw:=mycamera/depth_demo</remapping>
          <remapping>mycamera/camera_info:=mycamera/raw_cam_info_demo</remapping>
          <remapping>mycamera/depth/camera_info:=mycamera/depth_cam_info_demo</remapping>
          <remapping>mycamera/points:=mycamera/points_demo</remapping></ros>
        <camera_name>mycamera</camera_name></plugin></sensor>""")
    t = camera_topics(parse_camera(depth, "camera1", True, "x"), "camera1", ros_version=1)
    assert (t.image, t.depth_image, t.camera_info, t.depth_camera_info, t.points) == (
        "/demo_cam/mycamera/image_demo", "/demo_cam/mycamera/depth_demo",
        "/demo_cam/mycamera/raw_cam_info_demo", "/demo_cam/mycamera/depth_cam_info_demo",
        "/demo_cam/mycamera/points_demo")  # fmt: skip
    assert (t.min_depth_m, t.max_depth_m, t.out_of_range_nan) == (0.4, math.inf, False)
    # gazebo_ros_camera_demo.world: a bare "image_raw" remapping does not match the topic
    # camera1/image_raw (its comment says to view /demo_cam/camera1/image_raw)
    camera = _sensor("""<sensor type="camera" name="camera1"><camera/>
      <plugin name="camera_controller" filename="libgazebo_ros_camera.so">
        <ros><namespace>demo_cam</namespace><remapping>image_raw:=image_demo</remapping></ros>
      </plugin></sensor>""")
    t = camera_topics(parse_camera(camera, "camera1", False, "x"), "camera1", ros_version=2)
    assert (t.image, t.camera_info, t.points) == (
        "/demo_cam/camera1/image_raw",
        "/demo_cam/camera1/camera_info",
        "",
    )


def test_topic_names_of_the_ros1_plugins() -> None:
    # gazebo_plugins/test/camera/depth_camera.world (noetic-devel f9e1a46)
    depth = _sensor("""<sensor type="depth" name="camera1"><camera/>
      <plugin name="camera_controller" filename="libgazebo_ros_depth_camera.so">
        <cameraName>camera1</cameraName><imageTopicName>image_raw</imageTopicName>
        <depthImageTopicName>depth/image_raw</depthImageTopicName>
        <pointCloudTopicName>points</pointCloudTopicName><frameName>camera_link</frameName>
        <pointCloudCutoff>0.001</pointCloudCutoff></plugin></sensor>""")
    t = camera_topics(parse_camera(depth, "camera1", True, "x"), "camera1", ros_version=2)
    assert (t.image, t.camera_info, t.depth_image, t.depth_camera_info, t.points) == (
        "/camera1/image_raw", "/camera1/ir/camera_info", "/camera1/depth/image_raw",
        "/camera1/depth/camera_info", "/camera1/points")  # fmt: skip
    assert (t.min_depth_m, t.max_depth_m, t.out_of_range_nan) == (0.001, 5.0, True)
    bare = _sensor("""<sensor type="camera" name="cam"><camera/>
      <plugin name="p" filename="libgazebo_ros_camera.so"/></sensor>""")
    spec = parse_camera(bare, "cam", False, "x")
    # nothing says which plugin: the bus's version decides (ROS 1's cameraName is empty)
    assert camera_topics(spec, "cam", ros_version=1).image == "/image_raw"
    assert camera_topics(spec, "cam", ros_version=2).image == "/cam/image_raw"
    ns = _sensor("""<sensor type="camera" name="cam"><camera/><plugin name="p"
      filename="libgazebo_ros_camera.so"><robotNamespace>/r1</robotNamespace>
      <cameraName>front</cameraName><imageTopicName>/abs/image</imageTopicName></plugin></sensor>""")
    t = camera_topics(parse_camera(ns, "cam", False, "x"), "cam", ros_version=2)
    assert (t.image, t.camera_info) == ("/abs/image", "/r1/front/camera_info")


def test_an_unrendered_image_format_is_one_error_line() -> None:
    from robomodel.sim.exceptions import SimulationError

    el = _sensor("""<sensor type="camera" name="cam"><camera><image><format>BAYER_RGGB8</format>
      </image></camera></sensor>""")
    with pytest.raises(SimulationError, match=r"f.urdf:3: sensor 'cam'.*BAYER_RGGB8.*valid: "):
        parse_camera(el, "cam", False, "f.urdf:3")


def test_no_offscreen_opengl_names_the_debian_packages(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(_gl, "_chosen", None)
    monkeypatch.delenv("MUJOCO_GL", raising=False)
    monkeypatch.setattr(_gl.ctypes.util, "find_library", lambda name: None)
    with pytest.raises(_gl.RenderingUnavailableError) as err:
        _gl.gl_context(4, 4)
    message = str(err.value)
    assert "\n" not in message
    assert "egl: libEGL not found; osmesa: libOSMesa not found" in message
    assert "libegl1 libegl-mesa0 or libosmesa6" in message


BOX = """<robot name="box">
  <link name="base">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <gazebo reference="base">
    <sensor type="depth" name="cam"><update_rate>20</update_rate><pose>0.1 0 0.4 0 0 0</pose>
      <camera><horizontal_fov>1.2</horizontal_fov><image><width>64</width><height>48</height>
        <format>B8G8R8</format></image><clip><near>0.05</near><far>10</far></clip></camera>
      <plugin name="p" filename="libgazebo_ros_camera.so"><ros><namespace>robot</namespace>
        <remapping>cam/points:=cam/cloud</remapping></ros>
        <frame_name>cam_optical</frame_name><max_depth>2.0</max_depth></plugin>
    </sensor>
  </gazebo>
</robot>"""


def test_a_ros2_depth_camera_on_the_bus_with_its_range_as_inf() -> None:
    from robomodel.description.urdf.reader import read_urdf

    sim = Simulation(read_world(WALL_WORLD))
    sim.add_robot(read_urdf(BOX.encode()).robot, placement=Placement(xyz_m=(0.0, 0.0, 0.1)))
    context = Context(clock=ManualClock())
    SimBridge(sim, context, ros_version=2)
    topics = {"/robot/cam/image_raw": IMAGE, "/robot/cam/camera_info": INFO,
              "/robot/cam/depth/image_raw": IMAGE, "/robot/cam/depth/camera_info": INFO,
              "/robot/cam/cloud": CLOUD}  # fmt: skip
    got: dict[str, list[Any]] = {topic: [] for topic in topics}
    node = context.create_node("test")
    for topic, msg_type in topics.items():
        node.create_subscription(msg_type, topic, got[topic].append)
    while min(len(v) for v in got.values()) < 2:
        assert sim.time_s < 5.0, {t: len(v) for t, v in got.items()}
        sim.step(10)
        context.advance(0.0)
    image = got["/robot/cam/image_raw"][-1]
    assert (image.encoding, image.width, image.height, image.step) == ("bgr8", 64, 48, 192)
    depth_msg = got["/robot/cam/depth/image_raw"][-1]
    depth = np.frombuffer(depth_msg.data, "<f4").reshape(48, 64)
    # the wall's face is 2.1 m ahead, beyond max_depth 2.0: +inf as ROS 2's plugin; the floor
    # near the bottom rows is nearer
    assert depth[24, 32] == math.inf and np.isfinite(depth[-1]).all()
    assert depth_msg.header.frame_id == "cam_optical"
    cloud = got["/robot/cam/cloud"][-1]
    xyz = np.frombuffer(cloud.data, np.uint8).reshape(48, 64, 32)[..., :12].copy().view("<f4")
    assert (xyz[24, 32] == math.inf).all() and not cloud.is_dense
    bgr = np.frombuffer(image.data, np.uint8).reshape(48, 64, 3)
    rgb_bytes = np.frombuffer(cloud.data, np.uint8).reshape(48, 64, 32)[..., 16:19]
    assert (rgb_bytes == bgr).all()  # the image's bytes, in its own order, as gazebo_ros


def test_camera_info_crosses_the_ros1_wire_with_k() -> None:
    from robomodel.runtime.transport.ros1.ros1_types import ros1_type

    wire = ros1_type(INFO)
    assert wire.md5sum == "c9a58c1b0b154e0e6da7578cb991d214"  # Debian's sensor_msgs/CameraInfo
    info: Any = INFO
    sent = info(height=2, width=3, d=[0.1] * 5, k=[float(i) for i in range(9)],
                r=[1.0] * 9, p=[2.0] * 12)  # fmt: skip
    back: Any = wire.decode(wire.encode(sent))
    assert (list(back.d), list(back.k), list(back.p)) == (list(sent.d), list(sent.k), [2.0] * 12)


FALLBACK = """
from robomodel.sim.sensors import _gl
from robomodel.sim.sensors.camera import CameraSensor
from tests.sim.test_camera import Scene
scene = Scene()
scene.wait_for(1)
print(_gl._chosen, scene.got["/camera/rgb/image_raw"][-1].width)
"""


def test_without_a_working_egl_osmesa_renders() -> None:
    import os
    import subprocess
    import sys

    from .conftest import EXAMPLES

    env = dict(os.environ, __EGL_VENDOR_LIBRARY_FILENAMES="/nonexistent.json")  # glvnd: no EGL
    env.pop("MUJOCO_GL", None)
    env.pop("PYOPENGL_PLATFORM", None)
    run = subprocess.run([sys.executable, "-c", FALLBACK], env=env, capture_output=True,
                         text=True, cwd=EXAMPLES.parent, check=False)  # fmt: skip
    assert run.returncode == 0, run.stderr
    assert run.stdout.split() == ["osmesa", "320"]
    assert "Exception ignored" not in run.stderr  # contexts freed before PyOpenGL goes


# gazebo_plugins/worlds/gazebo_ros_camera_demo.world (ros2 d52f7c4): its camera_model as
# written, comments dropped; a wall 2.2 m behind it (the camera looks along -x, yaw 3.14)
DEMO_WORLD = """<sdf version="1.6"><world name="default">
  <include><uri>model://sun</uri></include>
  <model name="wall"><static>true</static><pose>-2.25 0 0.5 0 0 0</pose>
    <link name="link"><collision name="c"><geometry><box><size>0.1 4 1</size></box></geometry>
    </collision></link></model>
  <model name="camera_model">
    <pose>0 0 0.5 0 0 3.14</pose>
    <static>true</static>
    <link name="camera_link">
      <sensor type="camera" name="camera1">
        <update_rate>60</update_rate>
        <visualize>true</visualize>
        <camera name="head">
          <horizontal_fov>1.3962634</horizontal_fov>
          <image><width>640</width><height>480</height><format>R8G8B8</format></image>
          <clip><near>0.02</near><far>300</far></clip>
          <noise><type>gaussian</type><mean>0.0</mean><stddev>0.007</stddev></noise>
        </camera>
        <plugin name="camera_controller" filename="libgazebo_ros_camera.so">
          <ros>
            <namespace>demo_cam</namespace>
            <remapping>image_raw:=image_demo</remapping>
            <remapping>camera_info:=camera_info_demo</remapping>
          </ros>
        </plugin>
      </sensor>
    </link>
  </model>
</world></sdf>"""


def test_a_camera_of_an_sdf_world_model_publishes_what_the_wall_looks_like() -> None:
    from robomodel.sim import parse_world

    sim = Simulation(parse_world(DEMO_WORLD))
    context = Context(clock=ManualClock())
    SimBridge(sim, context, ros_version=2)
    images: list[Any] = []
    infos: list[Any] = []
    node = context.create_node("test")
    node.create_subscription(IMAGE, "/demo_cam/camera1/image_raw", images.append)
    node.create_subscription(INFO, "/demo_cam/camera1/camera_info", infos.append)
    while not images or not infos:
        assert sim.time_s < 5.0, "no image within 5 s of sim time"
        sim.step(10)
        context.advance(0.0)
    image = images[-1]
    assert (image.width, image.height, image.header.frame_id) == (640, 480, "camera_link")
    rgb = np.frombuffer(image.data, np.uint8).reshape(480, 640, 3)
    f = infos[-1].k[0]
    # the wall's top edge (z 1 m) seen from 0.5 m up, 2.2 m away: the row (h - 1) / 2 - f 0.5 / 2.2
    top = (480 - 1) / 2 - f * (1.0 - 0.5) / 2.2
    bottom = (480 - 1) / 2 + f * 0.5 / 2.2  # and its foot (z 0; no ground plane in this world)
    rows = np.arange(480)
    assert (rgb[rows < top - 1.5] == 0).all()
    lit = rgb[(rows > top + 1.5) & (rows < bottom - 1.5)].max(axis=2)
    assert (lit > 40).all()
    assert (rgb[rows > bottom + 1.5] == 0).all()
