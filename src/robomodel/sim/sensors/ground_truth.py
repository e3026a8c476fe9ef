"""Ground truth of a robot's root link as ``nav_msgs/Odometry`` in the ``world`` frame
(what Gazebo's ``libgazebo_ros_p3d.so`` publishes): pose and twist (linear in the world,
angular in the world) of the root body."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from robomodel.runtime.msg.types.builtin_interfaces import Time
from robomodel.runtime.msg.types.geometry_msgs import (
    Point,
    Pose,
    PoseWithCovariance,
    Quaternion,
    Transform,
    TransformStamped,
    Twist,
    TwistWithCovariance,
    Vector3,
)
from robomodel.runtime.msg.types.nav_msgs import Odometry
from robomodel.runtime.msg.types.std_msgs import Header
from robomodel.runtime.msg.types.tf2_msgs import TFMessage
from robomodel.sim._mujoco import mujoco

__all__ = ["GroundTruth", "yaw_of"]


def yaw_of(quat_wxyz: np.ndarray) -> float:
    """Heading [rad] of a ``wxyz`` quaternion (rotation about world z)."""
    w, x, y, z = (float(v) for v in quat_wxyz)
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


class GroundTruth:
    """The true pose of body ``body_name`` (child frame ``child_frame``)."""

    def __init__(self, model: Any, data: Any, body_name: str, child_frame: str) -> None:
        self.model = model
        self.data = data
        self.body = int(model.body(body_name).id)
        self.child_frame = child_frame
        self._velocity = np.zeros(6)  # mj_objectVelocity's output: [angular, linear]
        self._body_type = int(mujoco().mjtObj.mjOBJ_BODY)

    def xy_yaw(self) -> tuple[float, float, float]:
        p = self.data.xpos[self.body]
        return float(p[0]), float(p[1]), yaw_of(self.data.xquat[self.body])

    def transform(self, time_s: float, child_frame: str) -> TFMessage:
        """The same pose as TF ``world -> child_frame`` (for drawing the true pose)."""
        px, py, pz = self.data.xpos[self.body].tolist()
        qw, qx, qy, qz = self.data.xquat[self.body].tolist()
        return TFMessage(
            [
                TransformStamped(
                    header=Header(stamp=Time.from_seconds(time_s), frame_id="world"),
                    child_frame_id=child_frame,
                    transform=Transform(
                        translation=Vector3(px, py, pz),
                        rotation=Quaternion(x=qx, y=qy, z=qz, w=qw),
                    ),
                )
            ]
        )

    def measure(self, time_s: float) -> Odometry:
        d = self.data
        px, py, pz = d.xpos[self.body].tolist()
        qw, qx, qy, qz = d.xquat[self.body].tolist()
        vel = self._velocity
        mujoco().mj_objectVelocity(self.model, d, self._body_type, self.body, vel, 0)
        wx, wy, wz, vx, vy, vz = vel.tolist()
        return Odometry(
            header=Header(stamp=Time.from_seconds(time_s), frame_id="world"),
            child_frame_id=self.child_frame,
            pose=PoseWithCovariance(
                pose=Pose(
                    position=Point(px, py, pz), orientation=Quaternion(x=qx, y=qy, z=qz, w=qw)
                )
            ),
            twist=TwistWithCovariance(
                twist=Twist(linear=Vector3(vx, vy, vz), angular=Vector3(wx, wy, wz))
            ),
        )
