"""Sensor descriptions read from SDF ``<sensor>`` elements (sdformat sensor.sdf, ray.sdf, imu.sdf).

Defaults are SDF's: ``update_rate`` 0 (every physics step), ray ``samples`` 640,
``resolution`` 1, angles 0, ``range`` 0..0; noise ``none``. The topic is the plugin's
(``topicName`` in ROS 1, the ``~/out`` remapping in ROS 2) or, failing that, ``/<sensor name>``.
"""

from __future__ import annotations

import enum
import math
import warnings
from dataclasses import dataclass, replace

from lxml import etree

from robomodel.sim.exceptions import SimulationError
from robomodel.sim.sensors.camera_spec import CameraSpec, parse_camera

__all__ = ["Noise", "RaySpec", "SensorKind", "SensorSpec", "parse_sensor"]


class SensorKind(enum.Enum):
    RAY = "ray"  # ray, gpu_ray, lidar, gpu_lidar
    SONAR = "sonar"
    IMU = "imu"
    CONTACT = "contact"
    CAMERA = "camera"
    DEPTH = "depth"  # depth, depth_camera, rgbd_camera: an image, a depth image and a cloud


_KINDS = {
    "ray": SensorKind.RAY,
    "gpu_ray": SensorKind.RAY,
    "lidar": SensorKind.RAY,
    "gpu_lidar": SensorKind.RAY,
    "sonar": SensorKind.SONAR,
    "imu": SensorKind.IMU,
    "contact": SensorKind.CONTACT,
    "camera": SensorKind.CAMERA,
    "depth": SensorKind.DEPTH,
    "depth_camera": SensorKind.DEPTH,
    "rgbd_camera": SensorKind.DEPTH,
}


@dataclass(frozen=True, slots=True)
class Noise:
    """SDF ``<noise>``: gaussian with ``mean`` and ``stddev`` (``none`` has both 0)."""

    mean: float = 0.0
    stddev: float = 0.0

    @property
    def active(self) -> bool:
        return self.mean != 0.0 or self.stddev != 0.0


@dataclass(frozen=True, slots=True)
class RaySpec:
    """``<ray>`` / ``<lidar>`` horizontal scan and range (or a sonar's cone)."""

    samples: int = 640
    resolution: float = 1.0
    min_angle_rad: float = 0.0
    max_angle_rad: float = 0.0
    range_min_m: float = 0.0
    range_max_m: float = 0.0
    noise: Noise = Noise()
    output: str = "LaserScan"

    @property
    def count(self) -> int:
        return max(1, round(self.samples * self.resolution))

    @property
    def angle_increment_rad(self) -> float:
        """(max - min) / (samples * resolution - 1), as Gazebo's ``GetAngleResolution``."""
        n = self.count
        return (self.max_angle_rad - self.min_angle_rad) / (n - 1) if n > 1 else 0.0


@dataclass(frozen=True, slots=True)
class SensorSpec:
    """One ``<sensor>`` attached to a link.

    Attributes:
        pose: ``<pose>`` as (x, y, z, roll, pitch, yaw) [m, rad] in the link frame.
        frame: The ``frame_id`` of the messages (plugin ``frameName``/``frame_name`` or the link).
        collision: For a contact sensor, the collision name it watches (unused: the whole link).
        camera: For a camera or depth sensor, its image and plugin (topics are resolved by
            :func:`~robomodel.sim.sensors.camera_spec.camera_topics`, not ``topic``).
    """

    name: str
    kind: SensorKind
    link: str
    update_rate_hz: float = 0.0
    topic: str = ""
    frame: str = ""
    pose: tuple[float, float, float, float, float, float] = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    ray: RaySpec | None = None
    noise: Noise = Noise()
    camera: CameraSpec | None = None
    where: str = ""


def _num(el: etree._Element | None, default: float, where: str) -> float:
    if el is None or el.text is None or not el.text.strip():
        return default
    try:
        return float(el.text.strip())
    except ValueError:
        raise SimulationError(
            f"<{el.tag}> must be a number, got {el.text!r}", where=where
        ) from None


def _noise(el: etree._Element | None, where: str) -> Noise:
    if el is None:
        return Noise()
    kind = (el.findtext("type") or el.get("type") or "none").strip()
    if kind == "none":
        return Noise()
    return Noise(_num(el.find("mean"), 0.0, where), _num(el.find("stddev"), 0.0, where))


def _ray(el: etree._Element, where: str) -> RaySpec:
    ray = el.find("ray")
    if ray is None:
        ray = el.find("lidar")
    if ray is None:
        return RaySpec()
    h = ray.find("scan/horizontal")
    rng = ray.find("range")
    return RaySpec(
        samples=int(_num(h.find("samples") if h is not None else None, 640, where)),
        resolution=_num(h.find("resolution") if h is not None else None, 1.0, where),
        min_angle_rad=_num(h.find("min_angle") if h is not None else None, 0.0, where),
        max_angle_rad=_num(h.find("max_angle") if h is not None else None, 0.0, where),
        range_min_m=_num(rng.find("min") if rng is not None else None, 0.0, where),
        range_max_m=_num(rng.find("max") if rng is not None else None, 0.0, where),
        noise=_noise(ray.find("noise"), where),
    )


def _sonar(el: etree._Element, where: str) -> RaySpec:
    sonar = el.find("sonar")
    lo = _num(sonar.find("min") if sonar is not None else None, 0.0, where)
    hi = _num(sonar.find("max") if sonar is not None else None, 1.0, where)
    radius = _num(sonar.find("radius") if sonar is not None else None, 0.5, where)
    half = math.atan2(radius, hi) if hi > 0 else 0.0
    return RaySpec(5, 1.0, -half, half, lo, hi, output="Range")


def _plugin_topic(el: etree._Element) -> tuple[str, str, str]:
    """(topic, frame, output type) from the sensor's ROS plugin, if any."""
    plugin = el.find("plugin")
    if plugin is None:
        return "", "", ""
    topic = (plugin.findtext("topicName") or "").strip()
    for remap in plugin.iterfind("ros/remapping"):
        text = (remap.text or "").strip()
        if text.startswith("~/out:="):
            topic = text.split(":=", 1)[1]
    ns = (plugin.findtext("ros/namespace") or "").strip().rstrip("/")
    if topic and not topic.startswith("/"):
        topic = f"{ns}/{topic}" if ns else f"/{topic}"
    frame = (plugin.findtext("frameName") or plugin.findtext("frame_name") or "").strip()
    output = (plugin.findtext("output_type") or "").strip().rsplit("/", 1)[-1]
    return topic, frame, output


def parse_sensor(el: etree._Element, link: str, where: str) -> SensorSpec | None:
    """A :class:`SensorSpec` for ``el``, or ``None`` (with a warning) for unknown types."""
    name = el.get("name") or f"{link}_sensor"
    type_name = (el.get("type") or "").strip()
    kind = _KINDS.get(type_name)
    if kind is None:
        warnings.warn(
            f"{where}: sensor '{name}' has type '{type_name}', which the simulator does not "
            f"support ({', '.join(sorted(_KINDS))}); skipped",
            stacklevel=3,
        )
        return None
    pose_text = (el.findtext("pose") or "").split()
    try:
        pose = tuple(float(v) for v in pose_text) if pose_text else (0.0,) * 6
    except ValueError:
        raise SimulationError(f"sensor '{name}': <pose> must be 6 numbers", where=where) from None
    if len(pose) != 6:
        raise SimulationError(f"sensor '{name}': <pose> must be 6 numbers", where=where)
    topic, frame, output = _plugin_topic(el)
    topic = topic or (el.findtext("topic") or "").strip() or f"/{name}"
    if not topic.startswith("/"):
        topic = "/" + topic
    ray: RaySpec | None = None
    noise = Noise()
    camera: CameraSpec | None = None
    if kind in (SensorKind.CAMERA, SensorKind.DEPTH):
        camera = parse_camera(el, name, kind is SensorKind.DEPTH, where)
    elif kind is SensorKind.RAY:
        ray = _ray(el, where)
        if output in ("Range",):
            ray = replace(ray, output="Range")
        if ray.range_max_m <= 0:
            raise SimulationError(
                f"sensor '{name}': <range><max> must be positive, got {ray.range_max_m}",
                where=where,
            )
    elif kind is SensorKind.SONAR:
        ray = _sonar(el, where)
    elif kind is SensorKind.IMU:
        noise = _noise(el.find("imu/angular_velocity/x/noise"), where)
    return SensorSpec(
        name=name,
        kind=kind,
        link=link,
        update_rate_hz=_num(el.find("update_rate"), 0.0, where),
        topic=topic,
        frame=frame or link,
        pose=pose,
        ray=ray,
        noise=noise,
        camera=camera,
        where=where,
    )
