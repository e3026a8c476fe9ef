"""Simulated cameras, their forms: the topic names of gazebo_ros's ROS 1 and ROS 2
plugins, a ROS 2 depth camera on the bus, CameraInfo on the ROS 1 wire, the OpenGL choice, a
camera of an SDF world model."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from lxml import etree

from robomodel.runtime import Context, ManualClock
from robomodel.runtime.msg.schema import get_message_type
from robomodel.sim import Placement, Simulation, read_world
from robomodel.sim.bus import SimBridge
from robomodel.sim.sensors import _gl
from robomodel.sim.sensors.camera_spec import camera_topics, parse_camera

from .conftest import WALL_WORLD

IMAGE = get_message_type("sensor_msgs/msg/Image")
INFO = get_message_type("sensor_msgs/msg/CameraInfo")
CLOUD = get_message_type("sensor_msgs/msg/PointCloud2")


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
    while len(images) < 2 or not infos:
        assert sim.time_s < 5.0, "no images within 5 s of sim time"
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
    wall = (rows > top + 1.5) & (rows < bottom - 1.5)
    empty = (rows < top - 1.5) | (rows > bottom + 1.5)
    stddev = 0.007 * 255  # the demo's <noise>, in 8-bit steps
    assert (rgb[empty] < 7 * stddev).all() and rgb[empty].mean() < stddev  # black, noisy
    assert (rgb[wall].max(axis=2) > 40).all()
    # Gazebo's noise: one sample per pixel and frame, the same on its three channels
    before = np.frombuffer(images[-2].data, np.uint8).reshape(480, 640, 3)
    change = rgb[wall].astype(int) - before[wall]
    assert (change[..., 0] == change[..., 1]).all() and (change[..., 1] == change[..., 2]).all()
    assert change[..., 0].std() == pytest.approx(math.sqrt(2) * stddev, rel=0.1)


def test_robomodel_sim_without_the_asked_opengl_is_one_error_line_and_exit_2() -> None:
    import os
    import subprocess

    from tests.conftest import ROBOMODEL

    from .conftest import SIMPLEBOT_CAMERA

    env = dict(os.environ, MUJOCO_GL="egl", __EGL_VENDOR_LIBRARY_FILENAMES="/nonexistent.json")
    run = subprocess.run(
        [*ROBOMODEL, "sim", str(SIMPLEBOT_CAMERA), "--world", str(WALL_WORLD), "--headless",
         "--rate", "max", "--duration", "0.5", "--bus", "inproc"],
        env=env, capture_output=True, text=True, check=False,
    )  # fmt: skip
    assert run.returncode == 2, run.stderr
    errors = [line for line in run.stderr.splitlines() if "error" in line]
    assert len(errors) == 1 and "Traceback" not in run.stderr
    assert "egl: " in errors[0] and "install Debian's libegl1 libegl-mesa0" in errors[0]


@pytest.mark.parametrize(
    ("image", "rate", "said"),
    [
        ("<width>100000</width><height>100000</height>", "10",
         r"the image is 100000 x 100000 pixels; <image><width> and <height> must be 1\.\.4096"),
        ("<width>4097</width><height>1</height>", "10", r"the image is 4097 x 1 pixels"),
        ("<width>320</width><height>240</height>", "1e9",
         r"<update_rate> 1e\+09 Hz is outside 0\.\.1000 Hz"),
        ("<width>320</width><height>240</height>", "-5", r"<update_rate> -5 Hz is outside"),
    ],
)  # fmt: skip
def test_a_camera_outside_its_bounds_is_refused_at_load(image: str, rate: str, said: str) -> None:
    from robomodel.sim.exceptions import SimulationError

    el = _sensor(f"""<sensor type="camera" name="cam"><update_rate>{rate}</update_rate>
      <camera><image>{image}</image></camera></sensor>""")
    with pytest.raises(SimulationError, match=rf"^robot.urdf:7: sensor 'cam': {said}") as caught:
        parse_camera(el, "cam", False, "robot.urdf:7")
    assert caught.value.name == "cam"
    edge = _sensor("""<sensor type="camera" name="cam"><update_rate>1000</update_rate>
      <camera><image><width>4096</width><height>1</height></image></camera></sensor>""")
    assert parse_camera(edge, "cam", False, "x").width_px == 4096


def test_robomodel_sim_refuses_a_huge_camera_with_one_line_naming_the_sensor(
    tmp_path: Any,
) -> None:
    import shutil
    import subprocess

    from tests.conftest import ROBOMODEL

    from .conftest import SIMPLEBOT_CAMERA

    package = tmp_path / "simplebot_description"
    shutil.copytree(SIMPLEBOT_CAMERA.parents[1], package)
    robot = package / "urdf" / SIMPLEBOT_CAMERA.name
    text = robot.read_text()
    assert "<width>320</width>" in text
    robot.write_text(text.replace("<width>320</width>", "<width>100000</width>").replace(
        "<height>240</height>", "<height>100000</height>"))  # fmt: skip
    run = subprocess.run(
        [*ROBOMODEL, "sim", str(robot), "--headless", "--rate", "max", "--duration", "0.5",
         "--bus", "inproc"],
        capture_output=True, text=True, check=False,
    )  # fmt: skip
    assert run.returncode == 2, run.stderr
    assert "Traceback" not in run.stderr and "FatalError" not in run.stderr
    [line] = [x for x in run.stderr.splitlines() if "error" in x]
    assert line.startswith(f"robomodel: error: {robot} (expanded):")  # the line of its <sensor>
    assert "sensor 'camera': the image is 100000 x 100000 pixels" in line
