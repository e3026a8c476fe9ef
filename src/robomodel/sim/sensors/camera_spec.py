"""Camera and depth sensors read from SDF (sdformat camera.sdf) and their gazebo_ros plugin.

SDF defaults: ``horizontal_fov`` 1.047 rad, ``image`` 320 x 240 ``R8G8B8``, ``clip`` 0.1..100 m.
The topics are the gazebo_ros plugin's, in the form of the plugin's ROS version
(:func:`camera_topics`), transcribed from ros-simulation/gazebo_ros_pkgs:

- ROS 1 (noetic-devel f9e1a46, ``gazebo_plugins/src/gazebo_ros_camera_utils.cpp``): a node handle
  ``<robotNamespace>/<cameraName>`` (``cameraName`` empty by default) publishing
  ``imageTopicName`` (``image_raw``) and ``cameraInfoTopicName`` (``camera_info``). The depth
  plugins (``gazebo_ros_openni_kinect.cpp``, ``gazebo_ros_depth_camera.cpp``) default these to
  ``ir/image_raw`` and ``ir/camera_info`` and add ``depthImageTopicName``
  (``depth/image_raw``), ``depthImageCameraInfoTopicName`` (``depth/camera_info``) and
  ``pointCloudTopicName`` (``points``), with depths outside ``pointCloudCutoff`` (0.4 m) ..
  ``pointCloudCutoffMax`` (5 m) as NaN.
- ROS 2 (ros2 d52f7c4, ``gazebo_plugins/src/gazebo_ros_camera.cpp``): ``camera_name`` (the
  sensor's name by default) ``/image_raw``, ``/camera_info``, and for a depth sensor
  ``/depth/image_raw``, ``/depth/camera_info``, ``/points``, under ``<ros><namespace>``, each
  renamed by a ``<ros><remapping>FROM:=TO`` whose FROM is that relative name; depths at or
  below ``min_depth`` (0.4 m) are -inf, at or beyond ``max_depth`` (inf) +inf.

The frame is ``frameName`` (ROS 1) or ``frame_name`` (ROS 2), else the sensor's link (ROS 2's
``gazebo_ros::SensorFrameID``; ROS 1 would say ``/world``, which no TF tree has).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from lxml import etree

from robomodel.sim.exceptions import SimulationError

__all__ = [
    "MAX_CAMERA_SIDE_PX",
    "MAX_SENSOR_RATE_HZ",
    "CameraSpec",
    "CameraTopics",
    "camera_topics",
    "parse_camera",
]

# An image side MuJoCo's offscreen framebuffer takes on any GL (GL_MAX_RENDERBUFFER_SIZE is at
# least 4096 on the GPUs and software renderers MuJoCo runs on); 100000 x 100000 ended the
# simulator in mujoco.FatalError "Offscreen framebuffer is not complete".
MAX_CAMERA_SIDE_PX = 4096
MAX_SENSOR_RATE_HZ = 1000.0  # <update_rate>: one image per physics step of 1 ms at most

# Gazebo image formats and the sensor_msgs encodings gazebo_ros gives them (ROS 1 and ROS 2
# alike); bayer and 16-bit formats are not rendered.
_FORMATS = {"R8G8B8": "rgb8", "RGB_INT8": "rgb8", "B8G8R8": "bgr8", "BGR_INT8": "bgr8",
            "L8": "mono8", "L_INT8": "mono8"}  # fmt: skip

# Plugin tags only the ROS 1 plugins read (their ROS 2 counterparts are snake_case).
_ROS1_TAGS = ("robotNamespace", "cameraName", "frameName", "imageTopicName",
              "cameraInfoTopicName", "depthImageTopicName", "depthImageCameraInfoTopicName",
              "pointCloudTopicName", "pointCloudCutoff", "pointCloudCutoffMax", "updateRate")  # fmt: skip
_ROS1_ONLY_PLUGINS = ("libgazebo_ros_openni_kinect.so", "libgazebo_ros_depth_camera.so")


@dataclass(frozen=True, slots=True)
class CameraSpec:
    """``<camera>`` with the plugin's settings (what the messages need).

    Attributes:
        noise_mean: Gaussian ``<noise>`` of the colour image (and ``noise_stddev``), in [0, 1]
            of a channel; 0 for none.
        plugin: The plugin's child elements as (tag, text), ``ros/namespace`` and
            ``ros/remapping`` included (a remapping may repeat).
        ros_version: The plugin's form: 1 (camelCase tags or a ROS 1-only plugin), 2 (a ``<ros>``
            block or snake_case tags), 0 when nothing tells (the bus's version decides).
    """

    horizontal_fov_rad: float = 1.047
    width_px: int = 320
    height_px: int = 240
    encoding: str = "rgb8"
    near_m: float = 0.1
    far_m: float = 100.0
    depth: bool = False
    noise_mean: float = 0.0
    noise_stddev: float = 0.0
    plugin: tuple[tuple[str, str], ...] = ()
    ros_version: int = 0

    @property
    def focal_px(self) -> float:
        """``width / (2 tan(hfov / 2))``, as gazebo_ros computes the focal length."""
        return self.width_px / (2.0 * math.tan(self.horizontal_fov_rad / 2.0))

    @property
    def vertical_fov_rad(self) -> float:
        """The vertical field of view of square pixels (what MuJoCo's ``fovy`` takes)."""
        return 2.0 * math.atan(self.height_px / (2.0 * self.focal_px))

    def param(self, *names: str, default: str = "") -> str:
        """The first of the plugin's ``names`` that is set, else ``default``."""
        for name in names:
            for tag, text in self.plugin:
                if tag == name and text:
                    return text
        return default


@dataclass(frozen=True, slots=True)
class CameraTopics:
    """The resolved topics of one camera (empty for what it does not publish)."""

    image: str
    camera_info: str
    depth_image: str = ""
    depth_camera_info: str = ""
    points: str = ""
    min_depth_m: float = 0.0
    max_depth_m: float = math.inf
    out_of_range_nan: bool = False  # ROS 1: NaN; ROS 2: -inf / +inf


def _number(text: str | None, default: float, tag: str, where: str) -> float:
    if text is None or not text.strip():
        return default
    try:
        return float(text)
    except ValueError:
        raise SimulationError(f"<{tag}> must be a number, got {text!r}", where=where) from None


def _plugin(el: etree._Element) -> tuple[tuple[tuple[str, str], ...], int]:
    plugin = el.find("plugin")
    if plugin is None:
        return (), 0
    items: list[tuple[str, str]] = []
    for child in plugin:
        if not isinstance(child.tag, str):
            continue
        if child.tag == "ros":
            for sub in child:
                if isinstance(sub.tag, str):
                    items.append((f"ros/{sub.tag}", (sub.text or "").strip()))
        else:
            items.append((child.tag, (child.text or "").strip()))
    tags = {tag for tag, _ in items}
    filename = (plugin.get("filename") or "").rsplit("/", 1)[-1]
    if filename in _ROS1_ONLY_PLUGINS or tags & set(_ROS1_TAGS):
        version = 1
    elif any(tag.startswith("ros/") or "_" in tag for tag in tags):
        version = 2
    else:
        version = 0
    return tuple(items), version


def parse_camera(el: etree._Element, name: str, depth: bool, where: str) -> CameraSpec:
    """The :class:`CameraSpec` of ``<sensor type="camera|depth">`` ``el``."""
    cam = el.find("camera")
    if cam is None:
        cam = etree.Element("camera")
    fmt = (cam.findtext("image/format") or "R8G8B8").strip()
    encoding = _FORMATS.get(fmt)
    if encoding is None:
        raise SimulationError(
            f"sensor '{name}': <image><format> {fmt!r} is not rendered "
            f"(valid: {', '.join(sorted(_FORMATS))})",
            where=where,
        )
    plugin, version = _plugin(el)
    noise = cam.find("noise")
    gaussian = noise is not None and (noise.findtext("type") or "").strip() == "gaussian"
    spec = CameraSpec(
        horizontal_fov_rad=_number(cam.findtext("horizontal_fov"), 1.047, "horizontal_fov", where),
        width_px=int(_number(cam.findtext("image/width"), 320, "width", where)),
        height_px=int(_number(cam.findtext("image/height"), 240, "height", where)),
        encoding=encoding,
        near_m=_number(cam.findtext("clip/near"), 0.1, "near", where),
        far_m=_number(cam.findtext("clip/far"), 100.0, "far", where),
        depth=depth,
        noise_mean=_number(cam.findtext("noise/mean"), 0.0, "mean", where) if gaussian else 0.0,
        noise_stddev=_number(cam.findtext("noise/stddev"), 0.0, "stddev", where)
        if gaussian
        else 0.0,
        plugin=plugin,
        ros_version=version,
    )
    if spec.width_px <= 0 or spec.height_px <= 0 or not 0 < spec.horizontal_fov_rad < math.pi:
        raise SimulationError(
            f"sensor '{name}': the image must be at least 1 x 1 pixels and <horizontal_fov> "
            f"within (0, pi) rad, got {spec.width_px} x {spec.height_px}, "
            f"{spec.horizontal_fov_rad} rad",
            where=where,
            name=name,
        )
    if max(spec.width_px, spec.height_px) > MAX_CAMERA_SIDE_PX:
        raise SimulationError(
            f"sensor '{name}': the image is {spec.width_px} x {spec.height_px} pixels; "
            f"<image><width> and <height> must be 1..{MAX_CAMERA_SIDE_PX}",
            where=where,
            name=name,
        )
    rate_hz = _number(el.findtext("update_rate"), 0.0, "update_rate", where)
    if not 0.0 <= rate_hz <= MAX_SENSOR_RATE_HZ:
        raise SimulationError(
            f"sensor '{name}': <update_rate> {rate_hz:g} Hz is outside 0..{MAX_SENSOR_RATE_HZ:g} "
            "Hz (0: every physics step)",
            where=where,
            name=name,
        )
    if not 0 < spec.near_m < spec.far_m:
        raise SimulationError(
            f"sensor '{name}': <clip> needs 0 < near < far, got {spec.near_m}, {spec.far_m}",
            where=where,
        )
    return spec


def _join(*parts: str) -> str:
    """ROS name resolution of ``parts`` (a part that starts with / restarts from the root)."""
    out = ""
    for part in parts:
        if not part:
            continue
        out = part if part.startswith("/") else f"{out.rstrip('/')}/{part}"
    return "/" + out.strip("/")


def camera_topics(spec: CameraSpec, sensor: str, ros_version: int) -> CameraTopics:
    """The topics of camera ``sensor`` (see the module docstring); ``ros_version`` is the
    bus's, used when the plugin's own form does not tell."""
    if (spec.ros_version or ros_version) == 1:
        return _ros1_topics(spec)
    return _ros2_topics(spec, sensor)


def _ros1_topics(spec: CameraSpec) -> CameraTopics:
    base = _join(spec.param("robotNamespace"), spec.param("cameraName"))
    ir = "ir/" if spec.depth else ""
    topics = CameraTopics(
        image=_join(base, spec.param("imageTopicName", default=f"{ir}image_raw")),
        camera_info=_join(base, spec.param("cameraInfoTopicName", default=f"{ir}camera_info")),
    )
    if not spec.depth:
        return topics
    return CameraTopics(
        image=topics.image,
        camera_info=topics.camera_info,
        depth_image=_join(base, spec.param("depthImageTopicName", default="depth/image_raw")),
        depth_camera_info=_join(
            base, spec.param("depthImageCameraInfoTopicName", default="depth/camera_info")
        ),
        points=_join(base, spec.param("pointCloudTopicName", default="points")),
        min_depth_m=_number(spec.param("pointCloudCutoff"), 0.4, "pointCloudCutoff", ""),
        max_depth_m=_number(spec.param("pointCloudCutoffMax"), 5.0, "pointCloudCutoffMax", ""),
        out_of_range_nan=True,
    )


def _ros2_topics(spec: CameraSpec, sensor: str) -> CameraTopics:
    namespace = spec.param("ros/namespace")
    camera = spec.param("camera_name", default=sensor)
    remaps = [
        tuple(part.strip() for part in text.split(":=", 1))
        for tag, text in spec.plugin
        if tag == "ros/remapping" and ":=" in text
    ]

    def topic(relative: str) -> str:
        name = f"{camera}/{relative}"
        for source, target in remaps:
            if source in (name, f"~/{name}", _join(namespace, name)):
                name = target
        return _join(namespace, name)

    if not spec.depth:
        return CameraTopics(image=topic("image_raw"), camera_info=topic("camera_info"))
    return CameraTopics(
        image=topic("image_raw"),
        camera_info=topic("camera_info"),
        depth_image=topic("depth/image_raw"),
        depth_camera_info=topic("depth/camera_info"),
        points=topic("points"),
        min_depth_m=_number(spec.param("min_depth"), 0.4, "min_depth", ""),
        max_depth_m=_number(spec.param("max_depth"), math.inf, "max_depth", ""),
    )
