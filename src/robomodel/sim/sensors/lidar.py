"""Ray sensors (``ray``/``gpu_ray``/``lidar`` and ``sonar``) with ``mj_multiRay``.

Rays start at the sensor's site and cover the SDF horizontal scan (angle increment as Gazebo's
``GetAngleResolution``). They hit collision geoms of the world and of every robot except the
sensor's own link; visual geoms (group 1) are skipped. Ranges follow REP-117 as gz-sim and
ros_gz do: no return within ``range.max`` is ``+inf``, a return closer than ``range.min`` is
``-inf``. Gaussian ``<noise>`` is added to valid returns.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from robomodel.runtime.msg.schema import Message
from robomodel.runtime.msg.types.sensor_msgs import LaserScan
from robomodel.sim._mujoco import mujoco
from robomodel.sim.sensors.base import SimSensor
from robomodel.sim.sensors.msgs import range_type
from robomodel.sim.sensors.spec import RaySpec, SensorSpec

__all__ = ["Lidar"]

# Geom groups the rays see: all but 1 (visual geoms).
_GROUPS = np.array([1, 0, 1, 1, 1, 1], dtype=np.uint8)


class Lidar(SimSensor):
    """A planar lidar (LaserScan) or a sonar cone (Range: the nearest of its rays)."""

    message_type: type[Message] = LaserScan

    def __init__(
        self,
        spec: SensorSpec,
        model: Any,
        data: Any,
        *,
        prefix: str = "",
        seed: int = 0,
        site: str = "",
    ) -> None:
        super().__init__(spec, model, data, prefix=prefix, seed=seed, site=site)
        self.ray: RaySpec = spec.ray or RaySpec()
        n = self.ray.count
        self.angles = self.ray.min_angle_rad + self.ray.angle_increment_rad * np.arange(n)
        self._local = np.stack([np.cos(self.angles), np.sin(self.angles), np.zeros(n)], axis=1)
        self._geomid = np.zeros(n, dtype=np.int32)
        self._dist = np.zeros(n, dtype=float)
        self._sonar = self.ray.output == "Range"
        if self._sonar:
            self.message_type = range_type()

    def ranges(self) -> np.ndarray:
        """The current scan [m], REP-117 (see the module docstring)."""
        mj = mujoco()
        d = self.data
        origin = d.site_xpos[self.site]
        R = d.site_xmat[self.site].reshape(3, 3)
        vec = np.ascontiguousarray(self._local @ R.T).ravel()
        ray = self.ray
        n = len(self.angles)
        mj.mj_multiRay(
            self.model, d, origin, vec, _GROUPS, 1, self.body,
            self._geomid, self._dist, None, n, ray.range_max_m,
        )  # fmt: skip
        r: np.ndarray = self._dist.copy()
        miss = (self._geomid < 0) | (r > ray.range_max_m)
        if ray.noise.active:
            r += self.rng.normal(ray.noise.mean, ray.noise.stddev, n)
        r[miss] = math.inf
        r[~miss & (r < ray.range_min_m)] = -math.inf
        return r

    def measure(self, time_s: float) -> Message:
        ray = self.ray
        ranges = self.ranges()
        if self._sonar:
            finite = ranges[np.isfinite(ranges)]
            value = float(finite.min()) if len(finite) else math.inf
            built: Any = self.message_type  # a class built from its definition
            sonar: Message = built(
                header=self.header(time_s),
                field_of_view=ray.max_angle_rad - ray.min_angle_rad,
                min_range=ray.range_min_m,
                max_range=ray.range_max_m,
                range=value,
            )
            return sonar
        rate = self.spec.update_rate_hz
        return LaserScan(
            header=self.header(time_s),
            angle_min=ray.min_angle_rad,
            angle_max=float(self.angles[-1]),
            angle_increment=ray.angle_increment_rad,
            scan_time=1.0 / rate if rate > 0 else 0.0,
            range_min=ray.range_min_m,
            range_max=ray.range_max_m,
            ranges=ranges.tolist(),
        )
