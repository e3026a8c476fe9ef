"""Camera and depth sensors rendered with MuJoCo's offscreen renderer (headless: see ``_gl``).

Frames, as gazebo_ros: Gazebo's camera looks along the sensor's +x with +z up (the MuJoCo camera
added for it looks there); the messages carry ``frame_name`` as given, while the image, the
depth image and the cloud are in the optical convention (x right, y down, z forward), so
``frame_name`` should name an optical frame (``rpy="-pi/2 0 -pi/2"`` from the camera link), as
with Gazebo. Depths are along the optical axis (z), as Gazebo's depth camera gives them.

A frame is rendered once per update and every message of the sensor is built from it: the image
(and, for a depth sensor, the 32FC1 depth image and the ``xyz`` + ``rgb`` PointCloud2, point
step 32 as ``PointCloud2Modifier::setPointCloud2FieldsByString(2, "xyz", "rgb")``, the colour
bytes copied from the image in its own order as gazebo_ros does) and the CameraInfo (plumb_bob,
no distortion, ``K`` from the focal length ``width / (2 tan(hfov / 2))`` and the centre
``((width + 1) / 2, (height + 1) / 2)``). A gaussian ``<noise>`` is Gazebo's: one sample per
pixel and frame, added to each of its channels in [0, 1]. Not modelled: lens distortion, depth
noise, and the clip planes for the colour image (the depth image and the cloud honour them).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from robomodel.runtime.msg.schema import Message, get_message_type
from robomodel.sim._mujoco import mujoco
from robomodel.sim.sensors._gl import check_rendering, gl_context
from robomodel.sim.sensors.base import SimSensor
from robomodel.sim.sensors.camera_spec import CameraSpec, CameraTopics
from robomodel.sim.sensors.spec import SensorSpec

__all__ = ["CameraSensor", "Frame", "add_mujoco_camera"]

# Gazebo camera (x forward, z up) -> MuJoCo camera (looks along -z, y up, x right): columns are
# the MuJoCo camera's axes in the sensor frame.
_GAZEBO_TO_MUJOCO = np.array([[0.0, 0.0, -1.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
_SHADOW_MAP_PX = 1024
_FLOAT32 = 7  # sensor_msgs/PointField FLOAT32
_CLOUD = np.dtype({"names": ["x", "y", "z", "rgb"], "formats": ["<f4", "<f4", "<f4", ("u1", 3)],
                   "offsets": [0, 4, 8, 16], "itemsize": 32})  # fmt: skip


def add_mujoco_camera(spec: Any, body: Any, name: str, sensor: SensorSpec) -> None:
    """Add the MuJoCo camera of ``sensor`` to ``body`` (named ``name``, at the sensor's pose,
    looking along its +x) and grow the offscreen buffer to its image."""
    from robomodel.description.rigid import quat_wxyz_from_rpy

    mj = mujoco()
    camera = sensor.camera or CameraSpec()
    x, y, z, r, p, yaw = sensor.pose
    fix = np.zeros(4)
    mj.mju_mat2Quat(fix, _GAZEBO_TO_MUJOCO.ravel())
    quat = np.zeros(4)
    mj.mju_mulQuat(quat, np.asarray(quat_wxyz_from_rpy(r, p, yaw), dtype=float), fix)
    body.add_camera(name=name, pos=[x, y, z], quat=list(quat),
                    fovy=math.degrees(camera.vertical_fov_rad))  # fmt: skip
    offscreen = spec.visual.global_
    offscreen.offwidth = max(offscreen.offwidth, camera.width_px)
    offscreen.offheight = max(offscreen.offheight, camera.height_px)
    # software GL (llvmpipe) is the usual renderer here: MuJoCo's 4096 px shadow map and 4x
    # multisampling make a 320 x 240 frame ~6x slower (120 ms vs 20 ms) for softer edges
    spec.visual.quality.shadowsize = _SHADOW_MAP_PX
    spec.visual.quality.offsamples = 0


@dataclass(frozen=True, slots=True)
class Frame:
    """One rendered frame: ``rgb`` (rows top to bottom) and ``depth_m`` (z depth; +inf where
    nothing is within the clip planes, -inf nearer than the near plane), at ``time_s``."""

    time_s: float
    rgb: np.ndarray
    depth_m: np.ndarray | None


class CameraSensor(SimSensor):
    """A ``camera`` or ``depth`` sensor; :meth:`render` then the message builders."""

    def __init__(
        self,
        spec: SensorSpec,
        model: Any,
        data: Any,
        *,
        prefix: str = "",
        seed: int = 0,
        site: str = "",
        topics: CameraTopics | None = None,
    ) -> None:
        super().__init__(spec, model, data, prefix=prefix, seed=seed, site=site)
        self.camera: CameraSpec = spec.camera or CameraSpec()
        self.topics = topics
        self.camera_id = int(model.camera(self.site_name).id)
        self.image_type = get_message_type("sensor_msgs/msg/Image")
        self.info_type = get_message_type("sensor_msgs/msg/CameraInfo")
        self.cloud_type = get_message_type("sensor_msgs/msg/PointCloud2")
        self.field_type = get_message_type("sensor_msgs/msg/PointField")
        self.message_type = self.image_type
        self._gl: Any = None
        check_rendering()

    def _open(self) -> None:
        """The GL context, MuJoCo's scene and render context (on first use, on the thread
        that renders: a GL context is current on one thread)."""
        mj = mujoco()
        cam = self.camera
        self._gl = gl_context(cam.width_px, cam.height_px)
        self._scene = mj.MjvScene(self.model, maxgeom=10_000)
        self._context = mj.MjrContext(self.model, mj.mjtFontScale.mjFONTSCALE_100)
        mj.mjr_setBuffer(mj.mjtFramebuffer.mjFB_OFFSCREEN, self._context)
        self._view = mj.MjvCamera()
        self._view.type = mj.mjtCamera.mjCAMERA_FIXED
        self._view.fixedcamid = self.camera_id
        self._option = mj.MjvOption()
        # a robot built without visual geoms (group 1) is seen by its collision geoms (group 3)
        if not (self.model.geom_group == 1).any():
            self._option.geomgroup[:] = [1, 0, 0, 1, 0, 0]
        self._viewport = mj.MjrRect(0, 0, cam.width_px, cam.height_px)
        self._rgb = np.empty((cam.height_px, cam.width_px, 3), dtype=np.uint8)
        self._zbuffer = np.empty((cam.height_px, cam.width_px), dtype=np.float32)

    def render(self, time_s: float) -> Frame:
        """Render the current state (the depth too for a depth sensor)."""
        mj = mujoco()
        if self._gl is None:
            self._open()
        else:
            self._gl.make_current()
        mj.mjv_updateScene(self.model, self.data, self._option, None, self._view,
                           mj.mjtCatBit.mjCAT_ALL, self._scene)  # fmt: skip
        mj.mjr_render(self._viewport, self._scene, self._context)
        depth = self._zbuffer if self.camera.depth else None
        mj.mjr_readPixels(self._rgb, depth, self._viewport, self._context)
        rgb = self._rgb[::-1]  # OpenGL's rows are bottom to top
        if self.camera.noise_stddev > 0 or self.camera.noise_mean != 0:
            rgb = self._noisy(rgb)
        return Frame(time_s, rgb, self._depth_m() if self.camera.depth else None)

    def _noisy(self, rgb: np.ndarray) -> np.ndarray:
        """Gazebo's camera noise (see the module docstring), in 8-bit steps, clamped."""
        cam = self.camera
        h, w = rgb.shape[:2]
        noise = self.rng.normal(cam.noise_mean * 255.0, cam.noise_stddev * 255.0, (h, w, 1))
        noisy: np.ndarray = np.clip(rgb + noise, 0, 255).round().astype(np.uint8)
        return noisy

    def _depth_m(self) -> np.ndarray:
        """Linear z depth from the depth buffer (MuJoCo's near and far planes), clipped to the
        sensor's ``<clip>``."""
        m = self.model
        near = m.vis.map.znear * m.stat.extent
        far = m.vis.map.zfar * m.stat.extent
        z = self._zbuffer[::-1].astype(np.float64)
        with np.errstate(divide="ignore"):
            depth: np.ndarray = near / (1.0 - z * (1.0 - near / far))
        depth[(z >= 1.0) | (depth >= self.camera.far_m)] = math.inf
        depth[depth < self.camera.near_m] = -math.inf
        return depth

    def measure(self, time_s: float) -> Message:
        return self.image(self.render(time_s))

    def close(self) -> None:
        """Free the GL resources (the context of a finished simulation)."""
        if self._gl is not None:
            self._gl.make_current()
            self._context.free()
            self._gl.free()
            self._gl = None

    # -- messages ------------------------------------------------------------------------------
    def pixels(self, frame: Frame) -> np.ndarray:
        """The frame in the sensor's encoding (h x w x channels, contiguous)."""
        encoding = self.camera.encoding
        if encoding == "bgr8":
            return np.ascontiguousarray(frame.rgb[..., ::-1])
        if encoding == "mono8":  # ITU-R 601 luma
            luma: np.ndarray = frame.rgb @ np.array([0.299, 0.587, 0.114])
            mono: np.ndarray = luma.round().astype(np.uint8)[..., None]
            return mono
        return np.ascontiguousarray(frame.rgb)

    def image(self, frame: Frame) -> Message:
        """``sensor_msgs/Image`` in the sensor's encoding."""
        pixels = self.pixels(frame)
        h, w, channels = pixels.shape
        built: Any = self.image_type
        message: Message = built(
            header=self.header(frame.time_s), height=h, width=w, encoding=self.camera.encoding,
            is_bigendian=0, step=channels * w, data=pixels.tobytes(),
        )  # fmt: skip
        return message

    def camera_info(self, time_s: float) -> Message:
        """``sensor_msgs/CameraInfo`` as gazebo_ros fills it (see the module docstring)."""
        cam = self.camera
        f = float(cam.param("focalLength", "focal_length", default="0") or 0) or cam.focal_px
        cx = float(cam.param("Cx", "cx", default=str((cam.width_px + 1) / 2)))
        cy = float(cam.param("Cy", "cy", default=str((cam.height_px + 1) / 2)))
        cx_prime = float(cam.param("CxPrime", default=str(cx)))
        baseline = float(cam.param("hackBaseline", "hack_baseline", default="0"))
        built: Any = self.info_type
        message: Message = built(
            header=self.header(time_s), height=cam.height_px, width=cam.width_px,
            distortion_model="plumb_bob", d=[0.0] * 5,
            k=[f, 0.0, cx, 0.0, f, cy, 0.0, 0.0, 1.0],
            r=[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
            p=[f, 0.0, cx_prime, -f * baseline, 0.0, f, cy, 0.0, 0.0, 0.0, 1.0, 0.0],
        )  # fmt: skip
        return message

    def _ranged(self, depth_m: np.ndarray) -> np.ndarray:
        """The plugin's range: ROS 1 NaN outside the cutoffs, ROS 2 -inf / +inf."""
        topics = self.topics or CameraTopics("", "")
        lo, hi = topics.min_depth_m, topics.max_depth_m
        out: np.ndarray = depth_m.copy()
        near, far = depth_m <= lo, ~(depth_m < hi) & ~(depth_m <= lo)
        if topics.out_of_range_nan:
            out[near | far] = math.nan
        else:
            out[near], out[far] = -math.inf, math.inf
        return out

    def depth_image(self, frame: Frame) -> Message:
        """The 32FC1 depth image [m]."""
        depth = self._ranged(frame.depth_m if frame.depth_m is not None else np.zeros((0, 0)))
        h, w = depth.shape
        built: Any = self.image_type
        message: Message = built(
            header=self.header(frame.time_s), height=h, width=w, encoding="32FC1",
            is_bigendian=0, step=4 * w, data=depth.astype("<f4").tobytes(),
        )  # fmt: skip
        return message

    def points(self, frame: Frame) -> Message:
        """The organised ``xyz`` + ``rgb`` cloud in the optical convention."""
        depth = self._ranged(frame.depth_m if frame.depth_m is not None else np.zeros((0, 0)))
        h, w = depth.shape
        f = self.camera.focal_px
        cloud = np.zeros((h, w), dtype=_CLOUD)
        finite = np.isfinite(depth)
        u = (np.arange(w) - 0.5 * (w - 1)) / f  # tan of gazebo_ros's yAngle
        v = (np.arange(h) - 0.5 * (h - 1)) / f  # tan of its pAngle
        with np.errstate(invalid="ignore"):
            cloud["x"] = np.where(finite, depth * u[None, :], depth)
            cloud["y"] = np.where(finite, depth * v[:, None], depth)
        cloud["z"] = depth
        cloud["rgb"] = self.pixels(frame)  # the image's bytes as they are (mono: repeated)
        field: Any = self.field_type
        fields = [field(name=n, offset=o, datatype=_FLOAT32, count=1)
                  for n, o in (("x", 0), ("y", 4), ("z", 8), ("rgb", 16))]  # fmt: skip
        built: Any = self.cloud_type
        message: Message = built(
            header=self.header(frame.time_s), height=h, width=w, fields=fields,
            is_bigendian=False, point_step=32, row_step=32 * w, data=cloud.tobytes(),
            is_dense=bool(finite.all()),
        )  # fmt: skip
        return message
