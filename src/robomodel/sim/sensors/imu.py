"""IMU (sdf imu.sdf): orientation in the world, angular velocity and proper acceleration in the
sensor frame (at rest it reads +9.81 m/s^2 up, as Gazebo's and MuJoCo's accelerometers)."""

from __future__ import annotations

import numpy as np

from robomodel.runtime.msg.schema import Message
from robomodel.runtime.msg.types.geometry_msgs import Quaternion, Vector3
from robomodel.runtime.msg.types.sensor_msgs import Imu
from robomodel.sim._mujoco import mujoco
from robomodel.sim.sensors.base import SimSensor

__all__ = ["ImuSensor"]


class ImuSensor(SimSensor):
    message_type = Imu

    def measure(self, time_s: float) -> Message:
        mj = mujoco()
        m, d = self.model, self.data
        mj.mj_rnePostConstraint(m, d)  # fills cacc (includes gravity, as an accelerometer)
        vel = np.zeros(6)
        acc = np.zeros(6)
        mj.mj_objectVelocity(m, d, mj.mjtObj.mjOBJ_SITE, self.site, vel, 1)
        mj.mj_objectAcceleration(m, d, mj.mjtObj.mjOBJ_SITE, self.site, acc, 1)
        quat = np.zeros(4)
        mj.mju_mat2Quat(quat, d.site_xmat[self.site])
        gyro = vel[:3]
        noise = self.spec.noise
        if noise.active:
            gyro = gyro + self.rng.normal(noise.mean, noise.stddev, 3)
        w, x, y, z = (float(v) for v in quat)
        return Imu(
            header=self.header(time_s),
            orientation=Quaternion(x=x, y=y, z=z, w=w),
            angular_velocity=Vector3(*(float(v) for v in gyro)),
            linear_acceleration=Vector3(*(float(v) for v in acc[3:])),
        )
